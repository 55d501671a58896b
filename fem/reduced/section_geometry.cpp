#include "fem/reduced/section_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include "fem/core/angles.hpp"

namespace softarm::fem::section_geometry {
namespace {

Interval hull(Interval a, const Interval& b) {
  if (b.lo > b.hi) return a;
  if (a.lo > a.hi) return b;
  return {std::min(a.lo, b.lo), std::max(a.hi, b.hi)};
}
}  // namespace

double Interval::overlap(double a, double b) const {
  const double l = std::max(lo, a), h = std::min(hi, b);
  return h > l ? h - l : 0.0;
}

Interval disc_chord(double cx, double cy, double r, double y) {
  const double d = y - cy;
  if (std::abs(d) >= r) return {};
  const double h = std::sqrt(r * r - d * d);
  return {cx - h, cx + h};
}

Interval polygon_chord(const std::vector<Point>& p, double y) {
  Interval out{1e300, -1e300};
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto& a = p[i];
    const auto& b = p[(i + 1) % p.size()];
    if ((a[1] - y) * (b[1] - y) > 0 || a[1] == b[1]) continue;
    const double x = a[0] + (b[0] - a[0]) * (y - a[1]) / (b[1] - a[1]);
    out.lo = std::min(out.lo, x);
    out.hi = std::max(out.hi, x);
  }
  return out.lo <= out.hi ? out : Interval{};
}

// F(y) = r² asin(y/r) + y √(r² − y²) is ∫ 2√(r² − t²) dt. Exact strips keep the section a
// smooth function of the geometry (a sampled chord is not, near the circle's top and bottom),
// so finite-difference gradients of the rod's results are clean down to small steps.
double disc_strip_area(double cy, double r, double a, double b) {
  if (r <= 0) return 0.0;
  const auto f = [r](double y) {
    const double t = std::clamp(y, -r, r);
    return r * r * std::asin(t / r) + t * std::sqrt(std::max(0.0, r * r - t * t));
  };
  return f(b - cy) - f(a - cy);
}

// The union of the triangle, a rectangle on each edge and a disc on each vertex.
Interval envelope_chord(const std::array<Point, 3>& v, double rho, double y) {
  Interval out = polygon_chord({v[0], v[1], v[2]}, y);
  for (int i = 0; i < 3; ++i) {
    const auto& a = v[i];
    const auto& b = v[(i + 1) % 3];
    out = hull(out, disc_chord(a[0], a[1], rho, y));
    const double ex = b[0] - a[0], ey = b[1] - a[1], len = std::hypot(ex, ey);
    const double nx = ey / len * rho, ny = -ex / len * rho;  // outward for counter-clockwise vertices
    out = hull(out, polygon_chord({a, b, {b[0] + nx, b[1] + ny}, {a[0] + nx, a[1] + ny}}, y));
  }
  return out;
}

std::array<Point, 3> tca_axes(const TcaDesign& design, double z, double frame_angle_rad) {
  const double a_c = design.axis_distance(z);
  std::array<Point, 3> axes;
  for (int k = 0; k < 3; ++k) {
    const double phi = k * 2 * kPi / 3 - frame_angle_rad;
    axes[k] = {a_c * std::cos(phi), a_c * std::sin(phi)};
  }
  return axes;
}

std::array<Point, 3> counter_clockwise(std::array<Point, 3> v) {
  const double cross = (v[1][0] - v[0][0]) * (v[2][1] - v[0][1]) - (v[1][1] - v[0][1]) * (v[2][0] - v[0][0]);
  if (cross < 0) std::swap(v[1], v[2]);
  return v;
}

}  // namespace softarm::fem::section_geometry

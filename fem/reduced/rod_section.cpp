#include "fem/reduced/rod_section.hpp"

#include <algorithm>
#include <cmath>

namespace softarm::fem {
namespace {
constexpr double kPi = 3.14159265358979323846;

struct Interval {
  double lo = 1, hi = 0;  // empty when lo > hi
  double length() const { return hi > lo ? hi - lo : 0.0; }
};

// Chord of the disc (centre (cx, cy), radius r) on the line y = const.
Interval disc_chord(double cx, double cy, double r, double y) {
  const double d = y - cy;
  if (std::abs(d) >= r) return {};
  const double h = std::sqrt(r * r - d * d);
  return {cx - h, cx + h};
}

// Chord of a convex polygon (counter-clockwise vertices) on the line y = const.
Interval polygon_chord(const std::vector<std::array<double, 2>>& p, double y) {
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

// Exact area of the disc (centre height cy, radius r) between the lines y = a and y = b > a:
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

Interval hull(Interval a, const Interval& b) {
  if (b.lo > b.hi) return a;
  if (a.lo > a.hi) return b;
  return {std::min(a.lo, b.lo), std::max(a.hi, b.hi)};
}

// Chord of the Minkowski sum of the triangle `v` and a disc of radius rho: the
// union of the triangle, a rectangle on each edge and a disc on each vertex
// (convex, so the union of the chords is one interval).
Interval envelope_chord(const std::array<std::array<double, 2>, 3>& v, double rho, double y) {
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
}  // namespace

bool in_end_cap(const RraDesign& d, double z) {
  return z < d.end_cap_thickness_mm || z > d.length_mm - d.end_cap_thickness_mm;
}

double chamber_force_radius(const RraDesign& d, double z) {
  const double zc = std::clamp(z, d.end_cap_thickness_mm, d.length_mm - d.end_cap_thickness_mm);
  return d.chamber_radius(zc);
}

RodSection tca_section(const TcaDesign& design, double z, double bend_direction_rad, int strips, int subrows) {
  const RraDesign& a = design.actuator;
  const double r_o = a.outer_radius(z), r_f = chamber_force_radius(a, z);
  const double r_c = in_end_cap(a, z) ? 0.0 : a.chamber_radius(z);
  const double a_c = design.axis_distance(z), rho = r_o + design.sheath_thickness_mm;
  const double r_hole = design.centre_hole_diameter_mm / 2;
  // Section frame: y along the bending direction, x across it.
  std::array<std::array<double, 2>, 3> axes;
  RodSection s;
  for (int k = 0; k < 3; ++k) {
    const double phi = k * 2 * kPi / 3 - bend_direction_rad;
    axes[k] = {-a_c * std::sin(phi), a_c * std::cos(phi)};
    s.chamber_y.push_back(axes[k][1]);
    s.chamber_force_area.push_back(kPi * r_f * r_f);
  }
  // Counter-clockwise order for the envelope's outward normals.
  const double cross = (axes[1][0] - axes[0][0]) * (axes[2][1] - axes[0][1]) -
                       (axes[1][1] - axes[0][1]) * (axes[2][0] - axes[0][0]);
  if (cross < 0) std::swap(axes[1], axes[2]);
  double y_lo = 1e300, y_hi = -1e300;
  for (const auto& c : axes) y_lo = std::min(y_lo, c[1] - rho), y_hi = std::max(y_hi, c[1] + rho);
  // The envelope's chord is C1 inside (arcs meet the straight sides tangentially): 3-point
  // Gauss–Legendre per sub-row; the discs (tubes, chambers, centre hole) are exact.
  const double dy = (y_hi - y_lo) / strips, dr = dy / subrows;
  const double gauss[3][2] = {{-0.7745966692414834, 5.0 / 18}, {0.0, 8.0 / 18}, {0.7745966692414834, 5.0 / 18}};
  for (int j = 0; j < strips; ++j) {
    FibreStrip f;
    const double a = y_lo + j * dy, b = a + dy;
    f.y = 0.5 * (a + b);
    double envelope = 0, outer = disc_strip_area(0, r_hole, a, b);
    for (int r = 0; r < subrows; ++r)
      for (const auto& g : gauss)
        envelope += g[1] * dr * envelope_chord(axes, rho, a + (r + 0.5 + 0.5 * g[0]) * dr).length();
    for (const auto& c : axes) {
      const double disc = disc_strip_area(c[1], r_o, a, b);
      f.tube_area += disc - disc_strip_area(c[1], r_c, a, b);
      outer += disc;
    }
    f.sheath_area = std::max(0.0, envelope - outer);
    s.tube_area += f.tube_area;
    s.sheath_area += f.sheath_area;
    s.strips.push_back(f);
  }
  return s;
}

RodSection rra_section(const RraDesign& design, double z, int strips) {
  const double r_o = design.outer_radius(z), r_f = chamber_force_radius(design, z);
  const double r_c = in_end_cap(design, z) ? 0.0 : design.chamber_radius(z);
  RodSection s;
  s.chamber_y = {0.0};
  s.chamber_force_area = {kPi * r_f * r_f};
  const double dy = 2 * r_o / strips;
  for (int j = 0; j < strips; ++j) {
    FibreStrip f;
    const double a = -r_o + j * dy, b = a + dy;
    f.y = 0.5 * (a + b);
    f.tube_area = disc_strip_area(0, r_o, a, b) - disc_strip_area(0, r_c, a, b);
    s.tube_area += f.tube_area;
    s.strips.push_back(f);
  }
  return s;
}

}  // namespace softarm::fem

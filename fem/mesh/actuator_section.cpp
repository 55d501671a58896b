#include "fem/mesh/actuator_section.hpp"

#include <cmath>
#include <map>
#include <stdexcept>
#include "fem/core/angles.hpp"

namespace softarm::fem {
namespace {


Eigen::Vector2d direction(double angle) { return {std::cos(angle), std::sin(angle)}; }
Eigen::Vector2d lerp(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double t) { return a + t * (b - a); }
Eigen::Vector2d rotate(const Eigen::Vector2d& p, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * p.x() - s * p.y(), s * p.x() + c * p.y()};
}

/// The O-grid of one actuator in its own frame (3CA: O at the origin, the
/// actuator's axis C on the +x axis; lone RRA: C at the origin). Parameters
/// u ∈ [0, N) around the axis (counter-clockwise from the +x direction) and
/// v ∈ [0, V] outwards; half-integer values give the quadratic nodes.
class ActuatorGrid {
 public:
  ActuatorGrid(const SectionGeometry& g, bool three_chambered, int level, bool hole)
      : g_(g), tca_(three_chambered), L_(level), hole_(hole), N_(8 * level), m_(2 * level) {
    const double r_o = g.outer_radius;
    a_c_ = tca_ ? (2 * r_o + g.spacing) / std::sqrt(3.0) : 0.0;
    C_ = {a_c_, 0.0};
    r_c_ = r_o - g.wall_thickness;
    // Radial stations (thesis RRA: chamber, wall, ring band in two halves, core).
    knots_v_ = {0, double(L_), double(2 * L_), double(3 * L_), double(4 * L_)};
    knots_r_ = {0, r_c_, r_o - g.ring_side / 2, r_o, r_o + g.ring_side / 2};
    for (int q = 0; q < 4; ++q) kite_[q] = C_ + 0.5 * r_c_ * direction(phi(m_ / 2.0 + q * m_));
  }

  int rays() const { return N_; }
  int kite() const { return m_; }
  int radial() const { return tca_ ? 5 * L_ : 4 * L_; }
  static SectionRegion region_of_band(int band) {
    constexpr SectionRegion kBands[] = {SectionRegion::chamber, SectionRegion::tube, SectionRegion::ring_inner,
                                        SectionRegion::ring_outer, SectionRegion::core};
    return kBands[band];
  }
  int band_of_radial_element(int k) const { return k / L_; }

  /// Point of the ray grid.
  Eigen::Vector2d point(double u, double v) const {
    if (v <= knots_v_[1]) return lerp(kite_boundary(u), C_ + r_c_ * direction(phi(u)), v / L_);
    if (v <= knots_v_[4]) {
      int k = 1;
      while (v > knots_v_[k + 1]) ++k;
      const double t = (v - knots_v_[k]) / (knots_v_[k + 1] - knots_v_[k]);
      return C_ + (knots_r_[k] + t * (knots_r_[k + 1] - knots_r_[k])) * direction(phi(u));
    }
    const Eigen::Vector2d ring_edge = C_ + knots_r_[4] * direction(phi(u));
    return lerp(ring_edge, boundary(u), (v - knots_v_[4]) / L_);
  }

  /// Point of the kite (bilinear in its four corners), s, t ∈ [0, 1].
  Eigen::Vector2d kite_point(double s, double t) const {
    return (1 - s) * (1 - t) * kite_[0] + s * (1 - t) * kite_[1] + s * t * kite_[2] + (1 - s) * t * kite_[3];
  }

 private:
  /// Ray angle about C.
  double phi(double u) const {
    if (!tca_) return 2 * kPi * u / N_;
    const Eigen::Vector2d d = boundary(u) - C_;
    double angle = std::atan2(d.y(), d.x());
    if (u > N_ / 2.0 && angle < 0) angle += 2 * kPi;  // continuous through 180°
    if (u <= N_ / 2.0 && angle < 0) angle += 2 * kPi;
    return angle;
  }

  /// The sector boundary of a 3CA actuator: the envelope arc, the envelope's
  /// straight half-segment, the separating line to O (or to the hole, then the
  /// hole's arc); mirrored below the x axis.
  Eigen::Vector2d boundary(double u) const {
    if (u > N_ / 2.0) {
      const Eigen::Vector2d p = boundary(N_ - u);
      return {p.x(), -p.y()};
    }
    const double R_s = g_.outer_radius + g_.sheath_thickness;
    const Eigen::Vector2d e60 = direction(kPi / 3);
    const Eigen::Vector2d T1 = C_ + R_s * e60, M1 = (a_c_ / 2 + R_s) * e60;
    const double L = L_;
    if (u <= L) return C_ + R_s * direction(kPi / 3 * u / L);
    if (u <= 2 * L) return lerp(T1, M1, (u - L) / L);
    if (!hole_) return lerp(M1, Eigen::Vector2d::Zero(), (u - 2 * L) / (2 * L));
    if (u <= 3 * L) return lerp(M1, g_.hole_radius * e60, (u - 2 * L) / L);
    return g_.hole_radius * direction(kPi / 3 * (1 - (u - 3 * L) / L));
  }

  /// The kite's boundary, the inner end of every ray.
  Eigen::Vector2d kite_boundary(double u) const {
    double w = (u - m_ / 2.0) / m_;
    w -= 4 * std::floor(w / 4);
    const int q = std::min(3, static_cast<int>(w));
    return lerp(kite_[q], kite_[(q + 1) % 4], w - q);
  }

  SectionGeometry g_;
  bool tca_;
  int L_;
  bool hole_;
  int N_, m_;
  double a_c_ = 0, r_c_ = 0;
  Eigen::Vector2d C_;
  std::array<Eigen::Vector2d, 4> kite_;
  std::array<double, 5> knots_v_, knots_r_;
};

/// Collects raw points and (optionally) the quads over them, in a fixed order.
struct RawSection {
  std::vector<Eigen::Vector2d> points;
  std::vector<std::array<int, 9>> quads;
  std::vector<SectionRegion> region;
  std::vector<int> actuator;
};

/// Quad9 over a structured fine grid: `at(i, j)` is the raw index of fine node (i, j).
template <class At>
std::array<int, 9> grid_quad(int i0, int j0, const At& at) {
  return {at(i0, j0),     at(i0 + 2, j0),     at(i0 + 2, j0 + 2), at(i0, j0 + 2), at(i0 + 1, j0),
          at(i0 + 2, j0 + 1), at(i0 + 1, j0 + 2), at(i0, j0 + 1),     at(i0 + 1, j0 + 1)};
}

RawSection build_raw(const SectionGeometry& g, int actuators, int level, bool hole, bool with_quads) {
  RawSection raw;
  const double turn = 2 * kPi / 3;
  for (int i = 0; i < actuators; ++i) {
    const ActuatorGrid grid(g, actuators == 3, level, hole);
    const double angle = actuators == 3 ? g.first_axis_angle + i * turn : 0.0;
    const int N = grid.rays(), V = grid.radial(), m = grid.kite();
    // Ray grid: fine indices iu ∈ [0, 2N) (periodic), iv ∈ [0, 2V].
    const int ray_base = static_cast<int>(raw.points.size());
    for (int iu = 0; iu < 2 * N; ++iu)
      for (int iv = 0; iv <= 2 * V; ++iv) raw.points.push_back(rotate(grid.point(iu / 2.0, iv / 2.0), angle));
    const int kite_base = static_cast<int>(raw.points.size());
    for (int a = 0; a <= 2 * m; ++a)
      for (int b = 0; b <= 2 * m; ++b)
        raw.points.push_back(rotate(grid.kite_point(a / (2.0 * m), b / (2.0 * m)), angle));
    if (!with_quads) continue;
    const auto ray_at = [&](int iu, int iv) { return ray_base + (iu % (2 * N)) * (2 * V + 1) + iv; };
    for (int j = 0; j < N; ++j)
      for (int k = 0; k < V; ++k) {
        raw.quads.push_back(grid_quad(2 * j, 2 * k, ray_at));
        raw.region.push_back(ActuatorGrid::region_of_band(grid.band_of_radial_element(k)));
        raw.actuator.push_back(i);
      }
    const auto kite_at = [&](int a, int b) { return kite_base + a * (2 * m + 1) + b; };
    for (int a = 0; a < m; ++a)
      for (int b = 0; b < m; ++b) {
        raw.quads.push_back(grid_quad(2 * a, 2 * b, kite_at));
        raw.region.push_back(SectionRegion::chamber);
        raw.actuator.push_back(i);
      }
  }
  return raw;
}

double signed_area(const std::array<int, 9>& q, const std::vector<Eigen::Vector2d>& x) {
  double area = 0;
  for (int a = 0; a < 4; ++a) {
    const auto& p = x[q[a]];
    const auto& r = x[q[(a + 1) % 4]];
    area += p.x() * r.y() - r.x() * p.y();
  }
  return area / 2;
}

}  // namespace

ActuatorSection::ActuatorSection(int actuators, int level, bool with_hole, const SectionGeometry& reference)
    : actuators_(actuators), level_(level), hole_(with_hole) {
  if (actuators != 1 && actuators != 3) throw std::logic_error("ActuatorSection: 1 or 3 actuators");
  if (level < 1) throw std::logic_error("ActuatorSection: level must be >= 1");
  if (with_hole && !(reference.hole_radius > 0)) throw std::logic_error("ActuatorSection: hole topology needs a hole");
  RawSection raw = build_raw(reference, actuators, level, with_hole, true);

  // Merge coincident raw points (kite boundary and ray starts, shared sector
  // boundaries): spatial hash with a tolerance far below any element size.
  const double tol = 1e-7 * reference.outer_radius;
  std::map<std::pair<long long, long long>, std::vector<int>> cells;
  const auto cell = [&](const Eigen::Vector2d& p) {
    return std::make_pair(static_cast<long long>(std::floor(p.x() / (10 * tol))),
                          static_cast<long long>(std::floor(p.y() / (10 * tol))));
  };
  unique_of_raw_.assign(raw.points.size(), -1);
  for (std::size_t r = 0; r < raw.points.size(); ++r) {
    const auto [cx, cy] = cell(raw.points[r]);
    int found = -1;
    for (long long dx = -1; dx <= 1 && found < 0; ++dx)
      for (long long dy = -1; dy <= 1 && found < 0; ++dy) {
        const auto it = cells.find({cx + dx, cy + dy});
        if (it == cells.end()) continue;
        for (int u : it->second)
          if ((raw.points[raw_of_unique_[u]] - raw.points[r]).norm() < tol) found = u;
      }
    if (found < 0) {
      found = static_cast<int>(raw_of_unique_.size());
      raw_of_unique_.push_back(static_cast<int>(r));
      cells[{cx, cy}].push_back(found);
    }
    unique_of_raw_[r] = found;
  }
  num_nodes_ = static_cast<int>(raw_of_unique_.size());

  const std::vector<Eigen::Vector2d> x = positions(reference);
  for (std::size_t q = 0; q < raw.quads.size(); ++q) {
    std::array<int, 9> quad;
    for (int a = 0; a < 9; ++a) quad[a] = unique_of_raw_[raw.quads[q][a]];
    const double area = signed_area(quad, x);
    if (area < 0) quad = {quad[0], quad[3], quad[2], quad[1], quad[7], quad[6], quad[5], quad[4], quad[8]};
    if (std::abs(area) < 1e-12 * reference.outer_radius * reference.outer_radius)
      throw std::logic_error("ActuatorSection: degenerate quadrilateral (mesher bug)");
    quads_.push_back(quad);
  }
  region_ = std::move(raw.region);
  actuator_of_ = std::move(raw.actuator);
}

std::vector<Eigen::Vector2d> ActuatorSection::raw_points(const SectionGeometry& g) const {
  return build_raw(g, actuators_, level_, hole_, false).points;
}

std::vector<Eigen::Vector2d> ActuatorSection::positions(const SectionGeometry& g) const {
  const std::vector<Eigen::Vector2d> raw = raw_points(g);
  std::vector<Eigen::Vector2d> x(num_nodes_);
  for (int u = 0; u < num_nodes_; ++u) x[u] = raw[raw_of_unique_[u]];
  return x;
}

std::vector<Eigen::Vector2d> ActuatorSection::axes(const SectionGeometry& g) const {
  if (actuators_ == 1) return {Eigen::Vector2d::Zero()};
  const double a_c = (2 * g.outer_radius + g.spacing) / std::sqrt(3.0);
  std::vector<Eigen::Vector2d> c;
  for (int i = 0; i < 3; ++i) c.push_back(a_c * direction(g.first_axis_angle + i * 2 * kPi / 3));
  return c;
}

}  // namespace softarm::fem

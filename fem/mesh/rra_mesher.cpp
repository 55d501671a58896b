#include "fem/mesh/rra_mesher.hpp"

#include "fem/mesh/quadratic_mesh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "fem/core/input_error.hpp"
#include "fem/mesh/quadratic_mesh.hpp"
#include "fem/mesh/structured_mesh.hpp"

namespace softarm::fem {
namespace {

using Point = Eigen::Vector2d;  // (r, z)
constexpr double pi = std::numbers::pi;
constexpr int tube_part = 0, ring_part = 1;
// Half-diagonal of a ring's square core, as a fraction of the ring radius ρ.
constexpr double ring_core_fraction = 0.55;
// Axial reach of a bent lip transversal, as a fraction of the wall width there
// (further limited by the room in the neighbouring gap). At most 0.5, so that
// the 45° bend fits inside the wall.
constexpr double lip_bend_fraction = 0.2;

/// Outer surface of the tube between grooves (our definition): piecewise linear
/// through (0, r_b), both lips of every groove at that ring's centre radius
/// R_k = r_o(z_k), and (l, r_t). Giving both lips the radius R_k keeps the
/// surface continuous where the semicircular groove r = R_k − √(ρ² − (z − z_k)²)
/// meets it; the cost is that a lip sits off the straight taper by at most
/// |r_t − r_b|·ρ / l (0.02 mm for the thesis RRA).
class OuterProfile {
 public:
  explicit OuterProfile(const RraDesign& d) {
    knots_.push_back({0.0, d.bottom_radius_mm});
    const double rho = d.ring_section_radius();
    for (int k = 1; k <= d.ring_count; ++k) {
      const double z = d.ring_centre_z(k), r = d.outer_radius(z);
      knots_.push_back({z - rho, r});
      knots_.push_back({z + rho, r});
    }
    knots_.push_back({d.length_mm, d.top_radius_mm});
  }
  double radius(double z) const {
    const auto upper = std::upper_bound(knots_.begin() + 1, knots_.end() - 1, z,
                                        [](double value, const Point& knot) { return value < knot.x(); });
    const Point& a = *(upper - 1);
    const Point& b = *upper;
    return a.y() + (b.y() - a.y()) * (z - a.x()) / (b.x() - a.x());
  }

 private:
  std::vector<Point> knots_;  // (z, r)
};

/// The semicircular groove of ring k and the ring's circle: node q of the circle,
/// divided into 2·segments, is at angle φ_q with (r, z) = (R_k − ρ sin φ, z_k − ρ cos φ):
/// q = 0 is the lower lip, q = segments the upper lip, 0 < q < segments the
/// groove, q > segments the ring's free side. φ_q = qπ/segments, except that a
/// cap face ending in the groove may pin node `pinned` to the angle `pinned_phi`,
/// the groove's two parts on either side keeping uniform spacing.
struct Groove {
  Point centre;  // (R_k, z_k)
  double rho = 0;
  int segments = 0;
  int pinned = -1;
  double pinned_phi = 0;
  int cap_lines = 0;  // cap-face transversals ending in this groove

  static Point direction(double phi) { return {-std::sin(phi), -std::cos(phi)}; }
  double uniform_phi(double q) const { return q * pi / segments; }
  double phi(int q) const {
    if (pinned < 0 || q > segments) return uniform_phi(q);
    if (q <= pinned) return pinned_phi * q / pinned;
    return pinned_phi + (pi - pinned_phi) * (q - pinned) / (segments - pinned);
  }
  Point point_at(double phi) const { return centre + rho * direction(phi); }
  Point arc_point(int q) const { return point_at(phi(q)); }
  double lip_z(int side) const { return centre.y() + (side == 0 ? -rho : rho); }
};

/// A key mesh line across the wall, from `inner` (on r = r_c(z)) at η = 0 to
/// `outer` (on the outer surface) at η = 1, r linear in η. A bent one
/// (bend_extent > 0) leaves `outer` along a parabola in η that reaches the axial
/// offset `reach` at η0 = 1 − bend_extent with zero slope, then blends smoothly
/// (C1) to the inner end's own offset inner.z − outer.z (usually equal to
/// `reach`: a radial line). bend_extent = 2|reach| / Δr makes it leave `outer` at 45°.
struct Transversal {
  Point inner, outer;
  double bend_extent = 0, reach = 0;
  int groove = -1, arc_index = -1;  // `outer` is node arc_index of that groove's circle, if any
  bool bottom_cap_face = false, top_cap_face = false;

  Point at(double eta) const {
    if (bend_extent <= 0) return inner + eta * (outer - inner);
    const double eta0 = 1 - bend_extent, inner_offset = inner.y() - outer.y();
    double offset;
    if (eta >= eta0) {
      const double s = (eta - eta0) / bend_extent;
      offset = reach * (1 - s * s);
    } else {
      const double t = eta / eta0, smooth = t * t * (3 - 2 * t);
      offset = inner_offset + (reach - inner_offset) * smooth;
    }
    return {inner.x() + eta * (outer.x() - inner.x()), outer.y() + offset};
  }
  /// Deviation of the line from the straight chord inner–outer (transfinite interpolation).
  Point bend(double eta) const { return at(eta) - (inner + eta * (outer - inner)); }
};

class RraMesher {
 public:
  RraMesher(const RraDesign& d, int level, int wall_layers_at_level_1)
      : d_(d), sizes_(rra_mesh_sizes(d, level, wall_layers_at_level_1)), profile_(d) {
    if (d.square_rings()) return;  // square rings: build_square_wall lays out its own blocks
    for (int k = 1; k <= d.ring_count; ++k) {
      const double z = d.ring_centre_z(k);
      grooves_.push_back({Point(d.outer_radius(z), z), d.ring_section_radius(), sizes_.groove_segments});
    }
  }

  Mesh build() {
    if (d_.square_rings()) {
      build_square_wall();
    } else {
      const std::vector<Transversal> keys = key_transversals();
      build_wall(keys);
    }
    const auto bottom_core = build_core(0, bottom_cap_column_, sizes_.core_layers_bottom);
    const auto top_core = build_core(top_cap_column_, static_cast<int>(columns_.size()) - 1, sizes_.core_layers_top);
    for (std::size_t k = 0; k < grooves_.size(); ++k) build_ring(grooves_[k], arc_nodes_[k]);

    Mesh mesh = builder_.finish({"tube", "rings"});
    add_node_sets(mesh, bottom_core, top_core);
    add_chamber(mesh, bottom_core.back(), top_core.front());
    return mesh;
  }

 private:
  Point chamber_point(double z) const { return {d_.chamber_radius(z), z}; }
  /// z of the foot of the perpendicular from p to the chamber line r = r_c(z).
  double normal_foot_z(const Point& p) const {
    const double slope = (d_.top_radius_mm - d_.bottom_radius_mm) / d_.length_mm;
    return (p.y() + slope * (p.x() - d_.chamber_radius(0))) / (1 + slope * slope);
  }
  int refined(double length) const {
    const double h1 = sizes_.element_size_mm * sizes_.refinement;
    return std::max(1, static_cast<int>(std::lround(length / h1))) * sizes_.refinement;
  }

  /// The outer-surface point across the gap from lip `side` of groove k: the
  /// facing lip of the neighbouring groove, or the tube's end.
  Point across_gap(int k, int side) const {
    const int n = static_cast<int>(grooves_.size());
    if (side == 0) return k == 0 ? Point(d_.bottom_radius_mm, 0) : lip_point(k - 1, 1);
    return k == n - 1 ? Point(d_.top_radius_mm, d_.length_mm) : lip_point(k + 1, 0);
  }
  Point lip_point(int k, int side) const {
    const Groove& g = grooves_[static_cast<std::size_t>(k)];
    return {g.centre.x(), g.lip_z(side)};
  }

  /// The line from a lip (side 0: lower, 1: upper), bending `reach` into the
  /// neighbouring gap, away from the groove, and ending `inner_distance` from
  /// the lip on the chamber line (= reach, unless a cap face is moved onto it).
  /// It leaves the lip along the bisector of the tube's corner there, between
  /// the groove (which leaves the lip radially) and the outer surface: 45° on a
  /// straight tube, tilted by the taper of the lip-to-lip profile.
  Transversal lip_transversal(int k, int side, double reach, double inner_distance) const {
    const double away = side == 0 ? -1.0 : 1.0;
    Transversal t;
    t.outer = lip_point(k, side);
    t.inner = chamber_point(t.outer.y() + away * inner_distance);
    const Point bisector = (across_gap(k, side) - t.outer).normalized() + Point(-1, 0);
    const double departure_slope = std::abs(bisector.y() / bisector.x());  // |dz/dr| of the bisector
    t.reach = away * reach;
    t.bend_extent = std::min(1.0, 2 * reach / ((t.outer.x() - t.inner.x()) * departure_slope));
    t.groove = k;
    t.arc_index = side == 0 ? 0 : grooves_[static_cast<std::size_t>(k)].segments;
    return t;
  }

  /// The block boundaries across the wall, ordered along z.
  std::vector<Transversal> key_transversals() {
    const int n = static_cast<int>(grooves_.size());
    // Bend reach of each lip (index 2k + side): a fraction of the wall width,
    // and at most a quarter of the gap it bends into, so the two lines bending
    // into one gap keep at least a quarter of it between their inner ends even
    // when one of them is moved onto a cap face (up to twice its reach).
    std::vector<double> reach(static_cast<std::size_t>(2 * n));
    for (int k = 0; k < n; ++k)
      for (int side = 0; side < 2; ++side) {
        const Point lip = lip_point(k, side);
        const double wall = lip.x() - d_.chamber_radius(lip.y());
        const double gap = std::abs(across_gap(k, side).y() - lip.y());
        reach[static_cast<std::size_t>(2 * k + side)] = std::min(lip_bend_fraction * wall, gap / 4);
      }

    std::vector<Transversal> keys;
    std::vector<double> inner_distance(reach);
    std::vector<int> lip_cap_face(static_cast<std::size_t>(2 * n), 0);  // 1 bottom, 2 top: merged cap face
    for (int face = 0; face < 2; ++face) {
      const double z_cap = face == 0 ? d_.end_cap_thickness_mm : d_.length_mm - d_.end_cap_thickness_mm;
      if (auto t = cap_face_transversal(z_cap, reach, inner_distance, lip_cap_face, face)) {
        (face == 0 ? t->bottom_cap_face : t->top_cap_face) = true;
        keys.push_back(*t);
      }
    }
    keys.push_back({chamber_point(0), Point(d_.bottom_radius_mm, 0)});
    keys.push_back({chamber_point(d_.length_mm), Point(d_.top_radius_mm, d_.length_mm)});
    for (int k = 0; k < n; ++k)
      for (int side = 0; side < 2; ++side) {
        const auto i = static_cast<std::size_t>(2 * k + side);
        Transversal t = lip_transversal(k, side, reach[i], inner_distance[i]);
        t.bottom_cap_face = lip_cap_face[i] == 1;
        t.top_cap_face = lip_cap_face[i] == 2;
        keys.push_back(t);
      }
    std::sort(keys.begin(), keys.end(), [](const Transversal& a, const Transversal& b) { return a.outer.y() < b.outer.y(); });
    for (std::size_t i = 0; i + 1 < keys.size(); ++i)
      if (!(keys[i].outer.y() < keys[i + 1].outer.y() && keys[i].inner.y() < keys[i + 1].inner.y()))
        throw InputError("geometry", "cannot lay out a mesh at level " + std::to_string(level()) +
                                         ": mesh blocks near z = " + std::to_string(keys[i].outer.y()) +
                                         " mm cross (is the chamber shorter than one groove segment?)");
    return keys;
  }

  /// The transversal ending on the cap's inner face z = z_cap.
  /// Inside a groove it runs straight from the chamber line to the level-1
  /// groove node nearest in z, so that every level has the same blocks and
  /// halves the previous level's elements exactly -- unless that line would be
  /// slanted by more than half the wall it crosses (the thin wall under a deep
  /// groove, which it would shear into inverted elements): then this level's
  /// nearest groove node is pinned where the chamber line's normal through
  /// z_cap meets the groove, and the line runs along that normal.
  /// Within twice a lip's bend reach of that lip, on its gap side, the lip's
  /// own line ends on the cap face instead (a separate line there would cross
  /// it, or leave a sliver between the two); it still leaves the lip along its
  /// corner's bisector. Returns nothing when merged into a lip.
  std::optional<Transversal> cap_face_transversal(double z_cap, const std::vector<double>& reach,
                                                  std::vector<double>& inner_distance,
                                                  std::vector<int>& lip_cap_face, int face) {
    for (std::size_t k = 0; k < grooves_.size(); ++k) {
      Groove& g = grooves_[k];
      if (!(g.lip_z(0) < z_cap && z_cap < g.lip_z(1))) continue;
      auto miss = [&](double phi) { return normal_foot_z(g.point_at(phi)) - z_cap; };
      auto z_of = [&](int q) { return g.point_at(g.uniform_phi(q)).y(); };
      const int f = sizes_.refinement;
      int best = f;
      for (int q = 2 * f; q < g.segments; q += f)
        if (std::abs(z_of(q) - z_cap) < std::abs(z_of(best) - z_cap)) best = q;
      const Point node = g.arc_point(best);
      const double wall_crossed = (node - chamber_point(normal_foot_z(node))).norm();
      if (std::abs(miss(g.uniform_phi(best))) > 0.5 * wall_crossed) {
        if (g.cap_lines > 0)  // pinning would move the node the other cap's line ends on
          throw InputError("geometry", "cannot lay out a mesh: both cap faces end in the groove at z = " +
                                           std::to_string(g.centre.y()) + " mm (the chamber is too short)");
        for (int q = 0; q < g.segments; ++q) {  // bracket the root between two nodes of this level
          double lo = g.uniform_phi(q), hi = g.uniform_phi(q + 1);
          if (miss(lo) * miss(hi) > 0) continue;
          for (int it = 0; it < 60; ++it) {  // bisection
            const double mid = 0.5 * (lo + hi);
            ((miss(mid) <= 0) == (miss(lo) <= 0) ? lo : hi) = mid;
          }
          g.pinned_phi = 0.5 * (lo + hi);
          g.pinned = std::clamp(static_cast<int>(std::lround(g.pinned_phi / g.uniform_phi(1))), 1, g.segments - 1);
          best = g.pinned;
          break;
        }
      }
      ++g.cap_lines;
      Transversal t{chamber_point(z_cap), g.arc_point(best)};
      t.groove = static_cast<int>(k);
      t.arc_index = best;
      return t;
    }
    for (std::size_t i = 0; i < reach.size(); ++i) {
      const int side = static_cast<int>(i % 2);
      const double lip = grooves_[i / 2].lip_z(side);
      const double distance = side == 0 ? lip - z_cap : z_cap - lip;  // measured into the gap it bends into
      if (distance < 0 || distance >= 2 * reach[i]) continue;
      if (lip_cap_face[i] != 0)
        throw InputError("geometry", "cannot lay out a mesh: both cap faces end on the lip at z = " +
                                         std::to_string(lip) + " mm (the chamber is too short)");
      inner_distance[i] = distance;
      lip_cap_face[i] = face + 1;
      return std::nullopt;
    }
    return Transversal{chamber_point(z_cap), Point(profile_.radius(z_cap), z_cap)};
  }

  /// The wall strip: blocks between consecutive key transversals, each filled
  /// by (length-scaled) transfinite interpolation of its four sides (bottom: the
  /// chamber line, top: the outer surface or a groove arc, sides: the two key
  /// transversals).
  void build_wall(const std::vector<Transversal>& keys) {
    arc_nodes_.assign(grooves_.size(), std::vector<int>(static_cast<std::size_t>(sizes_.groove_segments) + 1, -1));
    add_column(keys.front(), [&](double eta) { return keys.front().at(eta); });
    for (std::size_t b = 0; b + 1 < keys.size(); ++b) {
      const Transversal& A = keys[b];
      const Transversal& B = keys[b + 1];
      const bool on_arc = A.groove >= 0 && A.groove == B.groove && A.arc_index < B.arc_index;
      const int n = on_arc ? B.arc_index - A.arc_index
                           : refined(0.5 * ((B.outer - A.outer).norm() + (B.inner - A.inner).norm()));
      const std::vector<double> bottom_z = block_bottom(A, B, n, on_arc);
      for (int j = 1; j < n; ++j) {
        const double xi = static_cast<double>(j) / n;
        const Point bottom = chamber_point(bottom_z[static_cast<std::size_t>(j)]);
        const Point top = on_arc ? grooves_[static_cast<std::size_t>(A.groove)].arc_point(A.arc_index + j)
                                 : Point(A.outer + xi * (B.outer - A.outer));
        Transversal column{bottom, top};
        if (on_arc) {
          column.groove = A.groove;
          column.arc_index = A.arc_index + j;
        }
        // The sides' bends are blended in scaled by this column's length, so a
        // column through the thin wall under a deep groove is bent (sheared) no
        // more, relatively, than the sides are.
        const double length = (top - bottom).norm();
        const double from_A = (1 - xi) * length / (A.outer - A.inner).norm();
        const double from_B = xi * length / (B.outer - B.inner).norm();
        add_column(column, [&](double eta) -> Point {
          return (1 - eta) * bottom + eta * top + from_A * A.bend(eta) + from_B * B.bend(eta);
        });
      }
      add_column(B, [&](double eta) { return B.at(eta); });
    }
    if (bottom_cap_column_ < 0 || top_cap_column_ < 0) throw std::logic_error("mesh_rra: cap face not on a column");
    for (const auto& nodes : arc_nodes_)
      if (std::count(nodes.begin(), nodes.end(), -1) > 0) throw std::logic_error("mesh_rra: groove node missing");
  }

  /// The wall and rings for square rings (RraDesign::RingSection::square). Every
  /// column is a straight line at constant z from the chamber line to the groove
  /// bottom's line r_o(z) − a/2 (n_in layers), on through the groove depth to the
  /// outer surface r_o(z) (groove_layers) and, on a groove, through the ring's
  /// protruding half to r_o(z) + a/2 (ring_layers). Columns stand at the tube
  /// ends and at both faces of every groove, with uniform ones between: every
  /// block is a parallelogram following the taper, so the mesh is exact. Between
  /// the faces of a groove the outer two bands are ring ("rings"), elsewhere
  /// tube; the ring shares the groove's nodes (bonded). A cap's inner face gets a
  /// column of its own, or, when it falls within a quarter of an element of an
  /// existing column, moves that column's chamber end onto it (a slight slant
  /// under the groove-bottom line), so that no sliver element is made.
  void build_square_wall() {
    const double a = d_.ring_square_side_mm(), l = d_.length_mm;
    struct Column {
      double z_in, z_out;
      int cap_face = 0;  // 1 bottom, 2 top
    };
    std::vector<double> faces{0.0};  // interval i between faces i and i + 1 is a groove for odd i
    for (int k = 1; k <= d_.ring_count; ++k) {
      faces.push_back(d_.ring_centre_z(k) - a / 2);
      faces.push_back(d_.ring_centre_z(k) + a / 2);
    }
    faces.push_back(l);
    std::vector<Column> cols;
    std::vector<char> groove;  // groove[j]: the interval between columns j and j + 1 is a groove
    for (std::size_t i = 0; i + 1 < faces.size(); ++i) {
      const double z0 = faces[i], z1 = faces[i + 1];
      const int n = i % 2 == 1 ? sizes_.groove_segments : refined(z1 - z0);
      for (int j = 0; j < n; ++j) {
        const double z = j == 0 ? z0 : z0 + (z1 - z0) * j / n;
        cols.push_back({z, z});
        groove.push_back(i % 2 == 1);
      }
    }
    cols.push_back({l, l});

    for (int face = 1; face <= 2; ++face) {
      const double z_cap = face == 1 ? d_.end_cap_thickness_mm : l - d_.end_cap_thickness_mm;
      std::size_t i = 0;  // the interval [cols[i], cols[i + 1]) holding the cap face (by its outer z)
      while (i + 2 < cols.size() && cols[i + 1].z_out <= z_cap) ++i;
      const double z0 = cols[i].z_out, z1 = cols[i + 1].z_out, quarter = 0.25 * (z1 - z0);
      std::size_t snap = cols.size();
      if (z_cap - z0 < quarter && i > 0) snap = i;
      else if (z1 - z_cap < quarter && i + 2 < cols.size()) snap = i + 1;
      if (snap < cols.size()) {
        if (cols[snap].cap_face != 0)
          throw InputError("geometry", "cannot lay out a mesh at level " + std::to_string(level()) +
                                           ": both cap faces fall on the column at z = " + std::to_string(cols[snap].z_out) +
                                           " mm (the chamber is too short)");
        cols[snap].z_in = z_cap;
        cols[snap].cap_face = face;
      } else {
        Column c{z_cap, z_cap};
        c.cap_face = face;
        cols.insert(cols.begin() + static_cast<std::ptrdiff_t>(i) + 1, c);
        groove.insert(groove.begin() + static_cast<std::ptrdiff_t>(i) + 1, groove[i]);
      }
    }

    const int n_g = sizes_.groove_layers, n_in = sizes_.wall_layers - n_g, n_r = sizes_.ring_layers;
    const auto inner_nodes = static_cast<std::size_t>(n_in) + 1, tube_nodes = inner_nodes + static_cast<std::size_t>(n_g);
    for (std::size_t j = 0; j < cols.size(); ++j) {
      const Column& c = cols[j];
      const bool ring = (j > 0 && groove[j - 1]) || (j < groove.size() && groove[j]);
      const Point p0 = chamber_point(c.z_in), p2(d_.outer_radius(c.z_out), c.z_out);
      const Point p1(p2.x() - a / 2, c.z_out), p3(p2.x() + a / 2, c.z_out);
      std::vector<int> ids;
      for (int i = 0; i <= n_in; ++i) ids.push_back(builder_.add_node(i == 0 ? p0 : i == n_in ? p1 : Point(p0 + (p1 - p0) * (double(i) / n_in))));
      for (int i = 1; i <= n_g; ++i) ids.push_back(builder_.add_node(i == n_g ? p2 : Point(p1 + (p2 - p1) * (double(i) / n_g))));
      if (ring)
        for (int i = 1; i <= n_r; ++i) ids.push_back(builder_.add_node(i == n_r ? p3 : Point(p2 + (p3 - p2) * (double(i) / n_r))));
      if (c.cap_face == 1) bottom_cap_column_ = static_cast<int>(j);
      if (c.cap_face == 2) top_cap_column_ = static_cast<int>(j);
      if (j > 0) {
        const std::vector<int>& prev = columns_.back();
        auto band = [](const std::vector<int>& column, std::size_t from, std::size_t to) {
          return std::vector<int>(column.begin() + static_cast<std::ptrdiff_t>(from), column.begin() + static_cast<std::ptrdiff_t>(to));
        };
        if (groove[j - 1]) {
          builder_.add_grid({band(prev, 0, inner_nodes), band(ids, 0, inner_nodes)}, tube_part);
          builder_.add_grid({band(prev, inner_nodes - 1, prev.size()), band(ids, inner_nodes - 1, ids.size())}, ring_part);
        } else {
          builder_.add_grid({band(prev, 0, tube_nodes), band(ids, 0, tube_nodes)}, tube_part);
        }
      }
      columns_.push_back(std::move(ids));
    }
    if (bottom_cap_column_ < 0 || top_cap_column_ < 0 || !(bottom_cap_column_ < top_cap_column_))
      throw std::logic_error("mesh_rra: cap faces not on distinct columns");
  }

  /// z of a block's nodes on the chamber line: uniform, except under a groove,
  /// where the columns turn towards the chamber line's normal as the groove
  /// deepens (weight sin²φ: 0 at the lips, 1 at the groove bottom), so that the
  /// thin wall under a deep groove is crossed straight rather than sheared.
  std::vector<double> block_bottom(const Transversal& A, const Transversal& B, int n, bool on_arc) const {
    const double z0 = A.inner.y(), z1 = B.inner.y();
    std::vector<double> uniform(static_cast<std::size_t>(n) + 1), z;
    for (int j = 0; j <= n; ++j) uniform[static_cast<std::size_t>(j)] = z0 + (z1 - z0) * j / n;
    if (!on_arc) return uniform;
    const Groove& g = grooves_[static_cast<std::size_t>(A.groove)];
    z = uniform;
    for (int j = 1; j < n; ++j) {
      const int q = A.arc_index + j;
      const double foot = std::clamp(normal_foot_z(g.arc_point(q)), z0, z1);
      const double w = std::pow(std::sin(g.phi(q)), 2);
      z[static_cast<std::size_t>(j)] = (1 - w) * uniform[static_cast<std::size_t>(j)] + w * foot;
    }
    for (int j = 0; j < n; ++j)  // keep at least a fifth of the uniform spacing, else stay uniform
      if (!(z[static_cast<std::size_t>(j) + 1] - z[static_cast<std::size_t>(j)] > 0.2 * (z1 - z0) / n)) return uniform;
    return z;
  }

  /// Adds one column of wall nodes at η = i / wall_layers (exact ends) and the
  /// elements joining it to the previous column.
  template <class Position>
  void add_column(const Transversal& line, Position position) {
    const int layers = sizes_.wall_layers;
    std::vector<int> ids;
    for (int i = 0; i <= layers; ++i)
      ids.push_back(builder_.add_node(i == 0 ? line.inner : i == layers ? line.outer : position(double(i) / layers)));
    if (line.groove >= 0) arc_nodes_[static_cast<std::size_t>(line.groove)][static_cast<std::size_t>(line.arc_index)] = ids.back();
    const int column = static_cast<int>(columns_.size());
    if (line.bottom_cap_face) bottom_cap_column_ = column;
    if (line.top_cap_face) top_cap_column_ = column;
    if (!columns_.empty()) builder_.add_grid({columns_.back(), ids}, tube_part);
    columns_.push_back(std::move(ids));
  }

  /// Solid core of an end cap, r ∈ [0, r_c(z)], on wall columns first..last:
  /// lines of constant z from the axis to the wall's inner node. Returns the
  /// lines (axis node first), bottom to top.
  std::vector<std::vector<int>> build_core(int first, int last, int layers) {
    std::vector<std::vector<int>> lines;
    for (int J = first; J <= last; ++J) {
      const int wall_node = columns_[static_cast<std::size_t>(J)].front();
      const Point edge = builder_.node(wall_node);
      std::vector<int> line;
      for (int i = 0; i < layers; ++i) line.push_back(builder_.add_node(edge.x() * i / layers, edge.y()));
      line.push_back(wall_node);
      lines.push_back(std::move(line));
    }
    builder_.add_grid(lines, tube_part);
    return lines;
  }

  /// O-grid of one ring: a square core (corners towards the lips, the groove
  /// bottom and the free side) of q × q quads, and an annulus of straight
  /// lines from the square's edge nodes to the circle's nodes. The groove half
  /// of the circle reuses the tube's nodes (the bond).
  void build_ring(const Groove& g, const std::vector<int>& groove_nodes) {
    const int q = g.segments / 2, around = 2 * g.segments, layers = sizes_.ring_layers;
    std::vector<int> circle(groove_nodes);
    for (int s = g.segments + 1; s < around; ++s) circle.push_back(builder_.add_node(g.arc_point(s)));

    std::array<Point, 4> corner;
    for (int s = 0; s < 4; ++s) corner[static_cast<std::size_t>(s)] = g.centre + ring_core_fraction * g.rho * Groove::direction(s * pi / 2);
    std::vector<std::vector<int>> core(static_cast<std::size_t>(q) + 1);  // core[u][v], bilinear on the square
    for (int u = 0; u <= q; ++u)
      for (int v = 0; v <= q; ++v) {
        const double a = double(u) / q, b = double(v) / q;
        core[static_cast<std::size_t>(u)].push_back(builder_.add_node((1 - a) * (1 - b) * corner[0] + a * (1 - b) * corner[1] +
                                                                      a * b * corner[2] + (1 - a) * b * corner[3]));
      }
    builder_.add_grid(core, ring_part);

    // Square edge node facing circle node s: edges corner0→1, 1→2, 2→3, 3→0 in turn.
    auto edge_node = [&](int s) {
      const int side = s / q, t = s % q;
      const auto at = [&](int u, int v) { return core[static_cast<std::size_t>(u)][static_cast<std::size_t>(v)]; };
      switch (side) {
        case 0: return at(t, 0);
        case 1: return at(q, t);
        case 2: return at(q - t, q);
        default: return at(0, q - t);
      }
    };
    std::vector<std::vector<int>> spokes;
    for (int s = 0; s < around; ++s) {
      const int inner = edge_node(s), outer = circle[static_cast<std::size_t>(s)];
      std::vector<int> spoke{inner};
      for (int l = 1; l < layers; ++l) {
        const double w = double(l) / layers;
        spoke.push_back(builder_.add_node((1 - w) * builder_.node(inner) + w * builder_.node(outer)));
      }
      spoke.push_back(outer);
      spokes.push_back(std::move(spoke));
    }
    spokes.push_back(spokes.front());
    builder_.add_grid(spokes, ring_part);
  }

  void add_node_sets(Mesh& mesh, const std::vector<std::vector<int>>& bottom_core,
                     const std::vector<std::vector<int>>& top_core) const {
    auto& sets = mesh.node_sets;
    for (const auto* core : {&bottom_core, &top_core})
      for (const auto& line : *core) sets["axis"].push_back(line.front());
    auto end_face = [&](const std::vector<int>& core_line, const std::vector<int>& wall_column) {
      std::vector<int> face(core_line.begin(), core_line.end() - 1);  // the last is the wall's inner node
      face.insert(face.end(), wall_column.begin(), wall_column.end());
      return face;
    };
    sets["bottom"] = end_face(bottom_core.front(), columns_.front());
    sets["top"] = end_face(top_core.back(), columns_.back());
    const bool top_fixed = d_.fixed_end == RraDesign::FixedEnd::top;
    sets["fixed_end"] = sets[top_fixed ? "top" : "bottom"];
    sets["free_end_centre"] = {top_fixed ? bottom_core.front().front() : top_core.back().front()};
  }

  /// Chain: axis → along the bottom cap face → up the chamber wall → along the
  /// top cap face → axis; positive volume because the wall is climbed in +z.
  void add_chamber(Mesh& mesh, const std::vector<int>& bottom_face, const std::vector<int>& top_face) const {
    std::vector<int> chain(bottom_face);
    for (int J = bottom_cap_column_ + 1; J <= top_cap_column_; ++J) chain.push_back(columns_[static_cast<std::size_t>(J)].front());
    chain.insert(chain.end(), top_face.rbegin() + 1, top_face.rend());
    Chamber chamber{1, "chamber", {}, {}};
    for (std::size_t i = 0; i + 1 < chain.size(); ++i) chamber.facets.push_back({chain[i], chain[i + 1]});
    mesh.chambers.push_back(std::move(chamber));
  }

  int level() const { return static_cast<int>(std::lround(std::log2(sizes_.refinement))) + 1; }

  const RraDesign& d_;
  RraMeshSizes sizes_;
  OuterProfile profile_;
  std::vector<Groove> grooves_;
  QuadMeshBuilder builder_;
  std::vector<std::vector<int>> columns_;    // wall columns along z, each inner → outer
  std::vector<std::vector<int>> arc_nodes_;  // per groove, its circle nodes 0..segments
  int bottom_cap_column_ = -1, top_cap_column_ = -1;
};

}  // namespace

RraMeshSizes rra_mesh_sizes(const RraDesign& d, int level, int wall_layers_at_level_1) {
  if (wall_layers_at_level_1 < 1) throw std::invalid_argument("mesh_rra: at least one element through the wall");
  if (level < 1 || level > 10) throw std::invalid_argument("mesh_rra: level must be in [1, 10], got " + std::to_string(level));
  validate(d);
  RraMeshSizes s;
  const int f = 1 << (level - 1);
  const double h1 = d.wall_thickness_mm / wall_layers_at_level_1;
  auto layers = [&](double length) { return std::max(1, static_cast<int>(std::lround(length / h1))) * f; };
  s.refinement = f;
  s.element_size_mm = h1 / f;
  s.wall_layers = wall_layers_at_level_1 * f;
  if (d.square_rings()) {
    const double a = d.ring_square_side_mm();
    s.groove_layers = layers(a / 2);
    s.wall_layers = layers(d.wall_thickness_mm - a / 2) + s.groove_layers;
    s.ring_layers = s.groove_layers;
    s.groove_segments = std::max(2, static_cast<int>(std::lround(a / h1))) * f;
  } else if (d.ring_count > 0) {
    const int quarter = std::max(2, static_cast<int>(std::ceil(pi * d.ring_section_radius() / (2 * h1) - 1e-9)));
    s.groove_segments = 2 * quarter * f;
    // Annulus layers about as thick as the circle's segments are long.
    s.ring_layers = std::max(1, static_cast<int>(std::lround((1 - ring_core_fraction) * 2 * quarter / pi))) * f;
  }
  s.core_layers_bottom = layers(d.chamber_radius(d.end_cap_thickness_mm));
  s.core_layers_top = layers(d.chamber_radius(d.length_mm - d.end_cap_thickness_mm));
  return s;
}

Mesh mesh_rra_quadratic(const RraDesign& design, int level, int wall_layers_at_level_1) {
  if (design.square_rings()) return to_quadratic(mesh_rra(design, level, wall_layers_at_level_1));  // all edges straight
  const double rho = design.ring_section_radius();
  // An edge whose two ends lie on ring k's circle (ring boundary or groove) is an arc of it.
  auto on_ring_circle = [&design, rho](const Eigen::Vector2d& a, const Eigen::Vector2d& b) -> std::optional<Eigen::Vector2d> {
    if (design.ring_count == 0) return std::nullopt;
    const Eigen::Vector2d mid = 0.5 * (a + b);
    const int k = std::clamp(static_cast<int>(mid.y() / design.pitch()) + 1, 1, design.ring_count);
    const Eigen::Vector2d centre(design.outer_radius(design.ring_centre_z(k)), design.ring_centre_z(k));
    const double tolerance = 1e-9 * rho;
    if (std::abs((a - centre).norm() - rho) > tolerance || std::abs((b - centre).norm() - rho) > tolerance)
      return std::nullopt;
    return Eigen::Vector2d(centre + rho * (mid - centre).normalized());
  };
  return to_quadratic(mesh_rra(design, level, wall_layers_at_level_1), on_ring_circle);
}

Mesh mesh_rra(const RraDesign& design, int level, int wall_layers_at_level_1) {
  return RraMesher(design, level, wall_layers_at_level_1).build();
}

}  // namespace softarm::fem

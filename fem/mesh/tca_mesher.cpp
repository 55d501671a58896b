#include "fem/mesh/tca_mesher.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "fem/mesh/layered_extrusion.hpp"

namespace softarm::fem {
namespace {

enum Part { kTube = 0, kRings = 1, kSheath = 2 };

/// What an axial band of an actuator holds, decided at its mid-height.
struct BandKind {
  bool cap = false, ring = false;
};

constexpr double kMaxBandHeight = 4.0;  // mm: longer bands get more element layers (level 1)

/// Axial bands of one actuator: breakpoints at both ends, the cap interfaces and
/// both faces of every ring. A cap interface closer than 0.3·a to a ring face is
/// moved onto it (the meshed cap then differs from t_c by < 0.3·a; without this a
/// sliver layer would form).
void actuator_bands(const RraDesign& d, double a, int level, std::vector<ExtrusionLayer>& layers,
                    std::vector<BandKind>& kinds) {
  const double l = d.length_mm;
  std::vector<double> z = {0.0, l};
  for (int k = 1; k <= d.ring_count; ++k) {
    z.push_back(d.ring_centre_z(k) - a / 2);
    z.push_back(d.ring_centre_z(k) + a / 2);
  }
  std::vector<double> caps = {d.end_cap_thickness_mm, l - d.end_cap_thickness_mm};
  for (double& c : caps)
    for (double p : z)
      if (std::abs(p - c) < 0.3 * a) c = p;
  z.insert(z.end(), caps.begin(), caps.end());
  std::sort(z.begin(), z.end());
  z.erase(std::unique(z.begin(), z.end(), [&](double p, double q) { return q - p < 1e-9 * l; }), z.end());
  for (std::size_t i = 0; i + 1 < z.size(); ++i) {
    const double mid = 0.5 * (z[i] + z[i + 1]), h = z[i + 1] - z[i];
    BandKind kind;
    kind.cap = mid < caps[0] || mid > caps[1];
    for (int k = 1; k <= d.ring_count; ++k) kind.ring = kind.ring || std::abs(mid - d.ring_centre_z(k)) < a / 2;
    layers.push_back({z[i], z[i + 1], level * std::max(1, static_cast<int>(std::ceil(h / kMaxBandHeight - 1e-9)))});
    kinds.push_back(kind);
  }
}

/// Element part of a section region in a band (−1: none), and whether the cell is chamber cavity.
int part_of_region(SectionRegion region, const BandKind& band, bool with_core) {
  switch (region) {
    case SectionRegion::chamber: return band.cap ? kTube : -1;
    case SectionRegion::tube: return kTube;
    case SectionRegion::ring_inner: return band.ring ? kRings : kTube;
    case SectionRegion::ring_outer: return band.ring ? kRings : (with_core ? kSheath : -1);
    case SectionRegion::core: return kSheath;
  }
  return -1;
}

Mesh mesh_actuators(const TcaDesign& design, int actuators, const SolidMeshOptions& options) {
  if (options.level < 1) throw std::logic_error("mesh level must be >= 1");
  const RraDesign& rra = design.actuator;
  const double a = rra.ring_count > 0 ? square_ring_side_mm(rra) : 0.0;
  const auto geometry = [&](double z) {
    SectionGeometry g;
    g.outer_radius = rra.outer_radius(z);
    g.wall_thickness = rra.wall_thickness_mm;
    g.ring_side = a;
    g.spacing = design.actuator_spacing_mm;
    g.sheath_thickness = design.sheath_thickness_mm;
    g.hole_radius = design.centre_hole_diameter_mm / 2;
    g.first_axis_angle = options.first_axis_angle_rad;
    return g;
  };
  const SectionGeometry reference = geometry(rra.length_mm / 2);
  // Without rings the ring band is a thin slice of wall; give it a nominal width.
  SectionGeometry ref = reference;
  const auto with_band = [&](SectionGeometry g) {
    if (g.ring_side <= 0) g.ring_side = 0.2 * g.wall_thickness;
    return g;
  };
  const ActuatorSection section(actuators, options.level, actuators == 3 && reference.hole_radius > 0, with_band(ref));

  std::vector<ExtrusionLayer> layers;
  std::vector<BandKind> kinds;
  actuator_bands(rra, a, options.level, layers, kinds);

  // Half models keep the quads on the y ≥ 0 side (y = 0 is made of element edges).
  const auto x_ref = section.positions(with_band(ref));
  std::vector<char> kept(section.num_quads(), 1);
  if (options.half)
    for (int q = 0; q < section.num_quads(); ++q) {
      double y = 0;
      for (int k = 0; k < 4; ++k) y += x_ref[section.quads()[q][k]].y() / 4;
      kept[q] = y > 0;
    }
  const bool with_core = actuators == 3;
  ExtrusionRules rules;
  rules.geometry = [&](double z) { return with_band(geometry(z)); };
  rules.part = [&](int q, int layer) {
    return kept[q] ? part_of_region(section.region(q), kinds[layer], with_core) : -1;
  };
  rules.cavity = [&](int q, int layer) {
    return kept[q] && section.region(q) == SectionRegion::chamber && !kinds[layer].cap ? section.actuator(q) : -1;
  };
  std::vector<Chamber> chambers;
  for (int i = 0; i < actuators; ++i) chambers.push_back({i + 1, "chamber " + std::to_string(i + 1), {}});
  std::vector<std::string> parts = {"tube", "rings"};
  if (with_core) parts.push_back("sheath");
  Mesh mesh = extrude_section(section, layers, rules, options.order, parts, chambers);
  if (options.half) mesh.node_sets["symmetry"] = mesh.node_sets["plane_y0"];
  mesh.node_sets.erase("plane_y0");
  return mesh;
}

}  // namespace

Mesh mesh_tca(const TcaDesign& design, const SolidMeshOptions& options) { return mesh_actuators(design, 3, options); }

Mesh mesh_rra_3d(const RraDesign& design, const SolidMeshOptions& options) {
  TcaDesign lone;
  lone.actuator = design;
  return mesh_actuators(lone, 1, options);
}

}  // namespace softarm::fem

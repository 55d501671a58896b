#include "fem/mesh/tca_mesher.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "fem/mesh/chamber_lids.hpp"
#include "fem/mesh/layered_extrusion.hpp"
#include "fem/mesh/serendipity_mesh.hpp"
#include "fem/mesh/spl_design.hpp"

namespace softarm::fem {
namespace {

enum Part { kTube = 0, kRings = 1, kSheath = 2 };

/// What an axial band of an actuator holds, decided at its mid-height.
struct BandKind {
  bool cap = false, ring = false;
};

constexpr double kMaxBandHeight = 4.0;  // mm: longer bands get more element layers (level 1)

/// Element layers through an axial band of height h at a level.
int band_divisions(double h, int level) {
  return level * std::max(1, static_cast<int>(std::ceil(h / kMaxBandHeight - 1e-9)));
}

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
    layers.push_back({z[i], z[i + 1], band_divisions(h, level)});
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

/// One piece of a stack along z: an actuator segment (3CA or lone RRA) or a solid connector.
struct StackPiece {
  const TcaDesign* segment = nullptr;  // null: connector
  double z0 = 0, z1 = 0;
  int first_chamber = 0;               // mesh chamber index of the segment's actuator 0
  int cell_ring = 0;                   // > 0: one ring pitch about this ring, a prism of its section
  double local_z0 = 0;                 // the segment's own height at z0: z1 − z0 short of its length
                                       // meshes a window of it (mesh_tca_end)
};

/// The bands of `layers` cut to [w0, w1], each cut band with its own layer count at `level`.
void clip_bands(double w0, double w1, int level, std::vector<ExtrusionLayer>& layers, std::vector<BandKind>& kinds) {
  std::vector<ExtrusionLayer> kept_layers;
  std::vector<BandKind> kept_kinds;
  for (std::size_t i = 0; i < layers.size(); ++i) {
    const double z0 = std::max(layers[i].z0, w0), z1 = std::min(layers[i].z1, w1);
    if (z1 - z0 <= 1e-9 * (w1 - w0)) continue;
    const bool cut = z0 != layers[i].z0 || z1 != layers[i].z1;
    kept_layers.push_back({z0, z1, cut ? band_divisions(z1 - z0, level) : layers[i].divisions});
    kept_kinds.push_back(kinds[i]);
  }
  layers = std::move(kept_layers);
  kinds = std::move(kept_kinds);
}

/// The bands of a ring-pitch cell: half a gap, the ring, half a gap, on z ∈ [0, pitch].
void cell_bands(const RraDesign& d, double a, int level, std::vector<ExtrusionLayer>& layers,
                std::vector<BandKind>& kinds) {
  const double p = d.pitch(), z[4] = {0.0, 0.5 * (p - a), 0.5 * (p + a), p};
  for (int i = 0; i < 3; ++i) {
    const double h = z[i + 1] - z[i];
    layers.push_back({z[i], z[i + 1], band_divisions(h, level)});
    kinds.push_back({false, i == 1});
  }
}

/// The section sizes of a segment at its local height.
SectionGeometry segment_geometry(const TcaDesign& design, double local_z, double first_axis_angle) {
  const RraDesign& rra = design.actuator;
  SectionGeometry g;
  g.outer_radius = rra.outer_radius(local_z);
  g.wall_thickness = rra.wall_thickness_mm;
  // Without rings the ring band is a thin slice of wall and core (one material each side).
  g.ring_side = rra.ring_count > 0 ? square_ring_side_mm(rra) : 0.2 * rra.wall_thickness_mm;
  g.spacing = design.actuator_spacing_mm;
  g.sheath_thickness = design.sheath_thickness_mm;
  g.hole_radius = design.centre_hole_diameter_mm / 2;
  g.first_axis_angle = first_axis_angle;
  return g;
}

SectionGeometry lerp(const SectionGeometry& a, const SectionGeometry& b, double t) {
  SectionGeometry g = a;
  const auto mix = [t](double p, double q) { return p + t * (q - p); };
  g.outer_radius = mix(a.outer_radius, b.outer_radius);
  g.wall_thickness = mix(a.wall_thickness, b.wall_thickness);
  g.ring_side = mix(a.ring_side, b.ring_side);
  g.spacing = mix(a.spacing, b.spacing);
  g.sheath_thickness = mix(a.sheath_thickness, b.sheath_thickness);
  g.hole_radius = mix(a.hole_radius, b.hole_radius);
  return g;
}

constexpr double kMaxConnectorLayer = 20.0;  // mm per element layer in a (stiff) connector at level 1

/// Every piece's section at its bottom and top: a segment's own (a cell's at its ring centre); a
/// connector takes the sections of the segments it joins, or at an end of the stack its one neighbour's.
void piece_end_sections(const std::vector<StackPiece>& pieces, double angle, std::vector<SectionGeometry>& bottom,
                        std::vector<SectionGeometry>& top) {
  bottom.assign(pieces.size(), {});
  top.assign(pieces.size(), {});
  for (std::size_t i = 0; i < pieces.size(); ++i)
    if (pieces[i].segment) {
      const auto& rra = pieces[i].segment->actuator;
      const int ring = pieces[i].cell_ring;
      bottom[i] = segment_geometry(*pieces[i].segment, ring > 0 ? rra.ring_centre_z(ring) : 0.0, angle);
      top[i] = segment_geometry(*pieces[i].segment, ring > 0 ? rra.ring_centre_z(ring) : rra.length_mm, angle);
    }
  for (std::size_t i = 0; i < pieces.size(); ++i)
    if (!pieces[i].segment) {
      if (i == 0 && pieces.size() == 1) throw std::logic_error("mesh_stack: a connector needs a segment");
      bottom[i] = i > 0 ? top[i - 1] : bottom[i + 1];
      top[i] = i + 1 < pieces.size() ? bottom[i + 1] : top[i - 1];
    }
}

/// The stack's element layers, bottom to top, each with its band (ring, gap, cap) and piece: a
/// segment's bands (a cell's, or the actuator's clipped to the piece), a connector's layers at most
/// kMaxConnectorLayer mm at level 1.
struct LayerKind {
  BandKind band;
  int piece = 0;
};
void stack_layers(const std::vector<StackPiece>& pieces, int axial_level, std::vector<ExtrusionLayer>& layers,
                  std::vector<LayerKind>& kinds) {
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const auto& p = pieces[i];
    if (!p.segment) {
      const int n = std::max(1, static_cast<int>(std::ceil((p.z1 - p.z0) / kMaxConnectorLayer - 1e-9)));
      layers.push_back({p.z0, p.z1, axial_level * n});
      kinds.push_back({{}, static_cast<int>(i)});
      continue;
    }
    std::vector<ExtrusionLayer> bands;
    std::vector<BandKind> band_kinds;
    const RraDesign& rra = p.segment->actuator;
    if (p.cell_ring > 0)
      cell_bands(rra, square_ring_side_mm(rra), axial_level, bands, band_kinds);
    else {
      actuator_bands(rra, rra.ring_count > 0 ? square_ring_side_mm(rra) : 0.0, axial_level, bands, band_kinds);
      clip_bands(p.local_z0, p.local_z0 + p.z1 - p.z0, axial_level, bands, band_kinds);
    }
    for (std::size_t b = 0; b < bands.size(); ++b) {
      layers.push_back({bands[b].z0 - p.local_z0 + p.z0, bands[b].z1 - p.local_z0 + p.z0, bands[b].divisions});
      kinds.push_back({band_kinds[b], static_cast<int>(i)});
    }
  }
}

/// The section's quads a model keeps: all, or for a half model those on the y ≥ 0 side (y = 0 is made
/// of element edges).
std::vector<char> kept_quads(const ActuatorSection& section, const SectionGeometry& reference, bool half) {
  std::vector<char> kept(section.num_quads(), 1);
  if (!half) return kept;
  const auto x_ref = section.positions(reference);
  for (int q = 0; q < section.num_quads(); ++q) {
    double y = 0;
    for (int k = 0; k < 4; ++k) y += x_ref[section.quads()[q][k]].y() / 4;
    kept[q] = y > 0;
  }
  return kept;
}

/// The mesh's part names: tube and rings, the sheath of a 3CA, a connector where the stack has one.
std::vector<std::string> stack_parts(const std::vector<StackPiece>& pieces, bool with_core) {
  std::vector<std::string> parts = {"tube", "rings"};
  if (with_core) parts.push_back("sheath");
  if (std::any_of(pieces.begin(), pieces.end(), [](const StackPiece& p) { return !p.segment; }))
    parts.push_back("connector");
  return parts;
}

/// Meshes a stack of segments and connectors, bottom to top. Connectors take the
/// sections of the segments they join (blended linearly through their thickness), so
/// every interface conforms; a connector at an end of the stack copies its one neighbour.
Mesh mesh_stack(const std::vector<StackPiece>& pieces, int actuators, int chamber_count, const SolidMeshOptions& options,
                const std::vector<std::string>& chamber_names) {
  if (options.level < 1 || options.axial_level < 0) throw std::logic_error("mesh level must be >= 1");
  const int axial_level = layers_level(options.level, options.axial_level);
  const double angle = options.first_axis_angle_rad;
  std::vector<SectionGeometry> bottom, top;
  piece_end_sections(pieces, angle, bottom, top);
  const auto geometry = [&](double z) {
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      const auto& p = pieces[i];
      if (z > p.z1 + 1e-9 * (1 + std::abs(p.z1)) && i + 1 < pieces.size()) continue;
      if (p.segment && p.cell_ring > 0)
        return segment_geometry(*p.segment, p.segment->actuator.ring_centre_z(p.cell_ring), angle);
      if (p.segment)
        return segment_geometry(*p.segment, std::clamp(z - p.z0 + p.local_z0, 0.0, p.segment->actuator.length_mm), angle);
      return lerp(bottom[i], top[i], std::clamp((z - p.z0) / (p.z1 - p.z0), 0.0, 1.0));
    }
    return top.back();
  };
  const SectionGeometry reference = geometry(0.5 * (pieces.front().z0 + pieces.front().z1));
  const ActuatorSection section(actuators, options.level, actuators == 3 && reference.hole_radius > 0, reference);
  std::vector<ExtrusionLayer> layers;
  std::vector<LayerKind> kinds;
  stack_layers(pieces, axial_level, layers, kinds);
  const std::vector<char> kept = kept_quads(section, reference, options.half);
  const bool with_core = actuators == 3;
  const int connector_part = with_core ? kSheath + 1 : kRings + 1;
  ExtrusionRules rules;
  rules.geometry = geometry;
  rules.part = [&](int q, int layer) {
    if (!kept[q]) return -1;
    if (!pieces[kinds[layer].piece].segment) return connector_part;
    return part_of_region(section.region(q), kinds[layer].band, with_core);
  };
  rules.cavity = [&](int q, int layer) {
    const auto& piece = pieces[kinds[layer].piece];
    return kept[q] && piece.segment && section.region(q) == SectionRegion::chamber && !kinds[layer].band.cap
               ? piece.first_chamber + section.actuator(q)
               : -1;
  };
  std::vector<Chamber> chambers;
  for (int i = 0; i < chamber_count; ++i) chambers.push_back({i + 1, chamber_names[i], {}, {}});
  Mesh mesh = extrude_section(section, layers, rules, options.order, stack_parts(pieces, with_core), chambers);
  if (options.half) mesh.node_sets["symmetry"] = mesh.node_sets["plane_y0"];
  mesh.node_sets.erase("plane_y0");
  if (options.serendipity && options.order == 2) return serendipity_from_triquadratic(mesh);
  return mesh;
}

std::vector<std::string> numbered_chambers(int count) {
  std::vector<std::string> names;
  for (int i = 1; i <= count; ++i) names.push_back("chamber " + std::to_string(i));
  return names;
}

}  // namespace

Mesh mesh_tca(const TcaDesign& design, const SolidMeshOptions& options) {
  return mesh_stack({{&design, 0.0, design.actuator.length_mm, 0}}, 3, 3, options, numbered_chambers(3));
}

Mesh mesh_tca_cell(const TcaDesign& design, int ring, const SolidMeshOptions& options) {
  const RraDesign& rra = design.actuator;
  if (ring < 1 || ring > rra.ring_count)
    throw std::logic_error("mesh_tca_cell: ring " + std::to_string(ring) + " outside 1.." + std::to_string(rra.ring_count));
  Mesh mesh = mesh_stack({{&design, 0.0, rra.pitch(), 0, ring}}, 3, 3, options, numbered_chambers(3));
  add_chamber_lids(mesh, mesh.node_sets.at("bottom"));
  add_chamber_lids(mesh, mesh.node_sets.at("top"));
  return mesh;
}

Mesh mesh_tca_end(const TcaDesign& design, TcaEnd end, int rings, const SolidMeshOptions& options) {
  const RraDesign& rra = design.actuator;
  if (rings < 1 || 2 * rings >= rra.ring_count)
    throw std::logic_error("mesh_tca_end: " + std::to_string(rings) + " rings at an end of a 3CA with " +
                           std::to_string(rra.ring_count) + " (needs more than twice as many)");
  const double l = rra.length_mm, h = rings * rra.pitch();
  const double z0 = end == TcaEnd::bottom ? 0.0 : l - h;
  Mesh mesh = mesh_stack({{&design, z0, z0 + h, 0, 0, z0}}, 3, 3, options, numbered_chambers(3));
  add_chamber_lids(mesh, mesh.node_sets.at(end == TcaEnd::bottom ? "top" : "bottom"));
  return mesh;
}

Mesh mesh_rra_3d(const RraDesign& design, const SolidMeshOptions& options) {
  TcaDesign lone;
  lone.actuator = design;
  return mesh_stack({{&lone, 0.0, design.length_mm, 0}}, 1, 1, options, numbered_chambers(1));
}

Mesh mesh_spl(const SplDesign& design, const SolidMeshOptions& options) {
  // Bottom to top: segment 3, connector 2–3, segment 2, connector 1–2, segment 1, shoulder connector.
  std::vector<StackPiece> pieces;
  for (int n = 3; n >= 1; --n) {
    const auto s = design.segment_extent(n);
    pieces.push_back({&design.segments[n - 1], s[0], s[1], 3 * (n - 1)});
    const auto c = design.connector_extent(n - 1);
    pieces.push_back({nullptr, c[0], c[1], 0});
  }
  Mesh mesh = mesh_stack(pieces, 3, 9, options, numbered_chambers(9));
  // The joints: each segment's end faces (node sets "segment_n_bottom" / "segment_n_top").
  const double tol = 1e-9 * design.total_length_mm();
  for (int n = 1; n <= 3; ++n) {
    const auto s = design.segment_extent(n);
    for (int k = 0; k < mesh.num_nodes(); ++k) {
      if (std::abs(mesh.X(k, 2) - s[0]) < tol) mesh.node_sets["segment_" + std::to_string(n) + "_bottom"].push_back(k);
      if (std::abs(mesh.X(k, 2) - s[1]) < tol) mesh.node_sets["segment_" + std::to_string(n) + "_top"].push_back(k);
    }
  }
  return mesh;
}

}  // namespace softarm::fem

#pragma once
// Axisymmetric bilinear-quad (Q1) mesh of a ring-reinforced actuator, in the
// (r, z) half-plane with z the axis (geometry: rra_design.hpp, spec §1).
//
// Parts: 0 "tube" (elastomer), 1 "rings" (ABS; present even without rings),
// bonded by shared nodes on the groove surfaces.
// Node sets: "axis" (r = 0), "bottom" (z = 0), "top" (z = l), "fixed_end" (top or
// bottom per design), "free_end_centre" (the one node at r = 0 on the free end face).
// Chamber 1 "chamber": 2-node edges chained from the axis along the bottom cap's
// inner face, up the chamber wall and back to the axis along the top cap's inner
// face, so that V = Σ π (z_b − z_a)(r_a² + r_a r_b + r_b²)/3 > 0 (mesh.hpp).
//
// Layout. The wall is one structured strip of "transversals" (mesh lines running
// from the chamber radius r_c(z) to the outer surface), split into blocks by key
// transversals at the tube ends, the cap faces z = t_c and l − t_c, and the lips
// of every groove; nodes inside a block are placed by transfinite interpolation.
// At a lip the tube has a convex 90° corner (the groove leaves the surface
// radially), so the lip transversal leaves it along the corner's bisector (45°
// on a straight tube) and bends back to radial; a straight radial one would
// make sliver elements that get worse with refinement. Under a groove the
// columns turn towards the chamber wall's normal, so a deep groove's thin
// remaining wall is crossed, not sheared. The caps' solid core (r ≤ r_c) is a
// structured block on the strip's inner line; each ring is an O-grid (a square
// core and an annulus) whose inner half shares the groove nodes.
//
// Square rings (RraDesign::RingSection::square) are meshed differently: every
// column is a straight line at constant z, bands follow the taper, and each
// ring is a structured block whose inner half shares the rectangular groove's
// nodes (build_square_wall); all edges are straight, so the mesh is exact.
//
// Checked (tests/test_rra_mesh.cpp, and a random search over 20,000 valid
// designs with tapers up to 6°, levels 1–3): every element has a positive
// Jacobian at its Gauss points. Tapers steeper than about 17° combined with
// nearly touching rings can still fold an element.
#include "fem/mesh/mesh.hpp"
#include "fem/mesh/rra_design.hpp"

namespace softarm::fem {

/// Element counts of mesh_rra at one level. Level 1 (f = 1):
///   element size h1 = t_w / w1 (w1 elements through the wall; 3 by default,
///   2 for biquadratic elements, which then have as many nodes through the wall); each wall block
///   between key transversals gets round(length / h1) ≥ 1 elements along z;
///   each groove semicircle 2q segments with q = max(2, ceil(π ρ / (2 h1))), so a
///   ring has 4q around and a q × q core; the ring annulus
///   max(1, round(0.29 q)) layers; each cap core round(r_c / h1) ≥ 1 layers.
/// Square rings instead: groove_layers = round((a/2) / h1) ≥ 1 through the groove
///   depth, as many through the ring's protruding half (ring_layers), round((t_w − a/2) / h1) ≥ 1
///   more under the groove (wall_layers counts both), max(2, round(a / h1)) groove_segments
///   along each groove (and its ring).
/// Level L multiplies every count by f = 2^(L − 1): element sizes halve per level.
struct RraMeshSizes {
  int refinement = 1;             // f
  double element_size_mm = 0;     // h1 / f
  int wall_layers = 0;            // through the wall
  int groove_segments = 0;        // along each groove semicircle (0 without rings)
  int ring_layers = 0;            // radial layers of the ring annulus (square: of the protruding half)
  int groove_layers = 0;          // square rings: layers through the groove depth a/2 (part of wall_layers)
  int core_layers_bottom = 0;     // radial layers of the bottom cap's core
  int core_layers_top = 0;
};
RraMeshSizes rra_mesh_sizes(const RraDesign& design, int level, int wall_layers_at_level_1 = 3);

/// Meshes a validated design at refinement `level` in [1, 10] (std::invalid_argument
/// otherwise). For the thesis RRA level 1 has about 900 elements; each level has
/// about four times as many. Throws InputError("geometry", ...) for the rare
/// designs whose blocks cannot be laid out (a chamber shorter than one groove segment).
Mesh mesh_rra(const RraDesign& design, int level, int wall_layers_at_level_1 = 3);

/// The same mesh promoted to 9-node quadrilaterals with the mid-edge nodes of
/// ring and groove edges on the true circles (so the rings' area error falls
/// from O(h²) to O(h⁴): 10 % → ~0.1 % at level 1). Default: 2 elements through
/// the wall at level 1 (5 nodes, as many as a 3-layer Q1 mesh has minus one).
Mesh mesh_rra_quadratic(const RraDesign& design, int level, int wall_layers_at_level_1 = 2);

}  // namespace softarm::fem

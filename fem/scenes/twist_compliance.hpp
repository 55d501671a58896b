#pragma once
// Torsion of a 3CA's pieces with their ends as they are held in an arm, at rest: the twist
// per unit torque between two faces, from the tangent at the undeformed state (linear).
//
// Why: the ring-pitch cell's GJ (tca_cell.hpp, cell_torsion_stiffness) is Saint-Venant's, the
// sections warping freely and alike in every pitch. Where a segment is bonded to a rigid
// connector its end face cannot warp, and the solid cap there (no chambers) is stiffer than a
// chambered pitch: a stubby segment (160 mm long, ~70 mm across on the thesis SPL) is stiffer in
// torsion than its cells say, and the arm's pose is most sensitive to torsion (GJ × 1.1 moves
// the thesis tip 16.5 mm: docs/cell-rod.md, What the rest is not; docs/cell-rod.md, Bonded ends
// in torsion).
//
// The faces' supports:
// - the held face: every node fixed (bonded to a body that does not turn);
// - the twisted face: turned rigidly about the axis (x = y = 0) in its plane, u = φ·(−Y, X), and
//   - warping free (its axial motion free): the cut of an end cell in the middle of a gap. A
//     mid-gap plane is a mirror plane of the ringed geometry, and a twist is odd under that
//     mirror, so there the periodic solution's in-plane motion is exactly a rigid turn and its
//     axial motion (the warping) is free;
//   - or warping held (axial motion zero): a face bonded to a rigid connector that turns.
// - on a half model (node set "symmetry", the plane y = 0 through chamber 1's axis): the plane
//   held in x and z and free across it. A twist is odd under that mirror, so the half model with
//   this support carries exactly half the full model's torque, for about a third of its cost.
// The torque is the reaction on the twisted face, T = Σ (X × f)_z over its nodes, f = K₀ u for the
// elastic tangent at rest K₀ and the linear response u to φ = 1 (exact for the tangent at rest);
// the compliance φ/T, rad per N·mm. NaN where the tangent at rest is not positive definite.
#include <string>
#include <vector>

#include "fem/materials/material.hpp"
#include "fem/mesh/mesh.hpp"
#include "fem/mesh/tca_mesher.hpp"
#include "fem/scenes/tca_scene.hpp"

namespace softarm::fem {

enum class TwistedFace { warping_free, warping_held };

/// The twist compliance (rad/(N·mm)) of `mesh` between node sets `held` and `twisted` (header).
double face_twist_compliance(const Mesh& mesh, const std::vector<Material>& part_materials,
                             ElementIntegration integration, const std::string& held, const std::string& twisted,
                             TwistedFace twisted_face);

/// A bonded end of spec's 3CA through its first `rings` rings (tca_end_cell.hpp's mesh; the half
/// model unless spec.allow_symmetry is off): the end face held, the cut twisted with its warping
/// free. The rod takes it over the end's length in place of its cells' 1/GJ (spatial_cell_rod.hpp,
/// SpatialEndTable).
double end_cell_twist_compliance(const TcaSceneSpec& spec, TcaEnd end, int rings);

/// The spatial cell rod's twist compliance (rad/(N·mm)) of spec's 3CA at rest, as it integrates
/// 1/GJ: on its cells' GJ (tca_cell.hpp; cells about cell_rod_rings, run once) for each entry 0 of
/// `end_rings`, and with both ends as bonded end cells through that many rings for each n > 0.
std::vector<double> tca_rod_twist_compliances(const TcaSceneSpec& spec, const std::vector<int>& end_rings);

/// spec's whole 3CA (the half model unless spec.allow_symmetry is off) bonded at both ends: the top face held, the bottom face on a
/// rigid connector that turns (warping held). The check of the rod's torsion with end cells.
double tca_twist_compliance(const TcaSceneSpec& spec);

}  // namespace softarm::fem

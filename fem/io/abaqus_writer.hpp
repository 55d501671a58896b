#pragma once
// Exports a scene as an Abaqus-format input deck that CalculiX (ccx 2.20)
// runs unchanged: nodes, elements by part, the same material cards, the
// boundary conditions, the chamber pressure as element-face loads, and
// displacement output of chosen node sets. It is softarm's bridge to an
// independent solver (shared/spec/calculix-notes.md):
//  - Ogden/Yeoh D_i = 0 ("no term" in Abaqus and softarm) are written as
//    1e30, because ccx silently replaces a zero by (0.1/μ0)^i;
//  - the axisymmetric Q2 element is written as CAX8 (its centre node is
//    dropped: CAX8 is the serendipity element of the same edges), Q1 as CAX4;
//    by default with reduced integration (CAX8R/CAX4R): fully integrated CAX8
//    locks on the near-incompressible silicone (thesis RRA, neo-Hookean, 20 kPa,
//    chord-edge meshes:
//    CAX8 7.22 mm, CAX8R 7.55 mm, softarm Q2/P1 7.69 mm at level 1; 7.49, 7.62,
//    7.65 mm at level 2);
//  - 3D: Hex20 is written as C3D20 as it is; Hex27 as C3D20 too (its six
//    face-centre nodes and body-centre node, VTK 20–26, are dropped: C3D20 is
//    the serendipity element of the same edges). VTK Hex27 nodes 0–19 are already in Abaqus C3D20 order: corners
//    0–7 = Abaqus 1–8 (bottom face counter-clockwise seen from the top, then
//    the top face), mid-edges 8–11 on (0,1), (1,2), (2,3), (3,0) = Abaqus 9–12,
//    12–15 on (4,5), (5,6), (6,7), (7,4) = 13–16, 16–19 on (0,4), (1,5), (2,6),
//    (3,7) = 17–20 (the node numbering figures of the Abaqus and ccx manuals).
//    Hex8 is written as C3D8R, or as C3D8I when reduced_integration is false:
//    fully integrated C3D8 locks on near-incompressible silicone (one cube
//    clamped at its base, neo-Hookean K/μ = 1000, pressure on its top face:
//    C3D8's top moves 63× less than C3D8I's and 28× less than C3D8R's), and
//    ccx 2.20 has no hybrid C3D8H ("unknown element type"); C3D8I
//    (incompatible modes, 2×2×2 points) is the fully integrated brick that
//    ccx offers with much less locking.
//    Chamber facets become element-face loads on the element whose face they
//    are (faces S1–S6: corners (1,2,3,4), (5,8,7,6), (1,5,6,2), (2,6,7,3),
//    (3,7,8,4), (4,8,5,1)), found by matching the facet's four corner nodes
//    and, where two elements share the face, picking the one the facet's
//    normal points into (the wall). A positive Pn pushes into the element
//    (checked on that cube), i.e. out of the cavity, as softarm's −p·V;
//  - gravity is a *DLOAD GRAV on every element with *DENSITY ρ·1e-9 t/mm³
//    (ρ in g/cm³) and magnitude 1000·|g| mm/s² (g in m/s²): the body force
//    1e-6 ρ|g| N/mm³ is that of softarm's gravity form (gravity_form.hpp).
//    *DENSITY is written only when gravity is on (a static step needs none;
//    this applies to axisymmetric decks too, which carried it before);
//  - linear (St Venant–Kirchhoff) parts become *ELASTIC under NLGEOM, which is
//    the same law.
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "fem/materials/material.hpp"
#include "fem/mesh/mesh.hpp"

namespace softarm::fem {

struct AbaqusDeck {
  std::string heading;
  const Mesh* mesh = nullptr;
  std::vector<Material> part_materials;        // indexed like mesh->part_names
  std::vector<std::string> clamped_node_sets;  // all displacement components fixed
  std::vector<std::string> axis_node_sets;     // u_r = 0 (axisymmetric symmetry axis; 2D only)
  // (node set, 1-based displacement component fixed to zero), e.g. {"symmetry", 2} for a plane y = const.
  std::vector<std::pair<std::string, int>> fixed_components;
  // Acceleration of gravity, m/s² (3D: x, y, z; axisymmetric meshes: not supported yet, must be zero).
  std::array<double, 3> gravity_m_s2{0.0, 0.0, 0.0};
  std::vector<double> chamber_pressure_MPa;    // per mesh chamber, applied over one *STATIC step
  std::vector<std::string> printed_node_sets;  // *NODE PRINT of U for these sets
  bool reduced_integration = true;
  double initial_increment = 0.05, min_increment = 1e-6, max_increment = 0.1;
};

/// Writes the deck; throws std::invalid_argument for meshes or laws it cannot express, and
/// for chamber facets that are no element's face.
void write_abaqus_deck(const std::string& path, const AbaqusDeck& deck);

}  // namespace softarm::fem

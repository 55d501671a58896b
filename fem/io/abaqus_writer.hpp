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
//  - linear (St Venant–Kirchhoff) parts become *ELASTIC under NLGEOM, which is
//    the same law.
#include <string>
#include <vector>

#include "fem/materials/material.hpp"
#include "fem/mesh/mesh.hpp"

namespace softarm::fem {

struct AbaqusDeck {
  std::string heading;
  const Mesh* mesh = nullptr;
  std::vector<Material> part_materials;        // indexed like mesh->part_names
  std::vector<std::string> clamped_node_sets;  // all displacement components fixed
  std::vector<std::string> axis_node_sets;     // u_r = 0 (axisymmetric symmetry axis)
  std::vector<double> chamber_pressure_MPa;    // per mesh chamber, applied over one *STATIC step
  std::vector<std::string> printed_node_sets;  // *NODE PRINT of U for these sets
  bool reduced_integration = true;
  double initial_increment = 0.05, min_increment = 1e-6, max_increment = 0.1;
};

/// Writes the deck; throws std::invalid_argument for meshes or laws it cannot express.
void write_abaqus_deck(const std::string& path, const AbaqusDeck& deck);

}  // namespace softarm::fem

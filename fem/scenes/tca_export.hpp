#pragma once
// The 3D actuator scenes as Abaqus-format decks for CalculiX (ccx 2.20), the
// independent cross-check of softarm's 3D models (shared/spec/calculix-notes.md):
//  - the three-chambered actuator (3CA) of tca_scene.hpp, on the mesh the scene
//    is solved on (tca_mesh: solver frame, half or full model);
//  - a lone RRA in 3D (mesh_rra_3d), chamber 1 pressurised.
// Both: the "top" face clamped, u_y = 0 on "symmetry" when the mesh is a half
// model (the nodes of "top" stay clamped in all components), and *NODE PRINT of
// U on "bottom", the free face z = 0. ccx prints only the nodes its elements use
// (C3D20 drops the Hex27 face and body centres): exported_nodes() gives exactly
// those, so that softarm's and ccx's free-face means are over the same nodes.
//
// The deck applies every load in one *STATIC step (pressure and gravity ramped
// together; softarm preloads gravity, then ramps the pressure: the end states
// agree for a hyperelastic body with a unique equilibrium path). ccx's pressure
// follows the faces but lacks the follower load stiffness, so keep the pressure
// below where ccx stalls (calculix-notes.md).
#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

#include "fem/assembly/energy_problem.hpp"
#include "fem/io/abaqus_writer.hpp"
#include "fem/mesh/mesh.hpp"
#include "fem/scenes/solid_scene_support.hpp"
#include "fem/scenes/tca_scene.hpp"

namespace softarm::fem {

/// The deck of a 3CA scene on `solver_frame_mesh` (tca_mesh(spec, model)):
/// chamber k at spec.chamber_pressure_kPa[k]·pressure_scale (only chambers that
/// have facets in the mesh), gravity spec.gravity_m_s2 rotated into the solver
/// frame, materials tca_part_materials(spec). The deck points at the mesh: keep
/// it alive until the deck is written.
AbaqusDeck tca_abaqus_deck(const TcaSceneSpec& spec, const Mesh& solver_frame_mesh, const ModelChoice& model,
                           double pressure_scale);

/// The deck of a lone 3D RRA (mesh_rra_3d, full or half): parts "tube", "rings",
/// chamber 1 at pressure_kPa, gravity (m/s², mesh frame) optional.
AbaqusDeck rra_3d_abaqus_deck(const Mesh& mesh, const Material& tube, const Material& rings, double pressure_kPa,
                              const Eigen::Vector3d& gravity_m_s2 = Eigen::Vector3d::Zero());

/// The constraints the decks express, for softarm: "top" clamped, u_y = 0 on
/// "symmetry" (when present): clamped_with_symmetry(mesh, "top"), as the 3CA scene.
DirichletConstraints actuator_3d_constraints(const Mesh& mesh);

/// The nodes of `nodes` that the deck writes (used by the C3D20/C3D8 elements:
/// the first 20 nodes of a Hex27, all 8 of a Hex8), sorted.
std::vector<int> exported_nodes(const Mesh& mesh, const std::vector<int>& nodes);

/// Mean of the displacement u (node-major, 3 per node) over `nodes`.
Eigen::Vector3d mean_displacement(const std::vector<int>& nodes, const Eigen::VectorXd& u);

/// The displacements in the last *NODE PRINT block of a ccx .dat file, by 0-based
/// node (ccx numbers = softarm's + 1). Empty when there is none.
std::map<int, Eigen::Vector3d> read_ccx_displacements(const std::string& dat_file);

/// Increments and Newton iterations of a finished ccx run, from its .sta file
/// (the converged increments' iteration counts; cut-back attempts are not listed
/// there, so they are not counted).
struct CcxStatistics {
  int increments = 0, iterations = 0;
  double reached_time = 0;  // step time of the last converged increment (1 = done)
};
CcxStatistics read_ccx_statistics(const std::string& sta_file);

}  // namespace softarm::fem

#pragma once
// The three-chambered actuator (3CA) bending scene (thesis §6.1): the top face
// clamped ("ENCASTRE"), chambers pressurised together from 0 to their peak
// pressures, optional gravity, quasi-static. Outputs along the path: bending
// angle (angle between the free face's mean normal now and at rest, spec §4),
// tip position (the free face's centroid), chamber volume, Newton iterations;
// at the end: peak principal stretch and stress per part.
//
// Model only what the scene requires: when the pressures and gravity are
// mirror-symmetric about the plane through the 3CA axis and one chamber's axis
// (p of the other two equal, gravity in that plane), the scene is solved on the
// half model with the symmetry plane constrained, which halves the unknowns and
// costs ~3× less to factorise; otherwise on the full model. The choice and its
// reason are part of the result.
//
// Frames: the user frame has the 3CA axis along z (top face z = l fixed, free
// face z = 0) and chamber 1's axis on +x (chamber k at (k − 1)·120°). The solver
// frame is rotated about z so that the mirror plane is y = 0; every reported
// position and vector is in the user frame.
#include <Eigen/Core>
#include <array>
#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "fem/forms/elastic_form.hpp"
#include "fem/materials/material.hpp"
#include "fem/mesh/mesh.hpp"
#include "fem/mesh/tca_design.hpp"
#include "fem/scenes/pressure_path.hpp"
#include "fem/scenes/solid_scene_support.hpp"

namespace softarm::fem {

struct TcaSceneSpec {
  TcaDesign design;
  Material tube_material, ring_material, sheath_material;
  int mesh_level = 1;
  int axial_level = 0;                                    // element layers along the axis as at this level; 0: mesh_level
  int element_order = 2;                                   // 1: Hex8/P0, 2: Hex27/P1 or Hex20/P1
  bool serendipity = false;                                // order 2: Hex20 instead of Hex27
  ElementIntegration integration = ElementIntegration::full;  // reduced: Hex20 at 2×2×2 points (C3D20R)
  std::array<double, 3> chamber_pressure_kPa{0, 0, 0};      // peak pressure of chambers 1–3, ramped together
  Eigen::Vector3d gravity_m_s2 = Eigen::Vector3d::Zero();   // user frame
  bool allow_symmetry = true;                               // false: always the full model
  std::vector<double> output_pressures_kPa;                 // of the most pressurised chamber; last = its peak
  double target_bending_deg = 90;                           // report the pressure that reaches it
  /// The cell rod (tca_cell.hpp) only: both ends through this many rings as 3D end cells
  /// (tca_end_cell.hpp) in place of rigid caps on the cells' κ₀ and λ₀; 0: rigid caps.
  int cell_rod_end_rings = 0;
  // 3D: no LU, factors reused, no iterating on an unstable branch, stiff parts rotated exactly (newton.hpp)
  NewtonSettings newton{.shift_indefinite_tangent = true, .reuse_factor = true, .max_indefinite_iterations = 4,
                        .rotate_stiff_parts = true};
  StepSettings steps;
  // 3D: volume control by CG, handed over only once a step past the last state has failed:
  // handed over ahead of the maximum, the thesis 3CA's free end cell took as long (56.6 s against
  // 53.6 s; bench_tca_cell --end-rings 2): volume control's CG from 310 kPa costs what pressure
  // control's failed tries did (LimitPointSettings::hand_over_after_failure).
  LimitPointSettings limit{.hand_over_ahead = false, .volume_control_by_cg = true};
  PathCheckpoint checkpoint;  // the whole 3CA's path only (not the cell rod's cells)
};

struct TcaState {
  double pressure_kPa = 0;             // of the most pressurised chamber
  double bending_angle_deg = 0;        // signed: > 0 away from the pressurised chambers
  Eigen::Vector3d tip_position_mm = Eigen::Vector3d::Zero();      // free face centroid
  Eigen::Vector3d tip_displacement_mm = Eigen::Vector3d::Zero();
  double chamber_volume_mm3 = 0;       // Σ f_i V_i over the loaded chambers (full model)
  int newton_iterations = 0;
  bool is_output = false;
};

struct SceneTimings {
  double mesh_s = 0, setup_s = 0, solve_s = 0, total_s = 0, assembly_s = 0;
  double factorize_s = 0;
  int factorizations = 0;
};

struct TcaResult {
  Mesh mesh;                          // in the user frame (the half model's half when half)
  ModelChoice model;
  std::string element_name;
  int dofs = 0;
  std::vector<TcaState> states;       // every converged state, rest included
  std::vector<TcaState> curve;        // the requested outputs (and the last state reached)
  PressurePathResult path;
  std::optional<double> target_pressure_kPa;   // where the bending angle reaches the target
  std::vector<PartPeak> final_peaks;  // at the last state reached
  std::vector<std::pair<std::string, double>> part_mass_kg;  // full body
  double mass_kg = 0;
  Vector final_positions;             // user frame
  std::vector<Vector> curve_positions;  // user frame, at each curve state (deformed.pvd's frames)
  std::vector<ElementResult> final_element_results;
  SceneTimings timings;
};

using TcaProgress = std::function<void(const TcaState&)>;

/// The model a spec will be solved on (no solve).
ModelChoice choose_tca_model(const TcaSceneSpec& spec);

/// The mesh the scene is solved on, in the solver frame of `model` (half or full),
/// and the material of each of its parts ("tube", "rings", "sheath").
Mesh tca_mesh(const TcaSceneSpec& spec, const ModelChoice& model);
/// The mesh options for spec's pieces twisted at rest: the half model y ≥ 0 with chamber 1 on its
/// mirror plane (a twist is odd under that mirror, antisymmetric_plane_dofs; turning the geometry
/// about its axis leaves its torsion as it is), the full model where spec.allow_symmetry is off.
SolidMeshOptions tca_twist_mesh_options(const TcaSceneSpec& spec);
std::vector<Material> tca_part_materials(const TcaSceneSpec& spec);
/// The side the 3CA bends to under its chamber pressures, user frame (unnormalised; zero when
/// no chamber or all alike are pressurised): away from them, −Σ p_k e_k with e_k chamber k's
/// axis direction at (k − 1)·120°.
Eigen::Vector3d tca_bend_direction(const std::array<double, 3>& chamber_pressure_kPa);

/// Gravity in the solver frame of `model`.
Eigen::Vector3d tca_solver_gravity(const TcaSceneSpec& spec, const ModelChoice& model);

/// The pressure ramp of a 3CA model (the whole 3CA, a ring-pitch cell, an end cell): `chambers` to
/// their peaks with the spec's outputs and solver settings; `dead_loads_first` applies gravity or a
/// cell's end loads (LoadState::gravity_scale) before it; `node_dimension` 3 for the mesh's nodes, 0
/// where the unknowns include a face pilot that is not one (the cells).
PressurePathSpec tca_pressure_path(const TcaSceneSpec& spec, const ChamberLoads& chambers, bool dead_loads_first,
                                   int node_dimension);

TcaResult run_tca_scene(const TcaSceneSpec& spec, const TcaProgress& progress = {});

/// The pressure at which the states' bending angle first reaches `angle_deg`
/// (quadratic interpolation through the neighbouring states), if it does.
std::optional<double> pressure_at_bending(const std::vector<TcaState>& states, double angle_deg);

}  // namespace softarm::fem

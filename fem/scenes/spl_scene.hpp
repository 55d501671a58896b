#pragma once
// The Soft Poly-Limb (SPL) pose scene (thesis §7): the shoulder connector's
// top face clamped, any pressure per chamber (1–9, ramped together from 0 to
// their peaks), gravity in any direction, an optional payload carried by the tip
// face. Outputs: tip position and tilt along the path; at the end the position
// and orientation of every segment joint and of the tip, mass per part, peak
// principal stretch and stress per part.
//
// Frames as in tca_scene.hpp: z along the arm (tip at z = 0, shoulder at z = L,
// hanging when gravity is −z), chamber 1 (and 4, 7) of every segment on +x. A
// half model is used only when every segment's pressures and gravity share a
// mirror plane (solid_scene_support.hpp); the thesis pose does not.
#include <Eigen/Core>
#include <array>
#include <functional>
#include <vector>

#include "fem/materials/material.hpp"
#include "fem/mesh/spl_design.hpp"
#include "fem/scenes/pressure_path.hpp"
#include "fem/scenes/solid_scene_support.hpp"
#include "fem/scenes/tca_scene.hpp"

namespace softarm::fem {

struct SplSceneSpec {
  SplDesign design;
  Material tube_material, ring_material, sheath_material, connector_material;
  int mesh_level = 1;
  int axial_level = 0;                                    // element layers along the axis as at this level; 0: mesh_level
  int element_order = 2;                                  // 1: Hex8/P0, 2: Hex27/P1 or Hex20/P1
  bool serendipity = false;                               // order 2: Hex20 instead of Hex27
  ElementIntegration integration = ElementIntegration::full;  // reduced: Hex20 at 2×2×2 points (C3D20R)
  std::array<double, 9> chamber_pressure_kPa{};          // peaks, ramped together
  Eigen::Vector3d gravity_m_s2{0, 0, -9.80665};           // user frame; hanging arm by default
  double tip_mass_kg = 0;
  bool allow_symmetry = true;
  std::vector<double> output_levels;                      // fractions of the peaks; last = 1
  // 3D: no LU, factors reused, no iterating on an unstable branch, stiff parts rotated exactly (newton.hpp)
  NewtonSettings newton{.shift_indefinite_tangent = true, .reuse_factor = true, .max_indefinite_iterations = 4,
                        .rotate_stiff_parts = true};
  StepSettings steps;
  // 3D: volume control by CG, handed over only once a step past the last state has failed:
  // handed over ahead of the maximum, the thesis 3CA's free end cell took as long (56.6 s against
  // 53.6 s; bench_tca_cell --end-rings 2): volume control's CG from 310 kPa costs what pressure
  // control's failed tries did (LimitPointSettings::hand_over_after_failure).
  LimitPointSettings limit{.hand_over_ahead = false, .volume_control_by_cg = true};
  PathCheckpoint checkpoint;  // the 3D model's path only (not the cell rod's cells)
};

struct SplJoint {
  std::string name;       // "segment 1 top (shoulder)", …, "tip"
  FacePose pose;          // user frame
};

struct SplState {
  double load_fraction = 0;
  Eigen::Vector3d tip_position_mm = Eigen::Vector3d::Zero();
  double tip_tilt_deg = 0;
  int newton_iterations = 0;
  std::vector<Eigen::Vector3d> centreline_mm;  // the rods' nodes from the shoulder to the tip (empty for the FEM)
};

struct SplResult {
  Mesh mesh;                          // user frame
  ModelChoice model;
  std::string element_name;
  int dofs = 0;
  std::vector<SplState> curve;        // at the requested output levels (and the last state reached)
  std::vector<SplJoint> joints;       // at the last state reached: each segment's top and bottom, then the tip
  PressurePathResult path;
  std::vector<PartPeak> final_peaks;
  std::vector<std::pair<std::string, double>> part_mass_kg;
  double mass_kg = 0;                 // arm without payload
  Vector final_positions;
  std::vector<Vector> curve_positions;  // user frame, at each curve state (deformed.pvd's frames)
  std::vector<ElementResult> final_element_results;
  SceneTimings timings;
};

ModelChoice choose_spl_model(const SplSceneSpec& spec);
SplResult run_spl_scene(const SplSceneSpec& spec, const std::function<void(const SplState&)>& progress = {});

}  // namespace softarm::fem

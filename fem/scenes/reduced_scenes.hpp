#pragma once
// The reduced model of the rra and tca scenes (the cheapest rung of the
// fidelity ladder, fem/scenes/fidelity.hpp): the same scene specs as the FEM
// runners, answered by the rods of arm_rod.hpp (planar) and spatial_rod.hpp.
//   rra: the lone RRA's extension by the rod with an uncalibrated chamber force
//        (the FEM-calibrated factor needs the FEM itself; docs/reduced-model.md,
//        Calibration on the lone RRA);
//   tca: the 3CA as one rod piece, top clamped: by the planar rod where the
//        loads lie in the x–z plane (chambers 2 and 3 at equal pressure, gravity
//        with no y part: the measured rung of the fidelity ladder), by the
//        spatial rod otherwise;
//   spl: the arm as the spatial rod of spatial_rod.hpp (any pressures, gravity
//        in any direction, a tip mass): the tip's path and every joint's pose.
#include <string>
#include <vector>

#include "fem/reduced/arm_rod.hpp"
#include "fem/reduced/spatial_rod.hpp"
#include "fem/scenes/rra_scene.hpp"
#include "fem/scenes/spl_scene.hpp"
#include "fem/scenes/tca_scene.hpp"

namespace softarm::fem {

struct ReducedRraResult {
  std::vector<double> pressure_kPa, extension_mm;  // at the scene's output pressures
  double seconds = 0;
};
ReducedRraResult run_reduced_rra(const RraSceneSpec& spec);

struct ReducedTcaResult {
  std::vector<double> pressure_kPa, bending_deg;  // every continuation step, rest excluded
  std::optional<double> target_pressure_kPa;      // where the bending reaches spec.target_bending_deg
  bool converged = false;                         // false: the path stopped short, and `diagnosis` says why
  std::string diagnosis;
  bool spatial = false;                           // solved by the spatial rod (loads out of the x–z plane)
  /// The centreline at the final state, per node, mm: the clamp at the origin, the scene's axes
  /// (the 3CA hangs along −z at rest; y = 0 for the planar rod).
  std::vector<Eigen::Vector3d> centreline_mm;
  PieceExtremes extremes;                         // fibre extremes at the final state
  std::vector<double> arc_length_mm;             // reference arc length per node, from the clamp
  double mass_kg = 0, seconds = 0;
  int nodes = 0;
};
/// `nodes`: rod nodes along the 3CA (17 by default: converged to 0.1 % on the thesis 3CA; the node
/// count's convergence is test [reduced], docs/testing.md, The design job).
ReducedTcaResult run_reduced_tca(const TcaSceneSpec& spec, int nodes = 17);

struct ReducedSplResult {
  std::vector<SplState> curve;          // every continuation step of the pressures (load fraction, tip, tilt)
  std::vector<SplJoint> joints;         // at the final state, named and ordered as the FEM's
  SpatialRodState final_state;          // converged=false: the path stopped (diagnosis inside)
  std::array<PieceExtremes, 3> segment_extremes;  // fibre extremes per segment at the final state
  RodPartMasses part_masses;
  double mass_kg = 0, seconds = 0;
  int nodes = 0;
};
/// `nodes_per_segment`: rod nodes along each 3CA segment; `cells`: cells across each section
/// (the defaults put the thesis pose within 0.1 % of the finest; docs/reduced-model.md, The SPL
/// pose by the spatial rod).
ReducedSplResult run_reduced_spl(const SplSceneSpec& spec, int nodes_per_segment = 17, int cells = 24);

}  // namespace softarm::fem

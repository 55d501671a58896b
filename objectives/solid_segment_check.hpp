#pragma once
// The ladder's last rung for a design (issue 6: "search on a cheap level, check on
// an accurate one, report the final design's error"): one segment of an arm
// candidate bent by the 3D FEM exactly as the search's rod bends it (chambers 2
// and 3 at the working pressure, gravity against the bend, top face clamped), so
// the rod's bending of that segment can be compared with the 3D model's.
//
// Two models (SolidCheckModel; the design config's check.solid_model):
// - the cell rod (the default): ring-pitch cells of the segment, Hex20/P1 at 27 points with level
//   4's element layers, under a planar rod (fem/scenes/tca_cell.hpp). Against the fidelity ladder's
//   reference mesh (the whole segment, Hex20/P1 with level 4's layers) it is within 3.0 % along the
//   thesis 3CA's curve and within 3.3 % along the main job's round-0 optimum's; on round 1's (Dragon
//   Skin 20, thin rings) +7.9 % at the working pressure and −12 % below it (docs/cell-rod.md, On other
//   designs; with chord lids: docs/cell-rod.md, Experiments not adopted);
// - the whole segment in 3D, Hex20/P1 at 2×2×2 Gauss points, mesh level 1, half model: within 0.85 %
//   of the reference on the thesis 3CA by two level-1 errors cancelling, but 17 % short and ballooning
//   early on the round-0 optimum, whose walls are thinner, and 16 % short on round 1's.
// A limit point (ballooning) before the working pressure is a result: the check reports the bending
// at the largest pressure reached and says so.
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "fem/scenes/pressure_path.hpp"
#include "fem/scenes/tca_scene.hpp"
#include "objectives/arm_evaluation.hpp"

namespace softarm::objectives {

struct SolidSegmentCheck {
  int segment = 0;                         // 1 (proximal) … 3 (distal)
  std::string element;                     // the 3D element used
  int dofs = 0;
  double reached_pressure_kPa = 0;         // the working pressure, or a limit point below it
  std::string outcome;                     // "completed", or the path's diagnosis
  double bending_deg = 0;                  // at the reached pressure, 3D
  double rod_bending_deg = 0;              // the search model's, at the same pressure
  std::optional<double> pressure_for_target_kPa;      // 3D; none if not reached
  std::optional<double> rod_pressure_for_target_kPa;  // the search model's
  fem::PathOutcome path = fem::PathOutcome::completed;  // completed: the working pressure was reached
  double seconds = 0;
  /// Rod minus 3D bending at the reached pressure, relative to the 3D one.
  double bending_error_percent() const;
  /// The 3D model's verdict on the two requirements it can judge: the target bending at or
  /// below the working pressure, and the working pressure held without a limit point.
  bool meets_bending() const { return pressure_for_target_kPa.has_value(); }
  bool holds_working_pressure() const { return path == fem::PathOutcome::completed; }
  /// "held", "NOT held (ballooning limit point at … kPa)" or "not established (… stalled at … kPa)".
  std::string working_pressure_verdict() const;
};

/// Every field as JSON (the unset optional pressures as null), and back: exactly, so that a
/// resumed design run (engine/design/design_checkpoint.hpp) reads the check it wrote.
nlohmann::json to_json(const SolidSegmentCheck& check);
SolidSegmentCheck solid_check_from_json(const nlohmann::json& j);

/// A segment's bending by the search model at pressure p: linear between its path's steps,
/// the last step's beyond them.
double bending_at_pressure(const SegmentMeasures& rod, double p_kPa);

/// The check's 3D model of segment `segment` (1–3) of `candidate`: its design and materials on
/// Hex20/P1 at 2×2×2 points, mesh `mesh_level`, with no load yet.
fem::TcaSceneSpec solid_segment_scene(const ArmCandidate& candidate, int segment, int mesh_level = 1);

/// The path settings of every 3D check of a design (as configs/tca_thesis.json): a small first step
/// (gravity preload, then the ramp), give up at 1e-3 of the load, chamber-volume control at any stall
/// to trace a ballooning limit point.
void use_design_check_path(fem::StepSettings& steps, fem::LimitPointSettings& limit);

/// The model a check bends its segment by.
enum class SolidCheckModel {
  cell_rod,      // the cell rod (fem/scenes/tca_cell.hpp): ring-pitch cells of Hex20/P1 at 27 points with
                 // level 4's layers, the fidelity ladder's rung; within 3.3 % of the ladder's reference mesh on
                 // the thesis 3CA and on the main job's round-0 optimum (docs/cell-rod.md, On other designs)
  hex20_reduced  // the whole segment in 3D, Hex20/P1 at 2×2×2 points, level 1 (solid_segment_scene)
};

/// Bends segment `segment` (1–3) of `candidate` by the 3D FEM under the load of `settings`
/// (working pressure, gravity, target bending, output steps) and compares it with `rod`, that
/// segment's measures by the search's rod (ArmMeasures::segments[segment − 1]). `mesh_level` ≥ 1.
/// Throws fem::InputError for a design that cannot be meshed.
/// `progress` (optional) is called with (pressure kPa, bending deg) at every output as the path goes.
SolidSegmentCheck check_segment_in_3d(const ArmCandidate& candidate, const EvaluationSettings& settings, int segment,
                                      const SegmentMeasures& rod, int mesh_level = 1,
                                      const std::function<void(double, double)>& progress = {},
                                      SolidCheckModel model = SolidCheckModel::hex20_reduced);

}  // namespace softarm::objectives

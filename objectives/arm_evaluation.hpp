#pragma once
// Turns an arm design into the numbers the requirements speak of (spec §3,
// definitions §4), at the reduced model's fidelity: the finite-strain rod of
// fem/reduced for bending, pose and payload; the axisymmetric FEM of each
// segment's RRA for what the rod cannot see (local peaks at the groove lips,
// a ballooning limit point). The 3D FEM is the check (issue 3;
// docs/design-on-the-accurate-model.md).
//
// Scenes (our definitions, overridable in the requirements config):
// - bending per segment: each 3CA alone, top clamped, chambers 2 and 3 at the
//   working pressure, gravity perpendicular to the axis and against the bend
//   (the thesis' 3CA test); the angle between the end faces;
// - payload: the whole arm hanging from the shoulder (gravity along its axis),
//   chambers 2 and 3 of every segment together; the largest tip mass it lifts
//   to horizontal at or below the working pressure (payload_capacity.hpp);
// - burst (safe working pressure, spec §4): along each segment's bending path
//   the actuator's stretch at the pressurised chambers' axes is mapped, through
//   the lone RRA's FEM path, to the local peak principal stretch and Cauchy
//   stress; (a) stress ≥ strength / SF, (b) stretch ≥ (1 + elongation at
//   break) / SF, (c) a limit point of the rod path or of the lone RRA's FEM
//   path: the first pressure where one holds is the safe working pressure;
// - durability proxy: the peak principal log strain at the working pressure
//   (same mapping), against the thesis RRA's at 206.8 kPa, which lasted 1.1 M
//   cycles (spec §1): ε ≤ ε_ref is the requirement's evidence.
#include <array>
#include <string>
#include <vector>

#include "fem/core/thesis_values.hpp"
#include "fem/mesh/spl_design.hpp"
#include "fem/reduced/arm_rod.hpp"
#include "fem/scenes/rra_calibration.hpp"

namespace softarm::objectives {

struct ArmCandidate {
  fem::SplDesign design;
  fem::Material tube, sheath, rings, connector;
};

struct EvaluationSettings {
  double working_pressure_kPa = fem::thesis::kWorkingPressure_kPa;  // supply pressure: the chambers' maximum
  double target_bending_deg = 90;       // per segment
  double lift_angle_deg = 90;           // payload: tip tangent from vertical
  double lift_reach_fraction = 0.25;    // payload: held out at least this share of the arm's length
  double rra_extension_pressure_kPa = fem::thesis::kRraTestPressure_kPa;  // the lone RRA's extension is reported here
  double safety_factor = 1.5;           // burst criteria (a), (b)
  double peak_averaging_radius_mm = fem::kDefaultPeakAveragingRadius_mm;  // the peaks (a), (b) and durability read
  int rra_mesh_level = 1;               // axisymmetric FEM of each segment's RRA
  int pressure_steps = 12;              // rod continuation steps to the working pressure
  int rod_nodes_per_segment = 17;
  bool ring_confinement = false;        // the rod's 3CA sections: rings hold the tube wall (fem/reduced/confined_wall.hpp)
  double gravity_m_s2 = 9.80665;
  bool operator==(const EvaluationSettings&) const = default;  // the same model, field by field
};

struct SegmentMeasures {
  std::vector<double> pressure_kPa, bending_deg;  // the bending path
  double bending_deg_at_working = 0;
  double pressure_for_target_kPa = -1;  // < 0: not reached at the working pressure
  double chamber_stretch = 1;           // at the working pressure
  fem::RraCalibration::Peaks peaks;     // local peaks at the working pressure
  double burst_utilisation = 0;         // max over (a), (b) of measure / allowable at the working pressure
  double safe_pressure_kPa = -1;        // first pressure where a criterion holds (< 0: none up to the working pressure)
  std::string governing;                // "stress", "stretch", "limit point (rod)", "limit point (RRA FEM)" or ""
  std::string rod_diagnosis;            // empty when the path completed
  double rra_fem_extension_mm = 0, rra_rod_extension_mm = 0, rra_pressure_kPa = 0;  // model-error evidence
  double rra_extension_mm = 0;  // the lone RRA at rra_extension_pressure_kPa: rod with the FEM-calibrated force
                                // (an RRA that balloons below it: the FEM's extension at rra_pressure_kPa)
};

struct ArmMeasures {
  double mass_kg = 0, length_mm = 0;
  fem::ArmRod::PartMasses masses;
  double payload_kg = 0;
  std::string payload_note;               // what limits a heavier payload
  double payload_lift_pressure_kPa = 0;    // pressure at which the capacity is lifted to horizontal
  std::vector<double> payload_tip_x_mm, payload_tip_z_mm;  // arm shape at the payload capacity
  std::array<SegmentMeasures, 3> segments;
  double min_bending_deg = 0, burst_utilisation = 0, durability_log_strain = 0;
  double safe_pressure_kPa = -1;
  std::string burst_governing;
  double seconds = 0;
};

/// The rod of the whole arm (shoulder connector first) or of one segment.
fem::ArmRod arm_rod(const ArmCandidate& c, const EvaluationSettings& s);
fem::ArmRod segment_rod(const ArmCandidate& c, const EvaluationSettings& s, int segment);

/// Segment n's (0..2) lone RRA by the axisymmetric FEM, far enough to cover the axial stretch
/// `stretch` its actuators reach in the 3CA (with a 25 % margin on the strain): the map from an
/// actuator's mean stretch to its local peaks (RraCalibration::peaks_at).
fem::RraCalibration segment_rra_fem(const ArmCandidate& c, const EvaluationSettings& s, int n, double stretch);

/// The burst criteria (a), (b), (c) and the durability strain along a segment's path: `out` holds
/// the path (pressure_kPa, and rod_diagnosis where it stopped short), `chamber_stretch` the largest
/// pressurised-chamber stretch at each of its pressures; fills chamber_stretch, peaks,
/// burst_utilisation, safe_pressure_kPa, governing and the lone RRA's extensions. A path that stopped
/// short counts as a limit point at its last pressure ("limit point (rod)").
void judge_segment(SegmentMeasures& out, const std::vector<double>& chamber_stretch, const ArmCandidate& c,
                   const EvaluationSettings& s, int n, const fem::RraCalibration& calibration);

/// Folds a segment's measures into the arm's (min_bending_deg starts at +∞): the least bending, the
/// largest burst utilisation and what governs it, the lowest safe pressure, the largest peak strain.
void add_segment(ArmMeasures& arm, const SegmentMeasures& segment);

/// Evaluates every measure. Throws fem::InputError for a design that cannot be built.
ArmMeasures evaluate_arm(const ArmCandidate& candidate, const EvaluationSettings& settings);

/// The durability reference: peak principal log strain of the thesis RRA (Table 7)
/// at `pressure_kPa` in the axisymmetric FEM at `mesh_level`, averaged over a ball of
/// `averaging_radius_mm` (the same model and definition the designs are measured with).
double durability_reference_log_strain(double pressure_kPa, int mesh_level, double averaging_radius_mm);

}  // namespace softarm::objectives

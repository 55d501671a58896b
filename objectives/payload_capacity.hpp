#pragma once
// Payload capacity (spec §4, our reading): the largest tip mass that the arm,
// hanging from its shoulder (gravity along its axis), lifts to horizontal with
// its chambers at or below the working pressure. "Lifts to horizontal":
//   - the tip tangent reaches `lift_angle_deg` from vertical at some pressure
//     p* ≤ p_w (chambers 2 and 3 of every segment together; the bend is planar),
//     taking the first such pressure on the way up;
//   - there, the payload is held out at a horizontal reach of at least
//     `reach_fraction` of the arm's length, and the sheath (which carries the
//     payload's tension) stays within burst criterion (b).
// Both extra conditions rule out a degenerate reading: a tip load's moment
// vanishes at the tip, so under a very heavy mass the pressure still curls the
// tip's last centimetres to 90° while the mass hangs below the shoulder. The
// thesis arm at its measured 0.3 kg holds the mass out at half its length.
//
// Method: continuation in the tip mass along the lift state (p*(m), shape):
// each mass step starts from the last state, the pressure is corrected by the
// secant method until the tip is at the lift angle; steps that turn the shape
// by more than 10° are halved (no jumping to another equilibrium branch). The
// first mass whose lift fails (p* > p_w, too short a reach, the sheath, or no
// nearby equilibrium: a fold) brackets the capacity; bisection refines it.
#include <string>
#include <vector>

#include "fem/core/thesis_values.hpp"
#include "fem/reduced/arm_rod.hpp"

namespace softarm::objectives {

struct PayloadSettings {
  double working_pressure_kPa = fem::thesis::kWorkingPressure_kPa;
  double lift_angle_deg = 90;
  double reach_fraction = 0.25;
  double sheath_allowable_stretch = 1e300;  // (1 + elongation at break) / SF of the sheath
  double gravity_m_s2 = 9.80665;
  int pressure_steps = 12;
};

struct PayloadResult {
  double capacity_kg = 0;        // < 0: the unloaded arm cannot lift its tip (extrapolated deficit)
  double lift_pressure_kPa = 0;  // p* at the capacity
  std::string limited_by;        // what stops a heavier mass
  std::vector<double> x_mm, z_mm;  // the arm's shape at the capacity
  int rod_solves = 0;
};

/// `arm` must be the whole arm, pieces {connector, segment 1, connector, segment 2, connector, segment 3}.
PayloadResult payload_capacity(const fem::ArmRod& arm, const PayloadSettings& settings);

}  // namespace softarm::objectives

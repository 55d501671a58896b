#pragma once
// One converged state of a pressure path (fem/scenes/pressure_path.hpp): what the path reports and
// what its log (path_log.hpp) keeps beside the positions.

namespace softarm::fem {

struct PressureState {
  double pressure_kPa = 0.0;
  double chamber_volume_mm3 = 0.0;         // Σ f_i V_i over the loaded chambers
  double pv_stiffness_kPa_per_mm3 = 0.0;   // dp/dV at this state
  bool tangent_positive_definite = true;
  int newton_iterations = 0;
  bool is_output = false;
};

}  // namespace softarm::fem

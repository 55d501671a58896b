#pragma once
// Calibration of the reduced model against the axisymmetric FEM, once per RRA
// design (issue 6: "cross-section properties computed or calibrated once per
// design from the FEM rather than guessed").
//
// The rod model's section sees the chamber pressure as the axial force p·A_c of
// the undeformed chamber. The real RRA also bulges between its rings, its wall
// is thinned by the grooves and stretched by the pressure: the lone RRA's FEM
// extension exceeds the rod's (thesis RRA, 206.8 kPa: FEM 76.7 mm). The factor
// c(p) on the pressure force makes the rod's lone-RRA extension equal to the
// FEM's at every output pressure of the FEM path; the 3CA and SPL rods use the
// same c(p) for the same actuator.
//
// The FEM path also maps the actuator's mean axial stretch λ̄ = 1 + extension/l
// to the peaks the rod cannot see (principal stretch, log strain and Cauchy
// stress at the groove lips): the rod's stretch at a chamber's axis, looked up
// in that map, gives the local peaks for the burst and durability criteria.
#include <string>
#include <vector>

#include "fem/reduced/arm_rod.hpp"
#include "fem/scenes/rra_scene.hpp"

namespace softarm::fem {

struct RraCalibration {
  ForceFactor force_factor;
  std::vector<double> pressure_kPa, fem_extension_mm, rod_extension_mm;  // rod_extension: uncalibrated (c = 1)
  std::vector<double> mean_stretch, peak_stretch, peak_log_strain, peak_stress_MPa;  // averaged (RraCurvePoint::averaged)
  std::vector<double> point_stretch;  // the single Gauss point's (the groove lip's): where the law is most extrapolated
  bool limit_point = false;       // the FEM path met a limit point (ballooning)
  double last_pressure_kPa = 0;   // highest pressure the FEM path reached
  std::string outcome;            // the FEM path's outcome, in words
  double fem_seconds = 0;
  int dofs = 0;

  struct Peaks {
    double stretch = 1, log_strain = 0, stress_MPa = 0;  // averaged over the ball (the criteria's)
    double point_stretch = 1;                            // at one Gauss point, the groove lip
    bool extrapolated = false;  // λ̄ beyond the FEM path's last state
  };
  /// The FEM's local peaks at the mean axial stretch λ̄ (piecewise linear; linear extrapolation beyond).
  Peaks peaks_at(double mean_stretch) const;
};

/// Runs the RRA FEM scene and fits c(p) at its output pressures.
RraCalibration calibrate_rra(const RraSceneSpec& fem_spec);

/// calibrate_rra on `spec` (its design, materials, mesh and averaging radius; its path replaced) with
/// the lone RRA's path far enough to cover the mean axial stretch `stretch` its actuators reach in a
/// 3CA, with a 25 % margin on the strain: up to the pressure at which the uncalibrated rod extends the
/// lone RRA that far (bisection; the rod extends less than the FEM, so the FEM covers the stretch),
/// at most `max_pressure_kPa` and at least 5 % of it, outputs every eighth of it. The free RRA
/// stretches far more than an embedded one at the same pressure (thesis RRA: λ̄ = 1.40 at 172 kPa,
/// while the 3CA's chambers reach 1.42 at 344.7 kPa), so the path stops well below the working
/// pressure, where a thin-walled free RRA would balloon for reasons the 3CA does not share.
RraCalibration calibrate_rra_to_stretch(RraSceneSpec spec, double stretch, double max_pressure_kPa);

/// The rod model's extension of the lone RRA at pressure p with force factor c, mm.
double rod_rra_extension_mm(const RraDesign& design, const FibreLaw& tube, double pressure_kPa, double factor,
                            int nodes = 41);

}  // namespace softarm::fem

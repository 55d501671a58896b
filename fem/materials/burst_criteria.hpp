#pragma once
// Spec §4 burst criteria (a) and (b), the one definition every caller uses:
// utilisation = the larger of
//   (a) max principal Cauchy stress / (tensile strength / SF),
//   (b) max principal stretch / ((1 + elongation at break) / SF);
// ≥ 1 means the criterion holds (burst). A material without a strength or an
// elongation at break (NaN) contributes nothing for that criterion.
#include <string>

#include "fem/materials/material.hpp"

namespace softarm::fem {

/// Criteria (a), (b) and the durability strain read the tube's peaks as averages over a ball of
/// this radius in the reference configuration, centred where the average is largest
/// (fem/post/region_average.hpp). A point value at the groove lip is singular and grows without
/// bound under refinement; the ball average converges (docs/definitions.md, "Peak averaging
/// radius", with the table of `bench_peak_convergence`). 2 mm: the thesis RRA's stretch peak then
/// changes by 0.3 % from RRA mesh level 2 to 3 (1.6 % from 1 to 2). Overridable in the
/// requirements config (criteria.peak_averaging_radius_mm) and in an RRA scene (mesh.peak_averaging_radius_mm).
inline constexpr double kDefaultPeakAveragingRadius_mm = 2.0;

struct BurstUtilisation {
  double value = 0;
  std::string criterion;  // "stretch", "stress", or "" when neither is known or both are 0
};

/// The largest principal stretch the material's law is trusted to: the reach of the uniaxial tests
/// it was fitted to, 1 + elongation at break (the thesis fitted its Ogden laws to ASTM D638 tests,
/// which pull to break; spec §2). NaN when the elongation at break is unknown. Beyond it the law is
/// extrapolated: its stresses there are the fit's guess, not a measurement.
double trusted_stretch_limit(const Material& m);

BurstUtilisation burst_utilisation(const Material& m, double max_principal_stress_MPa, double max_principal_stretch,
                                   double safety_factor);

}  // namespace softarm::fem

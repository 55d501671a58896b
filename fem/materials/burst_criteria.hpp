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

struct BurstUtilisation {
  double value = 0;
  std::string criterion;  // "stretch", "stress", or "" when neither is known or both are 0
};

BurstUtilisation burst_utilisation(const Material& m, double max_principal_stress_MPa, double max_principal_stretch,
                                   double safety_factor);

}  // namespace softarm::fem

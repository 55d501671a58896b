#include "fem/materials/burst_criteria.hpp"

#include <cmath>

namespace softarm::fem {

double trusted_stretch_limit(const Material& m) { return 1 + m.elongation_at_break; }

BurstUtilisation burst_utilisation(const Material& m, double max_principal_stress_MPa, double max_principal_stretch,
                                   double safety_factor) {
  BurstUtilisation u;
  if (std::isfinite(m.elongation_at_break)) {
    const double v = max_principal_stretch / ((1 + m.elongation_at_break) / safety_factor);
    if (v > u.value) u = {v, "stretch"};
  }
  if (std::isfinite(m.tensile_strength_MPa)) {
    const double v = max_principal_stress_MPa / (m.tensile_strength_MPa / safety_factor);
    if (v > u.value) u = {v, "stress"};
  }
  return u;
}

}  // namespace softarm::fem

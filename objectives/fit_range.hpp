#pragma once
// Is the tube's law used within the range it was fitted in (issue 33 item 3)? The criteria read the
// tube's peaks averaged over a ball (fem/materials/burst_criteria.hpp); the single point at the
// groove lip stretches further. Both are compared with the fit's trusted stretch (the uniaxial
// tests' reach, 1 + elongation at break), and the verdict is said in words for the console, the
// report and summary.json.
#include <nlohmann/json.hpp>
#include <string>

#include "fem/materials/material.hpp"
#include "objectives/arm_evaluation.hpp"

namespace softarm::objectives {

struct FitRangeCheck {
  double trusted_stretch = 0;        // NaN: the material states no elongation at break
  double averaged_peak_stretch = 1;  // the largest over the segments, at the working pressure
  double point_peak_stretch = 1;
  bool averaged_within = true, point_within = true;
  std::string words;
};

FitRangeCheck check_fit_range(const ArmMeasures& m, const fem::Material& tube);
nlohmann::json to_json(const FitRangeCheck& c);

}  // namespace softarm::objectives

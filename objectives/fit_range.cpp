#include "objectives/fit_range.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "fem/materials/burst_criteria.hpp"

namespace softarm::objectives {

FitRangeCheck check_fit_range(const ArmMeasures& m, const fem::Material& tube) {
  FitRangeCheck c;
  c.trusted_stretch = fem::trusted_stretch_limit(tube);
  for (const auto& s : m.segments) {
    c.averaged_peak_stretch = std::max(c.averaged_peak_stretch, s.peaks.stretch);
    c.point_peak_stretch = std::max(c.point_peak_stretch, s.peaks.point_stretch);
  }
  char text[400];
  if (!std::isfinite(c.trusted_stretch)) {
    std::snprintf(text, sizeof text,
                  "the tube material (%s) states no elongation at break: the range its law was fitted in is unknown",
                  tube.name.c_str());
    c.words = text;
    return c;
  }
  c.averaged_within = c.averaged_peak_stretch <= c.trusted_stretch;
  c.point_within = c.point_peak_stretch <= c.trusted_stretch;
  std::snprintf(text, sizeof text,
                "tube stretch at the working pressure: %.3f averaged (the criteria's), %.3f at the groove lip's "
                "point; %s's law is fitted to uniaxial tests up to %.3f: %s",
                c.averaged_peak_stretch, c.point_peak_stretch, tube.name.c_str(), c.trusted_stretch,
                !c.averaged_within ? "the criteria's stretch lies BEYOND the fitted range (the law is extrapolated)"
                : !c.point_within  ? "within it on average; the lip's point lies beyond it (extrapolated over a "
                                     "region smaller than the averaging ball)"
                                   : "within it");
  c.words = text;
  return c;
}

nlohmann::json to_json(const FitRangeCheck& c) {
  return {{"trusted_stretch", std::isfinite(c.trusted_stretch) ? nlohmann::json(c.trusted_stretch) : nlohmann::json()},
          {"averaged_peak_stretch", c.averaged_peak_stretch},
          {"point_peak_stretch", c.point_peak_stretch},
          {"averaged_within", c.averaged_within},
          {"point_within", c.point_within},
          {"words", c.words}};
}

}  // namespace softarm::objectives

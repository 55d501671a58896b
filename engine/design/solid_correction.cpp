#include "engine/design/solid_correction.hpp"

#include <algorithm>
#include <iomanip>
#include <sstream>

namespace softarm::engine {

std::string SolidCorrection::describe() const {
  if (checks == 0) return "none";
  std::ostringstream s;
  s << std::fixed << std::setprecision(3) << "bending x" << bending_factor << ", burst utilisation x" << burst_factor
    << " (from " << checks << " 3D check" << (checks > 1 ? "s" : "") << ")";
  return s.str();
}

SolidCorrection updated_correction(const SolidCorrection& previous, const objectives::SolidSegmentCheck& check,
                                   const objectives::ArmMeasures& searched, double working_pressure_kPa) {
  if (!fem::is_answer(check.path)) return previous;
  const objectives::SegmentMeasures& rod = searched.segments.at(static_cast<std::size_t>(check.segment - 1));
  SolidCorrection out = previous;
  ++out.checks;
  // β_θ: the newest check's, the search model's bending at the same pressure as the 3D path's.
  const double rod_deg = objectives::bending_at_pressure(rod, check.reached_pressure_kPa);
  if (rod_deg > 1e-6 && check.bending_deg > 0) out.bending_factor = check.bending_deg / rod_deg;
  // β_u: only a failure below the working pressure (a limit point, or a named material or element
  // failure) measures the 3D utilisation.
  if (check.path != fem::PathOutcome::completed && check.reached_pressure_kPa > 0 && rod.burst_utilisation > 1e-6) {
    const double u_3d = working_pressure_kPa / check.reached_pressure_kPa;
    out.burst_factor = std::max(previous.burst_factor, u_3d / rod.burst_utilisation);
  }
  return out;
}

objectives::ArmMeasures corrected(const objectives::ArmMeasures& m, const SolidCorrection& c) {
  objectives::ArmMeasures out = m;
  out.min_bending_deg *= c.bending_factor;
  out.burst_utilisation *= c.burst_factor;
  for (auto& s : out.segments) {
    s.bending_deg_at_working *= c.bending_factor;
    s.burst_utilisation *= c.burst_factor;
  }
  return out;
}

}  // namespace softarm::engine

#include "engine/design/design_measures.hpp"

#include <algorithm>

#include "fem/core/input_error.hpp"

namespace softarm::engine {

const std::vector<DesignMeasure>& design_measures() {
  using M = objectives::ArmMeasures;
  using S = objectives::EvaluationSettings;
  static const std::vector<DesignMeasure> measures = {
      {"mass_kg", "arm mass, connectors included", [](const M& m, const S&, double) { return m.mass_kg; }},
      {"payload_kg", "payload capacity (lift to horizontal; docs/definitions.md, The definitions)",
       [](const M& m, const S&, double) { return m.payload_kg; }},
      {"length_mm", "arm length, shoulder to tip", [](const M& m, const S&, double) { return m.length_mm; }},
      {"min_bending_deg", "smallest segment bending angle at the working pressure",
       [](const M& m, const S&, double) { return m.min_bending_deg; }},
      {"pressure_for_target_bending_kPa",
       "largest over the segments of the pressure that bends it to the target angle (segments that do not reach it: "
       "extrapolated linearly, p_w·target/angle)",
       [](const M& m, const S& s, double) {
         double p = 0;
         for (const auto& seg : m.segments)
           p = std::max(p, seg.pressure_for_target_kPa >= 0
                               ? seg.pressure_for_target_kPa
                               : s.working_pressure_kPa * s.target_bending_deg / std::max(seg.bending_deg_at_working, 1e-3));
         return p;
       }},
      {"safe_working_pressure_kPa",
       "lowest over the segments of the pressure where a burst criterion holds (none below the working pressure: "
       "extrapolated linearly, p_w / utilisation)",
       [](const M& m, const S& s, double) {
         double p = 1e300;
         for (const auto& seg : m.segments)
           p = std::min(p, seg.safe_pressure_kPa >= 0 ? seg.safe_pressure_kPa
                                                      : s.working_pressure_kPa / std::max(seg.burst_utilisation, 1e-6));
         return p;
       }},
      {"rra_extension_mm",
       "the distal segment's lone RRA (the thesis RRA's position) extended at 206.8 kPa: the rod with the force "
       "factor calibrated on its axisymmetric FEM path",
       [](const M& m, const S&, double) { return m.segments[2].rra_extension_mm; }},
      {"burst_utilisation", "largest burst utilisation at the working pressure (1 = at the limit)",
       [](const M& m, const S&, double) { return m.burst_utilisation; }},
      {"durability_strain_ratio", "peak log strain at the working pressure over the thesis RRA's at its cycling pressure",
       [](const M& m, const S&, double reference) { return m.durability_log_strain / reference; }},
  };
  return measures;
}

const DesignMeasure& design_measure(const std::string& name, const std::string& field) {
  for (const auto& m : design_measures())
    if (m.name == name) return m;
  std::string known;
  for (const auto& m : design_measures()) known += (known.empty() ? "" : ", ") + m.name;
  throw fem::InputError(field, "unknown measure '" + name + "'; valid: " + known);
}

std::string measure_label(const std::string& name) {
  static const std::pair<const char*, const char*> units[] = {{"_kg", "kg"}, {"_mm", "mm"}, {"_deg", "deg"}, {"_kPa", "kPa"}};
  std::string words = name, unit;
  for (const auto& [suffix, symbol] : units)
    if (words.ends_with(suffix)) {
      words.resize(words.size() - std::char_traits<char>::length(suffix));
      unit = symbol;
    }
  std::replace(words.begin(), words.end(), '_', ' ');
  return unit.empty() ? words : words + " (" + unit + ")";
}

}  // namespace softarm::engine

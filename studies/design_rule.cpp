#include "studies/design_rule.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace softarm::studies {
using nlohmann::json;

namespace {

std::string number_text(double x, int digits = 4) {
  std::ostringstream s;
  s << std::setprecision(digits) << x;
  return s.str();
}

std::optional<double> output_of(const json& record, const std::string& output) {
  if (!record.contains(output) || !record[output].is_number()) return std::nullopt;
  return record[output].get<double>();
}

std::string percent_text(double fraction) { return number_text(100 * fraction, 4) + " %"; }

/// Why a point is not eligible ("" if it is).
std::string exclusion(const DesignRuleSpec& rule, const json* record) {
  if (!record) return "not run yet";
  const std::string status = record->value("status", std::string("?"));
  if (status != "ok") {
    std::string diagnosis = record->value("diagnosis", std::string());
    const auto cut = diagnosis.find(" (");
    if (cut != std::string::npos) diagnosis.resize(cut);  // the full text is in the report's diagnoses table
    return status + ": " + diagnosis;
  }
  if (!output_of(*record, rule.output)) return rule.output + " not available";
  // Outputs are compared at the study's peak pressure: a path that stopped short is not comparable.
  if (!solved_to_peak(*record))
    return "stopped at " + number_text(*output_of(*record, "reached_pressure_kPa")) + " of " +
           number_text(*output_of(*record, "max_pressure_kPa")) + " kPa" +
           (output_of(*record, "limit_pressure_kPa") ? " (limit point: ballooning)" : "");
  for (const OutputLimit& l : rule.limits) {
    const auto v = output_of(*record, l.output);
    if (!v) continue;  // an output the model does not give (null) cannot exclude
    if (l.max && *v > *l.max) return l.output + " " + number_text(*v) + " > " + number_text(*l.max);
    if (l.min && *v < *l.min) return l.output + " " + number_text(*v) + " < " + number_text(*l.min);
  }
  return "";
}

/// Trend of y along x (sorted by x; points solved to the peak pressure only): monotone within 0.1 % of the range, a
/// peak or valley inside, or flat when the whole range is under 0.5 % of |y|.
void classify(const std::vector<double>& x, const std::vector<double>& y, CurveChoice& c) {
  if (y.size() < 3) return;
  const auto [lo, hi] = std::minmax_element(y.begin(), y.end());
  const double range = *hi - *lo, scale = std::max(std::abs(*hi), std::abs(*lo));
  if (range <= 0.005 * scale) {
    c.trend = "flat";
    return;
  }
  bool up = true, down = true;
  for (std::size_t i = 1; i < y.size(); ++i) {
    up = up && y[i] - y[i - 1] >= -1e-3 * range;
    down = down && y[i] - y[i - 1] <= 1e-3 * range;
  }
  const std::size_t imax = hi - y.begin(), imin = lo - y.begin();
  if (up) c.trend = "increasing";
  else if (down) c.trend = "decreasing";
  else if (imax > 0 && imax + 1 < y.size()) c.trend = "peak", c.extremum_at = x[imax];
  else if (imin > 0 && imin + 1 < y.size()) c.trend = "valley", c.extremum_at = x[imin];
  else c.trend = "mixed";
}

/// `output` of a record at pressure p, from its curve (linear between samples).
std::optional<double> curve_value_at(const json& record, const std::string& output, double p) {
  if (!record.contains("curve") || !record["curve"].contains(output)) return std::nullopt;
  const json& ps = record["curve"]["pressure_kPa"];
  const json& ys = record["curve"][output];
  for (std::size_t i = 0; i < ps.size() && i < ys.size(); ++i) {
    if (!ys[i].is_number()) return std::nullopt;
    const double pi = ps[i].get<double>();
    if (pi >= p * (1 - 1e-9)) {
      if (i == 0 || !ys[i - 1].is_number()) return ys[i].get<double>();
      const double p0 = ps[i - 1].get<double>(), y0 = ys[i - 1].get<double>(), y1 = ys[i].get<double>();
      return y0 + (y1 - y0) * (p - p0) / (pi - p0);
    }
  }
  return std::nullopt;
}

/// Ranks a curve's points by trend_of: at the peak pressure, or for a curve output at the
/// highest pressure every point with a curve reached.
void rank_points(const StudySpec& spec, const std::vector<StudyPoint>& points, const std::map<std::string, json>& records,
                 CurveChoice& curve) {
  const std::string& output = spec.thesis.trend_of;
  std::vector<std::pair<int, const json*>> usable;  // solved, completely or up to where the solver stopped
  for (int i : curve.points) {
    const auto it = records.find(points[i].key);
    const std::string status = it == records.end() ? "" : it->second.value("status", std::string());
    if (status == "ok" || status == "incomplete") usable.emplace_back(i, &it->second);
  }
  double p_common = 1e300;
  bool curves = true;
  for (const auto& [i, r] : usable) {
    if (!(r->contains("curve") && (*r)["curve"].contains(output))) curves = false;
    if (const auto reached = output_of(*r, "reached_pressure_kPa")) p_common = std::min(p_common, *reached);
  }
  std::vector<std::pair<int, double>> ranked;
  for (const auto& [i, r] : usable) {
    const auto v = curves && p_common < 1e300 ? curve_value_at(*r, output, p_common)
                                              : solved_to_peak(*r) ? output_of(*r, output) : std::nullopt;
    if (v) ranked.emplace_back(i, *v);
  }
  if (curves && p_common < 1e300) curve.order_pressure_kPa = p_common;
  std::sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
  for (const auto& [i, v] : ranked) curve.order.push_back(i);
}

std::string trend_words(const CurveChoice& c) {
  if (c.trend == "peak" || c.trend == "valley") return c.trend + " at " + number_text(*c.extremum_at);
  return c.trend;
}

}  // namespace

bool solved_to_peak(const json& record) {
  if (record.value("status", std::string()) != "ok") return false;
  const auto reached = output_of(record, "reached_pressure_kPa"), peak = output_of(record, "max_pressure_kPa");
  return !(reached && peak && *reached < (1 - 1e-6) * *peak);
}

std::string output_value_text(const std::string& output, double value) {
  static const std::vector<std::pair<std::string, std::string>> units{
      {"_mm", " mm"}, {"_g", " g"}, {"_kPa", " kPa"}, {"_deg", "°"}, {"_MPa", " MPa"}};
  for (const auto& [suffix, unit] : units)
    if (output.size() > suffix.size() && output.compare(output.size() - suffix.size(), suffix.size(), suffix) == 0)
      return number_text(value) + unit;
  return number_text(value);
}

std::vector<CurveChoice> apply_rule(const StudySpec& spec, const std::vector<StudyPoint>& points,
                                    const std::map<std::string, json>& records) {
  const DesignRuleSpec& rule = spec.rule;
  const SweepAxis& axis = spec.axes.front();
  std::vector<CurveChoice> curves;
  for (const StudyPoint& p : points) {
    const auto c = static_cast<std::size_t>(curve_index(spec, p));
    if (curves.size() <= c) curves.resize(c + 1);
    curves[c].label = curve_label(spec, p);
    curves[c].points.push_back(p.index);
  }
  const double sign = rule.goal == "max" ? 1 : -1;
  for (CurveChoice& curve : curves) {
    std::vector<int> eligible;
    std::vector<double> trend_x, trend_y;
    for (int i : curve.points) {
      const auto it = records.find(points[i].key);
      const json* record = it == records.end() ? nullptr : &it->second;
      const std::string why = exclusion(rule, record);
      if (why.empty()) eligible.push_back(i);
      else curve.excluded.emplace_back(i, why);
      if (record && axis.numeric() && solved_to_peak(*record))
        if (const auto v = output_of(*record, spec.thesis.trend_of)) {
          trend_x.push_back(points[i].values[0].get<double>());
          trend_y.push_back(*v);
        }
    }
    classify(trend_x, trend_y, curve);
    rank_points(spec, points, records, curve);
    const auto value = [&](int i, const std::string& output) { return *output_of(records.at(points[i].key), output); };
    std::ostringstream words;
    const std::string& name = axis.label;
    if (!trend_x.empty() && !curve.trend.empty())
      words << spec.thesis.trend_of << " along " << name << ": " << trend_words(curve) << ". ";
    if (eligible.empty()) {
      words << "No point is eligible";
      if (!curve.excluded.empty()) words << " (" << curve.excluded.front().second << ")";
      words << ".";
      curve.words = words.str();
      continue;
    }
    curve.best = *std::max_element(eligible.begin(), eligible.end(),
                                   [&](int a, int b) { return sign * value(a, rule.output) < sign * value(b, rule.output); });
    const double best = value(curve.best, rule.output);
    curve.chosen = curve.best;
    words << rule.output << " is " << (rule.goal == "max" ? "largest" : "smallest") << " at " << name << " = "
          << value_text(points[curve.best].values[0]) << " (" << output_value_text(rule.output, best) << ")";
    if (rule.keep_percent < 100 && !rule.then_minimise.empty()) {
      const double keep = rule.keep_percent / 100;
      for (int i : eligible) {
        const double v = value(i, rule.output);
        const bool kept = rule.goal == "max" ? v >= keep * best : v <= best / keep;
        if (kept && output_of(records.at(points[i].key), rule.then_minimise) &&
            value(i, rule.then_minimise) < value(curve.chosen, rule.then_minimise))
          curve.chosen = i;
      }
      if (curve.chosen != curve.best) {
        const double v = value(curve.chosen, rule.output);
        const double m = value(curve.chosen, rule.then_minimise), mb = value(curve.best, rule.then_minimise);
        words << "; " << name << " = " << value_text(points[curve.chosen].values[0]) << " keeps "
              << percent_text(v / best) << " of it with " << number_text(100 * (m / mb - 1), 3) << " % "
              << rule.then_minimise << " (" << output_value_text(rule.then_minimise, m) << " vs "
              << output_value_text(rule.then_minimise, mb) << ")";
      } else {
        words << "; no point within " << number_text(100 - rule.keep_percent) << " % of it has a smaller "
              << rule.then_minimise;
      }
    }
    words << ". The rule picks " << name << " = " << value_text(points[curve.chosen].values[0]) << ".";
    if (!curve.excluded.empty()) {
      words << " Not eligible:";
      for (const auto& [i, why] : curve.excluded) words << " " << value_text(points[i].values[0]) << " (" << why << ");";
    }
    curve.words = words.str();
  }
  return curves;
}

ThesisComparison compare_with_thesis(const StudySpec& spec, const std::vector<StudyPoint>& points,
                                     const std::vector<CurveChoice>& curves) {
  ThesisComparison out;
  const ThesisFinding& t = spec.thesis;
  std::ostringstream words;
  const auto same = [](const json& a, const json& b) {
    if (a.is_number() && b.is_number()) return std::abs(a.get<double>() - b.get<double>()) <= 1e-9 * std::max(1.0, std::abs(b.get<double>()));
    return a == b;
  };
  int agree = 0, chosen = 0;
  for (const CurveChoice& c : curves)
    if (c.chosen >= 0) {
      ++chosen;
      if (!t.choice.is_null() && same(points[c.chosen].values[0], t.choice)) ++agree;
    }
  out.choice_agrees = chosen > 0 && agree == chosen;
  if (!t.choice.is_null())
    words << "Thesis choice: " << spec.axes.front().label << " = " << value_text(t.choice) << "; softarm's rule picks "
          << (out.choice_agrees ? "the same" : "a different value on " + std::to_string(chosen - agree) + " of " +
                                                   std::to_string(chosen) + " curve(s)")
          << ". ";
  if (!t.trend.empty()) {
    int trend_agree = 0, classified = 0;
    for (const CurveChoice& c : curves) {
      if (c.trend.empty()) continue;
      ++classified;
      bool ok = c.trend == t.trend;
      if (ok && t.trend == "peak" && t.peak_at && c.extremum_at) ok = std::abs(*c.extremum_at - *t.peak_at) < 1e-9 + 1e-6 * std::abs(*t.peak_at);
      if (ok) ++trend_agree;
    }
    out.trend_agrees = classified > 0 && trend_agree == classified;
    words << "Thesis trend: " << t.trend << (t.trend == "peak" && t.peak_at ? " at " + number_text(*t.peak_at) : "")
          << "; softarm: ";
    for (std::size_t i = 0; i < curves.size(); ++i)
      words << (i ? ", " : "") << (curves[i].trend.empty() ? "—" : trend_words(curves[i]))
            << (curves[i].label.empty() ? "" : " (" + curves[i].label + ")");
    words << (out.trend_agrees ? " — agrees." : " — differs.");
  } else if (!t.order.empty()) {
    int order_agree = 0;
    for (const CurveChoice& c : curves) {
      std::vector<json> softarm_order;
      for (int i : c.order) softarm_order.push_back(points[i].values[0]);
      if (softarm_order == t.order) ++order_agree;
    }
    out.trend_agrees = order_agree == static_cast<int>(curves.size());
    const auto order_text = [](const std::vector<json>& v) {
      std::string s;
      for (const auto& x : v) s += (s.empty() ? "" : " > ") + value_text(x);
      return s;
    };
    words << "Thesis order of " << t.trend_of << ": " << order_text(t.order) << "; softarm";
    if (!curves.empty() && curves.front().order_pressure_kPa)
      words << " (at " << number_text(*curves.front().order_pressure_kPa) << " kPa, the highest pressure every point reached)";
    words << ": ";
    for (std::size_t i = 0; i < curves.size(); ++i) {
      std::vector<json> v;
      for (int k : curves[i].order) v.push_back(points[k].values[0]);
      words << (i ? ", " : "") << order_text(v) << (curves[i].label.empty() ? "" : " (" + curves[i].label + ")");
    }
    words << (out.trend_agrees ? " — agrees." : " — differs.");
  } else {
    out.trend_agrees = true;
  }
  out.words = words.str();
  return out;
}

}  // namespace softarm::studies

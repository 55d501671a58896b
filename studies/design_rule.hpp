#pragma once
// The design rule applied to a study's results, and the rule stated in words
// from the numbers (spec §5: what the thesis did by reading curves).
//
// Per curve (one combination of the axes after the first): the eligible points
// are those with status ok that keep every limit; the best is the largest (or
// smallest) `output`; the chosen is the best or, with keep_percent < 100, the
// point among those within keep_percent of the best that minimises
// `then_minimise`. The trend of the thesis' trend_of output along a numeric
// first axis is classified (increasing, decreasing, peak at x, valley at x,
// flat within 0.5 %) and compared with the thesis' trend; along a categorical
// axis the points are ranked by it, at the highest pressure every point reached
// when it is a curve output ("at the same pressure", as the thesis compares a
// ballooning Dragon Skin 10 with the others), and compared with the thesis' order.
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "studies/study_points.hpp"
#include "studies/study_spec.hpp"

namespace softarm::studies {

struct CurveChoice {
  std::string label;               // "" for a study with one curve
  std::vector<int> points;         // indices of the curve's points, in first-axis order
  int best = -1, chosen = -1;      // point indices (-1: no eligible point)
  std::vector<std::pair<int, std::string>> excluded;  // point index, why
  std::string trend;               // "increasing", "decreasing", "peak", "valley", "flat", "mixed" or ""
  std::optional<double> extremum_at;  // first-axis value of the peak / valley
  std::vector<int> order;          // points from the largest trend_of output to the smallest, compared at
  std::optional<double> order_pressure_kPa;  // the highest pressure all of them reached (curve outputs)
  std::string words;               // the rule, stated from the data
};

/// The rule on every curve; `records` by point key (missing points count as not run).
std::vector<CurveChoice> apply_rule(const StudySpec& spec, const std::vector<StudyPoint>& points,
                                    const std::map<std::string, nlohmann::json>& records);

struct ThesisComparison {
  bool choice_agrees = false, trend_agrees = false;  // trend: or the order of a categorical axis
  std::string words;
};
ThesisComparison compare_with_thesis(const StudySpec& spec, const std::vector<StudyPoint>& points,
                                     const std::vector<CurveChoice>& curves);

/// Status ok and solved up to the study's peak pressure: its outputs compare with the others'.
bool solved_to_peak(const nlohmann::json& record);

/// "76.67 mm", "43.5 g", "0.965" from an output name's unit suffix.
std::string output_value_text(const std::string& output, double value);

}  // namespace softarm::studies

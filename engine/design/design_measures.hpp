#pragma once
// The measures of an arm design that a requirements config may name as the
// objective ({"minimise": name} / {"maximise": name}) or as an extra constraint
// ({"measure": name, "min": v} / {"max": v}): each is a number computed from
// one evaluation (objectives/arm_evaluation.hpp), with its unit in its name.
#include <functional>
#include <string>
#include <vector>

#include "objectives/arm_evaluation.hpp"

namespace softarm::engine {

struct DesignMeasure {
  std::string name, doc;
  /// The value from an evaluation; `reference_strain` is the durability reference (thesis RRA).
  std::function<double(const objectives::ArmMeasures&, const objectives::EvaluationSettings&, double reference_strain)> value;
};

const std::vector<DesignMeasure>& design_measures();
/// The measure called `name`; an unknown name raises InputError(field) listing the known ones.
const DesignMeasure& design_measure(const std::string& name, const std::string& field);
/// A measure's name as an axis label: words and the unit its suffix states ("mass_kg" → "mass (kg)",
/// "burst_utilisation" → "burst utilisation").
std::string measure_label(const std::string& name);

}  // namespace softarm::engine

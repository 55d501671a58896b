#pragma once
// The search model's measures of the designs one design run has evaluated, kept for the run.
#include <mutex>
#include <vector>

#include "objectives/arm_evaluation.hpp"

namespace softarm::engine {

/// objectives::evaluate_arm of the design x (the variables; `arm` is the candidate they make) under
/// `settings`, computed once per run: the run measures the start design before its first search
/// evaluates it again, each search's optimum again for its report, and the check model's measures
/// equal the search model's where the config sets them alike. Safe to call from the search's
/// concurrent evaluations (two asking for one design at once may both compute it). Designs that
/// cannot be built throw, as evaluate_arm does, and are not kept.
class MeasuresMemo {
 public:
  objectives::ArmMeasures measures(const std::vector<double>& x, const objectives::ArmCandidate& arm,
                                   const objectives::EvaluationSettings& settings);
  int computed() const;  // evaluations run, not served from the memo
  int served() const;    // served from the memo

 private:
  struct Entry {
    std::vector<double> x;
    objectives::EvaluationSettings settings;
    objectives::ArmMeasures measures;
  };
  mutable std::mutex mutex_;
  std::vector<Entry> entries_;  // a run measures hundreds of designs at most: a linear search
  int computed_ = 0, served_ = 0;
};

}  // namespace softarm::engine

#include "engine/design/measures_memo.hpp"

namespace softarm::engine {

objectives::ArmMeasures MeasuresMemo::measures(const std::vector<double>& x, const objectives::ArmCandidate& arm,
                                               const objectives::EvaluationSettings& settings) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (const Entry& e : entries_)
      if (e.x == x && e.settings == settings) {
        ++served_;
        return e.measures;
      }
  }
  objectives::ArmMeasures m = objectives::evaluate_arm(arm, settings);
  const std::lock_guard<std::mutex> lock(mutex_);
  ++computed_;
  entries_.push_back({x, settings, m});
  return m;
}

int MeasuresMemo::computed() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return computed_;
}

int MeasuresMemo::served() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return served_;
}

}  // namespace softarm::engine

// Evaluation cache, budget, failure sanitising and history (see evaluation_cache.hpp).
#include "engine/optimiser/evaluation_cache.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace softarm::optimise::detail {

double max_violation(const Evaluation& e) {
  if (!e.ok) return std::numeric_limits<double>::infinity();
  double m = 0;
  for (double g : e.constraints) m = std::max(m, g);
  return m;
}

bool is_feasible(const Evaluation& e, double tolerance) {
  return e.ok && max_violation(e) <= tolerance;
}

bool better(const Evaluation& a, const Evaluation& b, double tolerance) {
  if (a.ok != b.ok) return a.ok;
  if (!a.ok) return false;
  const bool fa = is_feasible(a, tolerance), fb = is_feasible(b, tolerance);
  if (fa != fb) return fa;
  if (fa) return a.objective < b.objective;
  const double va = max_violation(a), vb = max_violation(b);
  if (va != vb) return va < vb;
  return a.objective < b.objective;
}

EvaluationCache::EvaluationCache(const Problem& problem, const DesignSpace& space,
                                 const Options& options)
    : problem_(problem),
      space_(space),
      options_(options),
      tolerance_(options.constraint_tolerance),
      global_limit_(options.max_evaluations),
      local_limit_(options.max_evaluations),
      best_feasible_(std::numeric_limits<double>::infinity()) {}

int EvaluationCache::remaining() const {
  return std::max(0, std::min(global_limit_, local_limit_) - evaluations());
}

Evaluation EvaluationCache::run(const std::vector<double>& x) const {
  Evaluation e;
  try {
    e = problem_.evaluate(x);
  } catch (const std::exception& error) {
    e = Evaluation{};
    e.ok = false;
    e.failure_reason = std::string("exception: ") + error.what();
  } catch (...) {
    e = Evaluation{};
    e.ok = false;
    e.failure_reason = "exception of unknown type";
  }
  if (!e.ok) {
    if (e.failure_reason.empty()) e.failure_reason = "evaluation failed (no reason given)";
    return e;
  }
  auto fail = [&](const std::string& why) {
    e.ok = false;
    e.failure_reason = why;
  };
  if (e.constraints.size() != problem_.constraint_names.size()) {
    std::ostringstream s;
    s << "evaluate returned " << e.constraints.size() << " constraints, expected "
      << problem_.constraint_names.size();
    fail(s.str());
  } else if (!std::isfinite(e.objective)) {
    std::ostringstream s;
    s << "non-finite objective (" << e.objective << ")";
    fail(s.str());
  } else {
    for (std::size_t i = 0; i < e.constraints.size(); ++i)
      if (!std::isfinite(e.constraints[i])) {
        std::ostringstream s;
        s << "non-finite constraint '" << problem_.constraint_names[i] << "' ("
          << e.constraints[i] << ")";
        fail(s.str());
        break;
      }
  }
  return e;
}

void EvaluationCache::report(const std::vector<double>& x, const Evaluation& e, bool cached) {
  Progress p;
  p.evaluation = evaluations();
  p.x = x;
  p.value = e;
  p.cached = cached;
  p.phase = phase_;
  p.best_feasible_objective = best_feasible_;
  if (!cached) history_.push_back(p);
  if (options_.on_evaluation && (!cached || options_.report_cache_hits)) options_.on_evaluation(p);
}

Evaluation EvaluationCache::evaluate(const std::vector<double>& raw) {
  const std::vector<double> x = space_.snapped(raw);
  const auto k = space_.key(x);
  if (auto it = index_.find(k); it != index_.end()) {
    ++cache_hits_;
    const Entry entry = entries_[it->second];
    if (options_.report_cache_hits) report(entry.x, entry.value, true);
    return entry.value;
  }
  if (evaluations() >= global_limit_) throw BudgetExhausted(true);
  if (evaluations() >= local_limit_) throw BudgetExhausted(false);
  Evaluation e;
  if (auto held = held_.find(k); held != held_.end()) {
    e = std::move(held->second);
    held_.erase(held);
  } else {
    e = run(x);
  }
  entries_.push_back(Entry{x, e});
  index_.emplace(k, entries_.size() - 1);
  if (is_feasible(e, tolerance_)) best_feasible_ = std::min(best_feasible_, e.objective);
  report(x, e, false);
  return e;
}

void EvaluationCache::prefetch(const std::vector<std::vector<double>>& designs) {
  if (!problem_.run_concurrently) return;
  std::vector<std::vector<double>> todo;
  std::vector<std::vector<std::int64_t>> keys;
  for (const auto& raw : designs) {
    if (static_cast<int>(todo.size()) >= remaining()) break;
    std::vector<double> x = space_.snapped(raw);
    auto k = space_.key(x);
    if (index_.count(k) || held_.count(k) || std::find(keys.begin(), keys.end(), k) != keys.end()) continue;
    todo.push_back(std::move(x));
    keys.push_back(std::move(k));
  }
  if (todo.size() < 2) return;
  std::vector<Evaluation> results(todo.size());
  try {
    problem_.run_concurrently(static_cast<int>(todo.size()), [&](int i) { results[i] = run(todo[i]); });
  } catch (const std::exception&) {
    return;  // no threads to be had (run() itself never throws): the serial search computes them as it asks
  }
  for (std::size_t i = 0; i < todo.size(); ++i) held_.emplace(std::move(keys[i]), std::move(results[i]));
}

const EvaluationCache::Entry* EvaluationCache::best(
    const std::function<bool(const std::vector<double>&)>& accept) const {
  const Entry* best = nullptr;
  for (const Entry& e : entries_) {
    if (accept && !accept(e.x)) continue;
    if (!best || better(e.value, best->value, tolerance_)) best = &e;
  }
  return best;
}

EvaluationCache::Scope::Scope(EvaluationCache& cache, std::string phase, int budget)
    : cache_(cache), old_phase_(cache.phase_), old_limit_(cache.local_limit_) {
  cache_.phase_ = std::move(phase);
  const long long limit = static_cast<long long>(cache_.evaluations()) + std::max(0, budget);
  cache_.local_limit_ = static_cast<int>(std::min<long long>(cache_.local_limit_, limit));
}

EvaluationCache::Scope::~Scope() {
  cache_.phase_ = old_phase_;
  cache_.local_limit_ = old_limit_;
}

}  // namespace softarm::optimise::detail

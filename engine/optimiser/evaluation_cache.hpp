// Evaluation cache and budget: the single door through which the optimiser
// calls Problem::evaluate. A real design (integers integral, categorical index)
// is evaluated at most once; later requests are cache hits. It enforces the
// evaluation budget (global, plus a nested local limit per phase), turns
// exceptions and non-finite numbers from evaluate into failures, records the
// history, calls the progress callback and keeps the ranking of designs
// (feasible first, then objective; else least maximum violation).
#pragma once

#include <cstdint>
#include <exception>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "engine/optimiser/design_space.hpp"
#include "engine/optimiser/optimiser.hpp"

namespace softarm::optimise::detail {

/// Thrown by EvaluationCache::evaluate when a new evaluation would exceed the
/// budget. Drivers catch it at their callback boundary and stop their solver.
struct BudgetExhausted : std::exception {
  bool global = true;  ///< the whole call's budget (false: only the phase's)
  explicit BudgetExhausted(bool whole) : global(whole) {}
  const char* what() const noexcept override { return "evaluation budget exhausted"; }
};

/// max_i g_i (0 without constraints); +infinity for a failure.
double max_violation(const Evaluation& e);
bool is_feasible(const Evaluation& e, double tolerance);
/// Strict ranking: a is better than b (ok before failed; feasible before
/// infeasible; then lower objective, or lower maximum violation when both
/// infeasible).
bool better(const Evaluation& a, const Evaluation& b, double tolerance);

class EvaluationCache {
 public:
  struct Entry {
    std::vector<double> x;
    Evaluation value;
  };

  EvaluationCache(const Problem& problem, const DesignSpace& space, const Options& options);

  /// The evaluation of a design (snapped first). Throws BudgetExhausted when it
  /// is not cached and the budget is spent; never throws for a failing design.
  Evaluation evaluate(const std::vector<double>& x);

  /// Evaluates, side by side (Problem::run_concurrently), the designs among `designs` that are
  /// neither cached nor held yet, at most remaining() of them in their order. Their results
  /// are held, not counted: a later evaluate() of one takes it as that call's real evaluation,
  /// with the same budget check, count and report as if it ran then. Without
  /// run_concurrently, or with fewer than two designs to run, it does nothing.
  void prefetch(const std::vector<std::vector<double>>& designs);

  int evaluations() const { return static_cast<int>(entries_.size()); }
  int cache_hits() const { return cache_hits_; }
  /// Real evaluations still allowed (the tighter of the global and local limits).
  int remaining() const;
  bool global_budget_exhausted() const { return evaluations() >= global_limit_; }

  const std::string& phase() const { return phase_; }
  double constraint_tolerance() const { return tolerance_; }
  std::size_t constraint_count() const { return problem_.constraint_names.size(); }

  /// The best entry (nullptr when nothing was evaluated), optionally among the
  /// designs a predicate accepts.
  const Entry* best(const std::function<bool(const std::vector<double>&)>& accept = {}) const;
  const std::vector<Progress>& history() const { return history_; }

  /// Sets the phase name and tightens the local limit to at most `budget` more
  /// real evaluations for the lifetime of the object; restores both after.
  class Scope {
   public:
    Scope(EvaluationCache& cache, std::string phase, int budget);
    ~Scope();
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    EvaluationCache& cache_;
    std::string old_phase_;
    int old_limit_;
  };

 private:
  Evaluation run(const std::vector<double>& x) const;
  void report(const std::vector<double>& x, const Evaluation& e, bool cached);

  const Problem& problem_;
  const DesignSpace& space_;
  const Options& options_;
  double tolerance_;
  int global_limit_;
  int local_limit_;
  std::string phase_;
  std::vector<Entry> entries_;
  std::map<std::vector<std::int64_t>, std::size_t> index_;
  std::map<std::vector<std::int64_t>, Evaluation> held_;  ///< prefetched, not yet asked for
  int cache_hits_ = 0;
  std::vector<Progress> history_;
  double best_feasible_ = 0;
};

}  // namespace softarm::optimise::detail

// One continuous optimisation run of a RelaxedObjective from a start point, by
// NLopt or Ipopt. The real-evaluation budget is enforced by the cache (the
// caller opens an EvaluationCache::Scope); the drivers stop their solver
// cleanly when it throws BudgetExhausted. The run's answer is the objective's
// tracked best relaxed point (RelaxedObjective::best_u), not the solver's last
// iterate, so every driver reports the same way.
#pragma once

#include <string>
#include <vector>

#include "engine/optimiser/algorithms.hpp"
#include "engine/optimiser/relaxed_objective.hpp"

namespace softarm::optimise::detail {

struct DriverSettings {
  Algorithm algorithm = Algorithm::cobyla;
  double tolerance = 1e-4;             ///< absolute on u, relative on f
  double constraint_tolerance = 1e-6;
  double finite_difference_step = 1e-3;
  unsigned seed = 1;
  int budget = 200;                    ///< real evaluations this run may use (sizes max_iter)
};

struct DriverOutcome {
  std::string stop_reason;
  bool budget_exhausted = false;
};

/// Never lets an exception from an evaluation into the solver; rethrows an
/// exception from the progress callback after the solver has returned.
DriverOutcome run_nlopt(RelaxedObjective& f, const std::vector<double>& u0, const DriverSettings& s);
DriverOutcome run_ipopt(RelaxedObjective& f, const std::vector<double>& u0, const DriverSettings& s);

inline DriverOutcome run_driver(RelaxedObjective& f, const std::vector<double>& u0,
                                const DriverSettings& s) {
  return s.algorithm == Algorithm::ipopt ? run_ipopt(f, u0, s) : run_nlopt(f, u0, s);
}

}  // namespace softarm::optimise::detail

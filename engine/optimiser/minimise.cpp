// minimise(): validation, the design space, the cache and the mixed-variable
// search wired together, and the Result assembled from the cache's best design
// (feasible first, then objective; else least violation). See optimiser.hpp.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "engine/optimiser/algorithms.hpp"
#include "engine/optimiser/design_space.hpp"
#include "engine/optimiser/evaluation_cache.hpp"
#include "engine/optimiser/mixed_variable_search.hpp"
#include "engine/optimiser/optimiser.hpp"

namespace softarm::optimise {

Result minimise(const Problem& problem, const Options& options) {
  using namespace detail;
  parse_algorithm(options.algorithm);  // throws, listing the valid names
  validate(problem, options);
  const auto t0 = std::chrono::steady_clock::now();

  const DesignSpace space(problem.variables);
  EvaluationCache cache(problem, space, options);
  std::vector<double> start = options.x0.empty() ? space.centre() : options.x0;
  for (std::size_t i : space.indices(VariableKind::categorical)) start[i] = std::round(start[i]);

  MixedVariableSearch search(space, cache, options);
  search.run(start);

  Result r;
  if (const auto* best = cache.best()) {
    r.x = best->x;
    r.best = best->value;
  } else {
    r.x = space.snapped(start);
    r.best.ok = false;
    r.best.failure_reason = "nothing was evaluated";
  }
  r.feasible = is_feasible(r.best, options.constraint_tolerance);
  r.evaluations = cache.evaluations();
  r.cache_hits = cache.cache_hits();
  r.history = cache.history();

  std::ostringstream reason;
  if (cache.global_budget_exhausted()) {
    reason << "evaluation budget of " << options.max_evaluations
           << " real evaluations reached; best design so far returned";
  } else {
    reason << "finished";
    std::string notes;
    for (const auto& n : search.notes()) notes += (notes.empty() ? "" : "; ") + n;
    if (!notes.empty()) reason << " (" << notes << ")";
  }
  if (!r.best.ok) {
    reason << "; every evaluation failed, the first with: " << r.best.failure_reason;
  } else if (!r.feasible) {
    std::size_t worst = 0;
    for (std::size_t i = 1; i < r.best.constraints.size(); ++i)
      if (r.best.constraints[i] > r.best.constraints[worst]) worst = i;
    reason << "; no feasible design found: constraint '" << problem.constraint_names[worst]
           << "' = " << r.best.constraints[worst] << " > 0 at the least-violating design";
  }
  r.stop_reason = reason.str();
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace softarm::optimise

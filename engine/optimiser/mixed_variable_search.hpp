// The search over mixed variables, on top of the continuous drivers:
//  - optimise_combination: one categorical combination; a multi-start continuous
//    search with the integers relaxed (relaxed_objective.hpp), then the integer
//    neighbour search (floor/ceil of the relaxed optimum, all combinations when
//    at most 8, else greedy; continuous variables re-optimised with a share of
//    the remaining budget); a start whose design fails is moved (towards the
//    centre, then to sampled points) until one evaluates;
//  - run: categorical screening (optimise the first combination, evaluate the
//    others at its optimum, fully optimise the categorical_keep best).
// The budget of each phase is a share of what remains; unused budget flows to
// the next phase. The answer is read from the cache (its best design), so every
// phase only has to explore.
#pragma once

#include <string>
#include <vector>

#include "engine/optimiser/algorithms.hpp"
#include "engine/optimiser/design_space.hpp"
#include "engine/optimiser/driver.hpp"
#include "engine/optimiser/evaluation_cache.hpp"
#include "engine/optimiser/relaxed_objective.hpp"

namespace softarm::optimise::detail {

class MixedVariableSearch {
 public:
  MixedVariableSearch(const DesignSpace& space, EvaluationCache& cache, const Options& options);

  /// Runs everything from `start` (a full physical design: x0, or the centre).
  /// Returns when done or when the budget is spent (never throws BudgetExhausted).
  void run(const std::vector<double>& start);

  /// One line per driver run, "phase: reason".
  const std::vector<std::string>& notes() const { return notes_; }

 private:
  void optimise_combination(const std::vector<double>& start, int budget, const std::string& label);
  void integer_neighbours(const std::vector<double>& relaxed, const std::string& label);
  /// u0, or when the design there fails, the first that does not of: two
  /// points towards the centre, then 2n+2 Latin-hypercube points.
  std::vector<double> usable_start(RelaxedObjective& f, const std::vector<double>& u0, int start_index);
  DriverSettings settings(int budget, bool local_only) const;
  std::string prefixed(const std::string& label, const std::string& phase) const;

  const DesignSpace& space_;
  EvaluationCache& cache_;
  const Options& options_;
  Algorithm algorithm_;
  std::vector<std::string> notes_;
};

}  // namespace softarm::optimise::detail

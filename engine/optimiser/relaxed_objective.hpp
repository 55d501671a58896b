// The function a continuous algorithm sees: u in [0,1]^n (the searched
// variables, normalised) -> objective and constraints. Variables not searched
// (categorical choices, integers fixed by the neighbour search) come from a
// base design. Searched integer variables are relaxed: a fractional value is
// never evaluated; the objective and constraints are interpolated piecewise
// linearly over the Kuhn (Freudenthal) simplex of the surrounding integer cell:
// with the k fractional parts sorted f_1 >= ... >= f_k, corner 0 is every floor,
// corner j adds 1 to the integer with the j-th largest fraction, and the
// weights are 1-f_1, f_1-f_2, ..., f_k. That is k+1 real (cached) designs, is
// continuous across cells, and for one integer is the linear interpolation
// between floor and ceil. It also tracks the best relaxed point it served
// (the relaxed optimum handed to the integer neighbour search) and the values
// from which NLopt's penalty for failed points is built.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "engine/optimiser/design_space.hpp"
#include "engine/optimiser/evaluation_cache.hpp"

namespace softarm::optimise::detail {

class RelaxedObjective {
 public:
  /// `base`: a full physical design (categorical indices, fixed integers);
  /// `searched`: the variables optimised (continuous or integer), in order.
  RelaxedObjective(const DesignSpace& space, EvaluationCache& cache, std::vector<double> base,
                   std::vector<std::size_t> searched);

  std::size_t dimension() const { return searched_.size(); }
  std::size_t constraint_count() const { return constraint_count_; }
  EvaluationCache& cache() const { return cache_; }

  /// The (interpolated) evaluation at u. Throws BudgetExhausted.
  Evaluation operator()(const std::vector<double>& u);

  /// Evaluates side by side the real designs that operator() will need at each of `us`
  /// (EvaluationCache::prefetch).
  void prefetch(const std::vector<std::vector<double>>& us);

  /// The relaxed physical design at u (integers possibly fractional).
  std::vector<double> physical(const std::vector<double>& u) const;
  /// The normalised searched coordinates of a physical design.
  std::vector<double> unit(const std::vector<double>& x) const;

  bool has_best() const { return has_best_; }
  const std::vector<double>& best_u() const { return best_u_; }
  const Evaluation& best_value() const { return best_value_; }

  /// Finite stand-ins for a failed point (NLopt): an objective above the worst
  /// seen, and each constraint violated by more than the worst seen.
  double penalty_objective() const;
  double penalty_constraint(std::size_t i) const;

 private:
  /// A real design of the integer-lattice cell around u and its interpolation weight (> 0).
  struct Corner {
    std::vector<double> x;
    double weight;
  };
  std::vector<Corner> corners(const std::vector<double>& u) const;

  const DesignSpace& space_;
  EvaluationCache& cache_;
  std::vector<double> base_;
  std::vector<std::size_t> searched_;
  std::size_t constraint_count_ = 0;
  bool has_best_ = false;
  std::vector<double> best_u_;
  Evaluation best_value_;
  bool seen_ok_ = false;
  double f_min_ = 0, f_max_ = 0;
  std::vector<double> g_max_;
};

}  // namespace softarm::optimise::detail

// The optimiser layer: minimise a black-box objective subject to inequality
// constraints over mixed continuous / integer / categorical variables, with
// NLopt (https://nlopt.readthedocs.io) and Ipopt (https://coin-or.github.io/Ipopt)
// behind one interface. It knows nothing of the FEM: a design is a vector of
// numbers and `Problem::evaluate` turns it into an objective and constraints.
//
// Each evaluation may cost seconds (a nonlinear FEM solve), so the layer is
// built around the evaluation count:
//  - every real evaluation goes through a cache keyed on the design (integers
//    rounded, categorical index, continuous values at ~1e-12 of their range),
//    so no design is evaluated twice (NLopt asks for the objective and the
//    constraints of the same point separately: the second is a cache hit);
//  - `Options::max_evaluations` bounds the real evaluations of the whole call
//    (all starts, integer and categorical phases together); when it is reached
//    the best design so far is returned and `Result::stop_reason` says so.
//
// Search in normalised space. The algorithms see u in [0,1]^n, u = (x − lower) /
// (upper − lower) for the continuous and integer variables, so tolerances and
// finite-difference steps mean the same for every variable.
//
// Gradients (nlopt:slsqp, nlopt:ccsaq, ipopt) are forward differences in u with
// step h = `finite_difference_step` (backward at the upper bound, or when the
// forward point fails); objective and constraint gradients come from the same
// n+1 evaluations, whose n neighbours run side by side when the problem gives
// `run_concurrently`.
//
// Integer variables: continuous relaxation, then a neighbour search.
//  1. During the continuous search an integer variable moves freely in
//     [lower, upper]; a design with fractional integers is never evaluated:
//     its objective and constraints are interpolated (piecewise linearly, over
//     the Kuhn simplex of the surrounding integer lattice cell: k fractional
//     integers cost k+1 real designs, k=1 is the linear interpolation between
//     floor and ceil) from real integral designs, all cached.
//  2. The relaxed optimum's integers are then fixed to floor/ceil (every
//     combination when there are at most 8, nearest first; otherwise greedy: the
//     nearest rounding, then each integer flipped in turn, a flip kept when it
//     improves) and the continuous variables re-optimised from the relaxed
//     optimum with a share of the remaining budget. The best feasible design wins
//     (this is how a rounded-nearest integer that violates a constraint is
//     avoided).
//
// Categorical variables: screening. The combinations of choices are enumerated;
// the first combination (x0's, or every first choice) is optimised with a
// 1/(categorical_keep + 1) share of the budget; every other combination is
// evaluated once at that optimum's continuous and integer values; the
// `categorical_keep` best combinations of that screening (feasible first, then
// objective) are optimised with equal shares of the rest, each from its
// screened point (the first, if kept, continues from its optimum), and the best
// design overall is returned.
//
// Failures: an Evaluation with ok=false (or one that throws std::exception, or
// returns a non-finite number or the wrong number of constraints) is an
// infeasible point, kept in the history with its reason. NLopt sees it as a
// finite penalty (objective above the worst seen, every constraint violated);
// Ipopt gets `false` from eval_* and cuts its step. Nothing non-finite and no
// exception ever reaches NLopt or Ipopt.
//
// The returned design is the best real evaluation: feasible (every g_i <=
// `constraint_tolerance`) with the lowest objective; when no evaluation is
// feasible, the one of least maximum violation with feasible=false, so the
// caller can say which constraint binds and by how much. Write constraints
// dimensionless (g = value / limit − 1) so one tolerance fits them all.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace softarm::optimise {

enum class VariableKind { continuous, integer, categorical };

struct Variable {
  std::string name;
  VariableKind kind = VariableKind::continuous;
  double lower = 0, upper = 1;        ///< continuous and integer (integer: integral bounds)
  std::vector<std::string> choices;   ///< categorical only
  int fixed_choice = -1;              ///< categorical: ≥ 0 holds the variable at that choice (none screened)
  std::string unit;                   ///< for reports only
};

/// One evaluation of a design: the objective and every constraint g_i
/// (feasible when g_i <= 0), or a failure.
struct Evaluation {
  bool ok = true;
  std::string failure_reason;
  double objective = 0;
  std::vector<double> constraints;
};

struct Problem {
  std::vector<Variable> variables;
  std::vector<std::string> constraint_names;
  /// x in physical units: continuous as is, integer as an integral double,
  /// categorical as the choice index (double). Must return
  /// constraint_names.size() constraints.
  std::function<Evaluation(const std::vector<double>& x)> evaluate;
  /// Optional: runs task(i) for every i in [0, n), several at once. Set it only when `evaluate`
  /// is safe to call concurrently and depends on x alone. The designs the optimiser knows it
  /// will ask for next (a finite-difference gradient's neighbours, the categorical screening)
  /// are then evaluated side by side; they are still counted, cached, reported and returned in
  /// the order a serial run asks for them, so the search takes the same path either way.
  /// Whatever threads `evaluate` starts itself must allow for running beside another
  /// (fem::parallel_tasks does: inside its tasks the FEM runs on one thread).
  std::function<void(int n, const std::function<void(int i)>& task)> run_concurrently;
};

/// Reported after every real evaluation (and, with Options::report_cache_hits,
/// after every cache hit).
struct Progress {
  int evaluation = 0;          ///< 1-based count of real evaluations so far
  std::vector<double> x;       ///< physical units
  Evaluation value;
  bool cached = false;         ///< true: served from the cache, cost nothing
  std::string phase;           ///< "start 2", "integer neighbours n=3", "categorical screening", ...
  double best_feasible_objective = 0;  ///< +infinity while no feasible design is known
};

struct Options {
  /// One of algorithm_names(): "nlopt:cobyla", "nlopt:auglag_bobyqa",
  /// "nlopt:isres", "nlopt:slsqp", "nlopt:ccsaq", "ipopt".
  std::string algorithm = "nlopt:cobyla";
  int max_evaluations = 200;          ///< real (uncached) evaluations, everything together
  double relative_tolerance = 1e-4;   ///< on u (normalised x, absolute in [0,1]) and relative on f
  double constraint_tolerance = 1e-6; ///< a design is feasible when every g_i <= this
  /// Multi-start: the first start at x0 (if given) else the centre, the others
  /// from a Latin-hypercube sample seeded with `seed`; the budget is shared.
  int starts = 1;
  unsigned seed = 1;                  ///< starts and nlopt:isres (NLopt's global seed)
  std::vector<double> x0;             ///< optional start, physical units
  double finite_difference_step = 1e-3;  ///< in normalised space (fraction of upper − lower)
  int categorical_keep = 2;           ///< how many categorical combinations get a full optimisation
  bool report_cache_hits = false;     ///< also call on_evaluation for cache hits (cached=true)
  std::function<void(const Progress&)> on_evaluation;
};

struct Result {
  std::vector<double> x;       ///< the best design, physical units
  Evaluation best;             ///< its evaluation
  bool feasible = false;
  int evaluations = 0;         ///< real evaluations
  int cache_hits = 0;
  double seconds = 0;
  std::string stop_reason;
  std::vector<Progress> history;  ///< every real evaluation, in order
};

/// The valid values of Options::algorithm.
const std::vector<std::string>& algorithm_names();

/// Throws std::invalid_argument for a malformed problem or options (unknown
/// algorithm: the message lists the valid names). Never throws for a failing
/// evaluation. Exceptions from Options::on_evaluation propagate (after the
/// NLopt/Ipopt run is stopped cleanly).
Result minimise(const Problem& problem, const Options& options);

}  // namespace softarm::optimise

// Finite-difference linearisation of the relaxed objective for the
// gradient-based algorithms (nlopt:slsqp, nlopt:ccsaq, ipopt).
//
// Forward differences in normalised space with step h (Options::
// finite_difference_step, a fraction of each variable's range), backward at the
// upper bound or when the forward point fails. The objective gradient and the
// constraint Jacobian come from the same n+1 evaluations, which the cache makes
// free when the solver asks for them separately.
//
// Cost: n+1 FEM solves per gradient. This is where an adjoint would pay: the
// discrete adjoint of the FEM equilibrium (one linear solve with the already
// factorised tangent per objective/constraint) gives the whole gradient for
// about the price of one solve, independent of n. With the handful of design
// variables of the arm the finite differences are affordable; with tens of
// shape variables they are not.
#pragma once

#include <string>
#include <vector>

#include "engine/optimiser/relaxed_objective.hpp"

namespace softarm::optimise::detail {

struct Linearisation {
  Evaluation value;                        ///< at u (value.ok false: no gradient)
  std::vector<double> objective_gradient;  ///< n, d f / d u
  std::vector<double> constraint_jacobian; ///< m x n row-major, d g_i / d u_j
  bool gradient_ok = false;                ///< false: some component had no successful neighbour
  std::string failure_reason;
};

/// Throws BudgetExhausted (from the cache).
Linearisation linearise(RelaxedObjective& f, const std::vector<double>& u, double step);

}  // namespace softarm::optimise::detail

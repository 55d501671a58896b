#pragma once
// Conjugate gradients on K d = b with a preconditioner M⁻¹ (Saad, Iterative Methods
// for Sparse Linear Systems, 2nd ed., Alg. 9.1). softarm's preconditioner is the
// Cholesky factor of an earlier tangent of the same mesh (LinearSolver::solve_reusing_factor):
// between two Newton iterations, or two load steps, the tangent changes little, so
// M⁻¹K is close to the identity and a few CG iterations, each one matrix product and
// one pair of triangular solves, replace a factorisation.
//
// CG needs K symmetric positive definite. It stops at the first search direction of
// non-positive curvature (pᵀKp ≤ 0): a certificate that K is not positive definite,
// on which the caller factorises instead (and learns the inertia from CHOLMOD).
//
// A caller with something better to do than iterate may let CG give up early (LinearSolver's solves
// on a held factor, which factorise instead; not volume control's, whose fallback is an LU): from
// its fourth iteration on, where the smallest relative residual so far, r, reached from the first
// iteration's r₁ at the mean rate ρ = (r/r₁)^(1/(k−1)), projects the tolerance beyond 1.5 times the
// iteration budget (k + log(tol/r)/log ρ > 1.5·max). The first iteration's residual, not
// ‖b‖, is the reference: CG's residual norm may rise above ‖b‖ at its first step. CG converges
// faster than geometrically as it goes, so the projection is pessimistic; the factor 1.5 leaves it
// room. On SPL segment 1's cells (`bench_speed --item segment`), whose CG runs on a held factor have
// 10-12 iterations each, 90 of 466 runs ran out of them, each at 10⁻¹-10⁻⁴ when it had to reach
// 10⁻⁵-10⁻¹⁰; replayed over the run's residual histories, the rule stops 73 of them at the fourth to
// seventh iteration, and 5 runs that would have converged (a factorisation each, as a failure costs).
// Run: CG iterations 2,570 → 2,052, factorisations 104 → 105.

#include <functional>

#include "fem/sparse/sparse_pattern.hpp"

namespace softarm::fem {

struct CgResult {
  bool converged = false;           // ‖b − K d‖ ≤ tolerance·‖b‖
  bool negative_curvature = false;  // stopped on pᵀKp ≤ 0
  int iterations = 0;
  double relative_residual = 1.0;   // ‖b − K d‖ / ‖b‖ at the end
  bool gave_up = false;             // stopped with the tolerance projected out of reach (above)
};

using LinearOperator = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;

/// Solves K d = b from d = 0; `precondition(r)` returns M⁻¹r. d holds the last iterate. With
/// `give_up_early`, stops where the tolerance is out of reach (above).
CgResult preconditioned_cg(const SparseMatrix& K, const Eigen::VectorXd& b, const LinearOperator& precondition,
                           double tolerance, int max_iterations, Eigen::VectorXd& d, bool give_up_early = false);
/// The same with K given by its action `apply(p)` = K p (a matrix plus a low-rank term).
CgResult preconditioned_cg(const LinearOperator& apply, const Eigen::VectorXd& b, const LinearOperator& precondition,
                           double tolerance, int max_iterations, Eigen::VectorXd& d, bool give_up_early = false);

/// Whether CG, k iterations in, its first relative residual `first` and the smallest so far `best`,
/// projects its tolerance beyond 1.5 times `max_iterations` (the rule above).
bool cg_out_of_reach(int k, double first, double best, double tolerance, int max_iterations);

}  // namespace softarm::fem

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
#include <functional>

#include "fem/sparse/sparse_pattern.hpp"

namespace softarm::fem {

struct CgResult {
  bool converged = false;           // ‖b − K d‖ ≤ tolerance·‖b‖
  bool negative_curvature = false;  // stopped on pᵀKp ≤ 0
  int iterations = 0;
  double relative_residual = 1.0;   // ‖b − K d‖ / ‖b‖ at the end
};

using LinearOperator = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;

/// Solves K d = b from d = 0; `precondition(r)` returns M⁻¹r. d holds the last iterate.
CgResult preconditioned_cg(const SparseMatrix& K, const Eigen::VectorXd& b, const LinearOperator& precondition,
                           double tolerance, int max_iterations, Eigen::VectorXd& d);
/// The same with K given by its action `apply(p)` = K p (a matrix plus a low-rank term).
CgResult preconditioned_cg(const LinearOperator& apply, const Eigen::VectorXd& b, const LinearOperator& precondition,
                           double tolerance, int max_iterations, Eigen::VectorXd& d);

}  // namespace softarm::fem

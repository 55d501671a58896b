#pragma once
// A supernodal Cholesky factor copied to single precision, for preconditioning.
//
// Conjugate gradients on an earlier factor (LinearSolver::solve_reusing_factor) spends most of its
// time in the two triangular sweeps with L, which read all of L once each and so run at the speed
// of memory, not of the arithmetic. L in floats is half the bytes to read. As a preconditioner it
// needs no more: rounding L to single precision perturbs it by δL with |δL| ≤ u|L| (u = 2⁻²⁴), and
// the preconditioned operator (L̃L̃ᵀ)⁻¹K differs from (LLᵀ)⁻¹K by O(u·κ(L)) = O(u·√κ(K)) in norm:
// 10⁻³ for a tangent conditioned at 10¹⁰, against the 10⁻²–10⁻¹ by which the tangent CG solves
// with differs from the one that was factorised. CG computes its residuals with K in double
// precision, so the answer's accuracy is CG's tolerance, as with the double factor.
#include <vector>

#include <Eigen/Core>
#include <cholmod.h>

namespace softarm::fem {

class SinglePrecisionFactor {
 public:
  /// Copies CHOLMOD's factor L (LLᵀ = P(A + βI)Pᵀ) where it is supernodal LLᵀ with int indices;
  /// false, leaving this empty, where it is not (a simplicial or LDLᵀ factor).
  bool assign(const cholmod_factor& L);
  bool empty() const { return n_ == 0; }
  void clear();
  /// x with L̃L̃ᵀ(Px) = Pb, in single precision: b scaled to unit norm, the supernodes' forward and
  /// backward sweeps (a triangular solve on each diagonal block, a matrix-vector product with the
  /// rows below it), the scale restored.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;

 private:
  int n_ = 0;
  std::vector<int> perm_;     // (Pb)[k] = b[perm_[k]]
  std::vector<int> super_;    // supernode s holds the columns super_[s] … super_[s + 1] − 1
  std::vector<int> row_start_;    // its row indices: rows_[row_start_[s] … row_start_[s + 1])
  std::vector<int> rows_;
  std::vector<long> value_start_;  // its nrow × ncol block, column-major, from values_[value_start_[s]]
  std::vector<float> values_;
  mutable std::vector<float> y_, below_;  // the sweeps' vector and one supernode's rows below its block
};

}  // namespace softarm::fem

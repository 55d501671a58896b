#pragma once
// Sparse direct solves with SuiteSparse. The symmetric tangent is factorised
// with CHOLMOD's LLᵀ (simplicial or supernodal, CHOLMOD chooses from the
// flop count: simplicial wins on 2D meshes, supernodal on 3D ones); its symbolic analysis (fill-reducing ordering,
// elimination tree) is done once per sparsity pattern and reused for every
// Newton iteration. When the tangent is not positive definite (past a limit
// point, or far from equilibrium) the Cholesky fails and the solve falls back
// to UMFPACK's LU, whose symbolic analysis is likewise kept.
#include <Eigen/CholmodSupport>
#include <Eigen/UmfPackSupport>
#include <memory>

#include "fem/assembly/sparse_pattern.hpp"

namespace softarm::fem {

class LinearSolver {
 public:
  enum class Status { positive_definite, indefinite, singular };

  LinearSolver();
  /// Factorises K (same pattern every call). Returns positive_definite when
  /// Cholesky succeeded, indefinite when LU was needed and succeeded, singular otherwise.
  Status factorize(const SparseMatrix& K);
  Eigen::VectorXd solve(const Eigen::VectorXd& b);
  Status status() const { return status_; }

  // Timings of the last call, seconds (for benchmarks).
  double analyse_seconds = 0.0, factorize_seconds = 0.0, solve_seconds = 0.0;
  int factorizations = 0, lu_fallbacks = 0;

 private:
  Eigen::CholmodDecomposition<SparseMatrix, Eigen::Lower> cholesky_;
  Eigen::UmfPackLU<SparseMatrix> lu_;
  bool cholesky_analysed_ = false, lu_analysed_ = false;
  Status status_ = Status::singular;
};

}  // namespace softarm::fem

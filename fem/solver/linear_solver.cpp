#include "fem/solver/linear_solver.hpp"

#include <chrono>

namespace softarm::fem {
namespace {
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

LinearSolver::LinearSolver() {
  cholesky_.setMode(Eigen::CholmodAuto);
  cholesky_.cholmod().final_ll = 1;     // LLᵀ: fails (and says so) on an indefinite tangent
  cholesky_.cholmod().print = 0;        // a failed Cholesky is an expected event, not a warning
  cholesky_.cholmod().quick_return_if_not_posdef = 1;
}

LinearSolver::Status LinearSolver::factorize(const SparseMatrix& K) {
  auto t0 = std::chrono::steady_clock::now();
  if (!cholesky_analysed_) {
    cholesky_.analyzePattern(K);
    cholesky_analysed_ = true;
    analyse_seconds += seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
  }
  ++factorizations;
  cholesky_.factorize(K);
  if (cholesky_.info() == Eigen::Success) {
    factorize_seconds += seconds_since(t0);
    return status_ = Status::positive_definite;
  }
  ++lu_fallbacks;
  if (!lu_analysed_) {
    lu_.analyzePattern(K);
    lu_analysed_ = true;
  }
  lu_.factorize(K);
  factorize_seconds += seconds_since(t0);
  return status_ = (lu_.info() == Eigen::Success ? Status::indefinite : Status::singular);
}

Eigen::VectorXd LinearSolver::solve(const Eigen::VectorXd& b) {
  const auto t0 = std::chrono::steady_clock::now();
  Eigen::VectorXd x = status_ == Status::positive_definite ? Eigen::VectorXd(cholesky_.solve(b))
                                                           : Eigen::VectorXd(lu_.solve(b));
  solve_seconds += seconds_since(t0);
  return x;
}

}  // namespace softarm::fem

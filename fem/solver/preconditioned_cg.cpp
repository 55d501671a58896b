#include "fem/solver/preconditioned_cg.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace softarm::fem {

bool cg_out_of_reach(int k, double first, double best, double tolerance, int max_iterations) {
  constexpr int kFirstCheck = 4;
  constexpr double kSlack = 1.5;  // of the budget
  if (k < kFirstCheck || k >= max_iterations || best <= tolerance) return false;
  const double rate = std::pow(best / first, 1.0 / (k - 1));  // mean reduction per iteration since the first
  if (!(rate < 1.0)) return true;
  return k + std::log(tolerance / best) / std::log(rate) > kSlack * max_iterations;
}

CgResult preconditioned_cg(const SparseMatrix& K, const Eigen::VectorXd& b, const LinearOperator& precondition,
                           double tolerance, int max_iterations, Eigen::VectorXd& d, bool give_up_early) {
  return preconditioned_cg([&K](const Eigen::VectorXd& p) { return Eigen::VectorXd(K * p); }, b, precondition,
                           tolerance, max_iterations, d, give_up_early);
}

CgResult preconditioned_cg(const LinearOperator& apply, const Eigen::VectorXd& b, const LinearOperator& precondition,
                           double tolerance, int max_iterations, Eigen::VectorXd& d, bool give_up_early) {
  CgResult out;
  d = Eigen::VectorXd::Zero(b.size());
  const double b_norm = b.norm();
  if (b_norm == 0.0) {
    out.converged = true;
    out.relative_residual = 0.0;
    return out;
  }
  Eigen::VectorXd r = b;
  Eigen::VectorXd z = precondition(r);
  Eigen::VectorXd p = z;
  double rz = r.dot(z);
  double first = 0.0, best = std::numeric_limits<double>::infinity();  // relative residuals (the give-up rule)
  for (int k = 0; k < max_iterations; ++k) {
    const Eigen::VectorXd Kp = apply(p);
    const double curvature = p.dot(Kp);
    if (!(curvature > 0.0)) {  // also catches NaN
      out.negative_curvature = true;
      return out;
    }
    const double alpha = rz / curvature;
    d += alpha * p;
    r -= alpha * Kp;
    out.iterations = k + 1;
    out.relative_residual = r.norm() / b_norm;
    if (out.relative_residual <= tolerance) {
      out.converged = true;
      return out;
    }
    if (k == 0) first = out.relative_residual;
    best = std::min(best, out.relative_residual);
    if (give_up_early && cg_out_of_reach(out.iterations, first, best, tolerance, max_iterations)) {
      out.gave_up = true;
      return out;
    }
    z = precondition(r);
    const double rz_next = r.dot(z);
    p = z + (rz_next / rz) * p;
    rz = rz_next;
  }
  return out;
}

}  // namespace softarm::fem

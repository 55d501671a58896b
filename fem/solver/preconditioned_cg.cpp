#include "fem/solver/preconditioned_cg.hpp"

#include <cmath>

namespace softarm::fem {

CgResult preconditioned_cg(const SparseMatrix& K, const Eigen::VectorXd& b, const LinearOperator& precondition,
                           double tolerance, int max_iterations, Eigen::VectorXd& d) {
  return preconditioned_cg([&K](const Eigen::VectorXd& p) { return Eigen::VectorXd(K * p); }, b, precondition,
                           tolerance, max_iterations, d);
}

CgResult preconditioned_cg(const LinearOperator& apply, const Eigen::VectorXd& b, const LinearOperator& precondition,
                           double tolerance, int max_iterations, Eigen::VectorXd& d) {
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
    z = precondition(r);
    const double rz_next = r.dot(z);
    p = z + (rz_next / rz) * p;
    rz = rz_next;
  }
  return out;
}

}  // namespace softarm::fem

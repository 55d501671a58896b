#include "fem/materials/symmetric_eigen3.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace softarm::fem {

bool symmetric_eigen3(const Eigen::Matrix3d& C, Eigen::Vector3d& c, Eigen::Matrix3d& Q) {
  if (C(0, 2) == 0.0 && C(1, 2) == 0.0) {
    // One Jacobi rotation diagonalises the (x, y) block exactly (Golub & Van Loan §8.5.2).
    const double a = C(0, 0), b = C(0, 1), d = C(1, 1);
    double cs = 1.0, sn = 0.0, t = 0.0;
    if (b != 0.0) {
      const double tau = (d - a) / (2.0 * b);
      t = (tau >= 0.0 ? 1.0 : -1.0) / (std::abs(tau) + std::sqrt(1.0 + tau * tau));
      cs = 1.0 / std::sqrt(1.0 + t * t);
      sn = t * cs;
    }
    c << a - t * b, d + t * b, C(2, 2);
    Q << cs, sn, 0.0, -sn, cs, 0.0, 0.0, 0.0, 1.0;
    return c.allFinite();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  // The closed form first: about 2.5× cheaper than the iterative solver; its eigenvalues come sorted,
  // accurate to ~ε‖C‖/gap, so the gaps tested here are the true ones to that accuracy.
  eig.computeDirect(C, Eigen::ComputeEigenvectors);
  c = eig.eigenvalues();
  const double apart = closed_form_eigenvalue_gap * std::abs(c[2]);
  if (c[1] - c[0] >= apart && c[2] - c[1] >= apart && c.allFinite() && eig.eigenvectors().allFinite()) {
    Q = eig.eigenvectors();
    return true;
  }
  eig.compute(C, Eigen::ComputeEigenvectors);
  if (eig.info() != Eigen::Success) return false;
  c = eig.eigenvalues();
  Q = eig.eigenvectors();
  return c.allFinite() && Q.allFinite();
}

Eigen::Vector3d ascending_eigenvalues(const Eigen::Matrix3d& C) {
  Eigen::Vector3d c;
  Eigen::Matrix3d Q;
  if (symmetric_eigen3(C, c, Q)) {
    std::sort(c.data(), c.data() + 3);  // the Jacobi path leaves the hoop value last
    return c;
  }
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(C, Eigen::EigenvaluesOnly).eigenvalues();
}

}  // namespace softarm::fem

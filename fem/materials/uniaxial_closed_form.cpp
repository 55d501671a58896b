#include "fem/materials/uniaxial_closed_form.hpp"

#include <cmath>

namespace softarm::fem {

Eigen::MatrixXd invariant_polynomial_basis(const Eigen::VectorXd& stretch, int terms) {
  Eigen::MatrixXd B(stretch.size(), terms);
  for (Eigen::Index r = 0; r < stretch.size(); ++r) {
    const double l = stretch[r];
    const double prefactor = 2.0 * (l - 1.0 / (l * l));  // P = 2(λ − λ^-2) ∂W̄/∂Ī1
    const double x = l * l + 2.0 / l - 3.0;               // Ī1 − 3
    for (int i = 1; i <= terms; ++i) B(r, i - 1) = prefactor * i * std::pow(x, i - 1);  // ∂[(Ī1−3)^i]/∂Ī1
  }
  return B;
}

double ogden_basis(double stretch, double alpha) {
  return (2.0 / alpha) * (std::pow(stretch, alpha - 1.0) - std::pow(stretch, -0.5 * alpha - 1.0));
}

double ogden_basis_dalpha(double stretch, double alpha) {
  const double log_l = std::log(stretch);
  const double up = std::pow(stretch, alpha - 1.0), down = std::pow(stretch, -0.5 * alpha - 1.0);
  // d/dα [(2/α)(u − d)] with du/dα = u ln λ, dd/dα = −(1/2) d ln λ.
  return -(2.0 / (alpha * alpha)) * (up - down) + (2.0 / alpha) * log_l * (up + 0.5 * down);
}

Eigen::MatrixXd ogden_basis(const Eigen::VectorXd& stretch, const Eigen::VectorXd& alpha) {
  Eigen::MatrixXd B(stretch.size(), alpha.size());
  for (Eigen::Index r = 0; r < stretch.size(); ++r)
    for (Eigen::Index i = 0; i < alpha.size(); ++i) B(r, i) = ogden_basis(stretch[r], alpha[i]);
  return B;
}

}  // namespace softarm::fem

#include "fem/materials/least_squares.hpp"

#include <Eigen/QR>

namespace softarm::fem {

Eigen::VectorXd linear_least_squares(const Eigen::MatrixXd& B, const Eigen::VectorXd& y) {
  Eigen::VectorXd scale = B.colwise().norm().transpose();
  for (Eigen::Index k = 0; k < scale.size(); ++k)
    if (!(scale[k] > 0.0)) scale[k] = 1.0;  // an all-zero column keeps coefficient 0
  const Eigen::MatrixXd scaled = B * scale.cwiseInverse().asDiagonal();
  const Eigen::VectorXd c = scaled.completeOrthogonalDecomposition().solve(y);
  return c.cwiseQuotient(scale);
}

double r_squared(const Eigen::VectorXd& y, const Eigen::VectorXd& fitted) {
  const double ss_res = (y - fitted).squaredNorm();
  const double ss_tot = (y.array() - y.mean()).matrix().squaredNorm();
  return 1.0 - ss_res / ss_tot;
}

}  // namespace softarm::fem

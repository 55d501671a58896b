#pragma once
// Linear least squares min ||B c − y||₂ for the moduli of a law that is linear
// in them (uniaxial_closed_form.hpp). Columns are scaled to unit norm first
// (Yeoh's (Ī1 − 3)² column is ~10³ times the first at λ = 7), then solved by a
// complete orthogonal decomposition, which returns the minimum-norm solution
// when columns are (numerically) dependent, e.g. two equal Ogden exponents.
#include <Eigen/Core>

namespace softarm::fem {

Eigen::VectorXd linear_least_squares(const Eigen::MatrixXd& B, const Eigen::VectorXd& y);

/// Coefficient of determination R² = 1 − SS_res/SS_tot (SS_tot about the mean of y).
double r_squared(const Eigen::VectorXd& y, const Eigen::VectorXd& fitted);

}  // namespace softarm::fem

#include "fem/reduced/fibre_law.hpp"

#include <algorithm>
#include <cmath>

#include "fem/materials/drucker_stability.hpp"

namespace softarm::fem {

FibreLaw::FibreLaw(const HyperelasticLaw& law, double lambda_min, double lambda_max, int points)
    : FibreLaw([&law](double l) { return nominal_stress(law, LoadingMode::uniaxial, l); }, lambda_min, lambda_max,
               points) {}

FibreLaw::FibreLaw(const std::function<double(double)>& stress, double lambda_min, double lambda_max, int points)
    : lo_(lambda_min), hi_(lambda_max), step_((lambda_max - lambda_min) / (points - 1)) {
  p_.resize(points);
  dp_.resize(points);
  const double h = 1e-5;
  for (int i = 0; i < points; ++i) {
    const double l = lo_ + i * step_;
    p_[i] = stress(l);
    dp_[i] = (stress(l + h) - stress(l - h)) / (2 * h);
  }
}

namespace {
// Cubic Hermite interpolation on the table (values and exact slopes at the
// nodes): C1, and tangent() is the exact derivative of stress(), so the rod's
// Newton iterations see a consistent Jacobian.
struct Cell {
  int i;
  double t;
};
Cell locate(double lo, double step, std::size_t n, double lambda) {
  const double s = (lambda - lo) / step;
  const int i = std::clamp(static_cast<int>(std::floor(s)), 0, static_cast<int>(n) - 2);
  return {i, s - i};
}
}  // namespace

double FibreLaw::stress(double lambda) const {
  const auto [i, t] = locate(lo_, step_, p_.size(), lambda);
  if (t < 0) return p_[0] + dp_[0] * (lambda - lo_);
  if (t > 1) return p_.back() + dp_.back() * (lambda - hi_);
  const double h00 = (1 + 2 * t) * (1 - t) * (1 - t), h10 = t * (1 - t) * (1 - t), h01 = t * t * (3 - 2 * t),
               h11 = t * t * (t - 1);
  return h00 * p_[i] + h10 * step_ * dp_[i] + h01 * p_[i + 1] + h11 * step_ * dp_[i + 1];
}

double FibreLaw::tangent(double lambda) const {
  const auto [i, t] = locate(lo_, step_, p_.size(), lambda);
  if (t < 0) return dp_[0];
  if (t > 1) return dp_.back();
  const double d00 = 6 * t * (t - 1), d10 = (1 - t) * (1 - 3 * t), d01 = -d00, d11 = t * (3 * t - 2);
  return (d00 * p_[i] + d01 * p_[i + 1]) / step_ + d10 * dp_[i] + d11 * dp_[i + 1];
}

void FibreLaw::evaluate(double lambda, double& stress, double& tangent) const {
  const auto [i, t] = locate(lo_, step_, p_.size(), lambda);
  if (t < 0 || t > 1) {
    stress = this->stress(lambda);
    tangent = this->tangent(lambda);
    return;
  }
  const double u = 1 - t;
  const double h00 = (1 + 2 * t) * u * u, h10 = t * u * u, h01 = t * t * (3 - 2 * t), h11 = t * t * (t - 1);
  const double d00 = 6 * t * (t - 1), d10 = u * (1 - 3 * t), d11 = t * (3 * t - 2);
  stress = h00 * p_[i] + h10 * step_ * dp_[i] + h01 * p_[i + 1] + h11 * step_ * dp_[i + 1];
  tangent = d00 * (p_[i] - p_[i + 1]) / step_ + d10 * dp_[i] + d11 * dp_[i + 1];
}

}  // namespace softarm::fem

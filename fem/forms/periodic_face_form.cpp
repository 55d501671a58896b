#include "fem/forms/periodic_face_form.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace softarm::fem {

PeriodicFaceForm::PeriodicFaceForm(std::vector<std::pair<int, int>> pairs, const Vector& reference,
                                   int shear_twist_pilot, int stretch_bend_pilot, double penalty,
                                   const std::vector<double>& weights)
    : p1_(shear_twist_pilot), p2_(stretch_bend_pilot), k_(penalty) {
  if (!weights.empty() && weights.size() != pairs.size())
    throw std::invalid_argument("PeriodicFaceForm: " + std::to_string(weights.size()) + " weights for " +
                                std::to_string(pairs.size()) + " pairs");
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const auto [t, b] = pairs[k];
    pairs_.push_back({t, b, reference.segment<3>(3 * t) - reference.segment<3>(3 * b), reference[3 * b],
                      reference[3 * b + 1], weights.empty() ? 1.0 : weights[k]});
  }
}

std::array<int, 12> PeriodicFaceForm::dofs(const Pair& p) const {
  return {3 * p.top,  3 * p.top + 1,  3 * p.top + 2,  3 * p.bottom, 3 * p.bottom + 1, 3 * p.bottom + 2,
          3 * p1_,    3 * p1_ + 1,    3 * p1_ + 2,    3 * p2_,      3 * p2_ + 1,      3 * p2_ + 2};
}

void PeriodicFaceForm::declare_pattern(SparsePattern& pattern) {
  blocks_.clear();
  for (const Pair& p : pairs_) blocks_.push_back(pattern.declare_block(dofs(p)));
}

FormStatus PeriodicFaceForm::add(const Vector& x, double* value, Vector* gradient, HessianAccumulator* hessian) const {
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    const Pair& p = pairs_[k];
    const std::array<int, 12> d = dofs(p);
    // J = ∂r/∂(x_t, x_b, t_x, t_y, φ, a, b, c), 3 × 12.
    Eigen::Matrix<double, 3, 12> J = Eigen::Matrix<double, 3, 12>::Zero();
    J.block<3, 3>(0, 0).setIdentity();
    J.block<3, 3>(0, 3) = -Eigen::Matrix3d::Identity();
    J(0, 6) = -1, J(0, 8) = p.Y;
    J(1, 7) = -1, J(1, 8) = -p.X;
    J(2, 9) = -1, J(2, 10) = -p.X, J(2, 11) = -p.Y;
    Eigen::Matrix<double, 12, 1> q;
    for (int i = 0; i < 12; ++i) q[i] = x[d[i]];
    const Eigen::Vector3d r = J * q - p.offset;
    const double stiffness = k_ * p.weight;
    if (value) *value += 0.5 * stiffness * r.squaredNorm();
    if (gradient) {
      const Eigen::Matrix<double, 12, 1> g = stiffness * J.transpose() * r;
      for (int i = 0; i < 12; ++i) (*gradient)[d[i]] += g[i];
    }
    if (hessian) {
      const Eigen::Matrix<double, 12, 12> h = stiffness * J.transpose() * J;  // column-major, as add_block reads it
      hessian->add_block(0, blocks_[k], h.data());
    }
  }
  return FormStatus::fine();
}

std::vector<std::pair<int, int>> facing_nodes(const std::vector<int>& top, const std::vector<int>& bottom,
                                              const Vector& reference, double tolerance_mm) {
  std::vector<std::pair<int, int>> pairs;
  for (int t : top) {
    int partner = -1;
    for (int b : bottom)
      if (std::abs(reference[3 * t] - reference[3 * b]) <= tolerance_mm &&
          std::abs(reference[3 * t + 1] - reference[3 * b + 1]) <= tolerance_mm) {
        partner = b;
        break;
      }
    if (partner < 0)
      throw std::invalid_argument("facing_nodes: top node " + std::to_string(t) + " has no bottom node below it");
    pairs.emplace_back(t, partner);
  }
  return pairs;
}

}  // namespace softarm::fem

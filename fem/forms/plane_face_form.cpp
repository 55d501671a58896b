#include "fem/forms/plane_face_form.hpp"

#include <array>
#include <cmath>

namespace softarm::fem {

PlaneFaceForm::PlaneFaceForm(std::vector<int> face_nodes, int pilot_node, double z0, double penalty)
    : nodes_(std::move(face_nodes)), pilot_(pilot_node), z0_(z0), k_(penalty) {}

PlaneFaceForm::PlaneFaceForm(std::vector<int> face_nodes, int pilot_node, double z0, double penalty,
                             int reference_node, Eigen::Vector2d reference_xy)
    : nodes_(std::move(face_nodes)),
      pilot_(pilot_node),
      z0_(z0),
      k_(penalty),
      reference_(reference_node),
      reference_xy_(reference_xy) {}

void PlaneFaceForm::declare_pattern(SparsePattern& pattern) {
  blocks_.clear();
  // Per face node: its x, y, z, then a, b, c, then the reference node's x, y.
  for (int n : nodes_) {
    std::vector<int> dofs = {3 * n, 3 * n + 1, 3 * n + 2, 3 * pilot_, 3 * pilot_ + 1, 3 * pilot_ + 2};
    if (reference_ >= 0) dofs.insert(dofs.end(), {3 * reference_, 3 * reference_ + 1});
    blocks_.push_back(pattern.declare_block(dofs));
  }
}

double PlaneFaceForm::max_gap(const Vector& x) const {
  double gap = 0;
  for (int n : nodes_) gap = std::max(gap, std::abs(this->gap(x, n)));
  return gap;
}

Eigen::Vector2d PlaneFaceForm::origin(const Vector& x) const {
  if (reference_ < 0) return Eigen::Vector2d::Zero();
  return Eigen::Vector2d(x[3 * reference_], x[3 * reference_ + 1]) - reference_xy_;
}

double PlaneFaceForm::gap(const Vector& x, int n) const {
  const double a = x[3 * pilot_], b = x[3 * pilot_ + 1], c = x[3 * pilot_ + 2];
  const Eigen::Vector2d u = origin(x);
  return x[3 * n + 2] - z0_ - a - b * (x[3 * n] - u.x()) - c * (x[3 * n + 1] - u.y());
}

FormStatus PlaneFaceForm::add(const Vector& x, double* value, Vector* gradient, HessianAccumulator* hessian) const {
  const double b = x[3 * pilot_ + 1], c = x[3 * pilot_ + 2];
  const Eigen::Vector2d u = origin(x);
  const int m = reference_ >= 0 ? 8 : 6;  // the block's size
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    const int n = nodes_[k];
    const double g = gap(x, n);
    // ∂g/∂(x_i, y_i, z_i, a, b, c[, x_r, y_r])
    const std::array<double, 8> dg = {-b, -c, 1.0, -1.0, -(x[3 * n] - u.x()), -(x[3 * n + 1] - u.y()), b, c};
    if (value) *value += 0.5 * k_ * g * g;
    if (gradient) {
      const std::array<int, 8> dofs = {3 * n,          3 * n + 1,      3 * n + 2,         3 * pilot_,
                                       3 * pilot_ + 1, 3 * pilot_ + 2, 3 * reference_, 3 * reference_ + 1};
      for (int i = 0; i < m; ++i) (*gradient)[dofs[i]] += k_ * g * dg[i];
    }
    if (hessian) {
      std::array<double, 64> h{};
      for (int j = 0; j < m; ++j)
        for (int i = 0; i < m; ++i) h[i + m * j] = k_ * dg[i] * dg[j];
      h[0 + m * 4] -= k_ * g, h[4 + m * 0] -= k_ * g;  // ∂²g/∂x_i∂b = −1
      h[1 + m * 5] -= k_ * g, h[5 + m * 1] -= k_ * g;  // ∂²g/∂y_i∂c = −1
      if (m == 8) {
        h[6 + m * 4] += k_ * g, h[4 + m * 6] += k_ * g;  // ∂²g/∂x_r∂b = +1
        h[7 + m * 5] += k_ * g, h[5 + m * 7] += k_ * g;  // ∂²g/∂y_r∂c = +1
      }
      hessian->add_block(0, blocks_[k], h.data());
    }
  }
  return FormStatus::fine();
}

}  // namespace softarm::fem

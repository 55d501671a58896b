#include "fem/forms/plane_face_form.hpp"

#include <array>
#include <cmath>
#include <span>

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

std::array<int, 8> PlaneFaceForm::block_dofs(int n) const {
  return {3 * n, 3 * n + 1, 3 * n + 2, 3 * pilot_, 3 * pilot_ + 1, 3 * pilot_ + 2, 3 * reference_, 3 * reference_ + 1};
}

void PlaneFaceForm::declare_pattern(SparsePattern& pattern) {
  blocks_.clear();
  for (int n : nodes_) {
    const std::array<int, 8> dofs = block_dofs(n);
    blocks_.push_back(pattern.declare_block(std::span<const int>(dofs.data(), block_size())));
  }
}

PlaneFaceForm::Plane PlaneFaceForm::plane(const Vector& x) const {
  Plane p{x[3 * pilot_], x[3 * pilot_ + 1], x[3 * pilot_ + 2], Eigen::Vector2d::Zero()};
  if (reference_ >= 0) p.origin = Eigen::Vector2d(x[3 * reference_], x[3 * reference_ + 1]) - reference_xy_;
  return p;
}

double PlaneFaceForm::gap(const Vector& x, int n, const Plane& p) const {
  return x[3 * n + 2] - z0_ - p.a - p.b * (x[3 * n] - p.origin.x()) - p.c * (x[3 * n + 1] - p.origin.y());
}

double PlaneFaceForm::max_gap(const Vector& x) const {
  const Plane p = plane(x);
  double gap = 0;
  for (int n : nodes_) gap = std::max(gap, std::abs(this->gap(x, n, p)));
  return gap;
}

FormStatus PlaneFaceForm::add(const Vector& x, double* value, Vector* gradient, HessianAccumulator* hessian) const {
  const Plane p = plane(x);
  const int m = block_size();
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    const int n = nodes_[k];
    const double g = gap(x, n, p);
    // ∂g/∂(x_i, y_i, z_i, a, b, c[, x_r, y_r])
    const std::array<double, 8> dg = {
        -p.b, -p.c, 1.0, -1.0, -(x[3 * n] - p.origin.x()), -(x[3 * n + 1] - p.origin.y()), p.b, p.c};
    if (value) *value += 0.5 * k_ * g * g;
    if (gradient) {
      const std::array<int, 8> dofs = block_dofs(n);
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

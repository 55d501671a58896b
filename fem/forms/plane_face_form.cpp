#include "fem/forms/plane_face_form.hpp"

#include <array>
#include <cmath>

namespace softarm::fem {

PlaneFaceForm::PlaneFaceForm(std::vector<int> face_nodes, int pilot_node, double z0, double penalty)
    : nodes_(std::move(face_nodes)), pilot_(pilot_node), z0_(z0), k_(penalty) {}

void PlaneFaceForm::declare_pattern(SparsePattern& pattern) {
  blocks_.clear();
  // Per face node: its x, y, z, then a, b, c.
  for (int n : nodes_) {
    const std::array<int, 6> dofs = {3 * n, 3 * n + 1, 3 * n + 2, 3 * pilot_, 3 * pilot_ + 1, 3 * pilot_ + 2};
    blocks_.push_back(pattern.declare_block(dofs));
  }
}

double PlaneFaceForm::max_gap(const Vector& x) const {
  double gap = 0;
  for (int n : nodes_) gap = std::max(gap, std::abs(this->gap(x, n)));
  return gap;
}

double PlaneFaceForm::gap(const Vector& x, int n) const {
  const double a = x[3 * pilot_], b = x[3 * pilot_ + 1], c = x[3 * pilot_ + 2];
  return x[3 * n + 2] - z0_ - a - b * x[3 * n] - c * x[3 * n + 1];
}

FormStatus PlaneFaceForm::add(const Vector& x, double* value, Vector* gradient, HessianAccumulator* hessian) const {
  const double b = x[3 * pilot_ + 1], c = x[3 * pilot_ + 2];
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    const int n = nodes_[k];
    const double g = gap(x, n);
    const std::array<double, 6> dg = {-b, -c, 1.0, -1.0, -x[3 * n], -x[3 * n + 1]};  // ∂g/∂(x_i, y_i, z_i, a, b, c)
    if (value) *value += 0.5 * k_ * g * g;
    if (gradient) {
      const std::array<int, 6> dofs = {3 * n, 3 * n + 1, 3 * n + 2, 3 * pilot_, 3 * pilot_ + 1, 3 * pilot_ + 2};
      for (int i = 0; i < 6; ++i) (*gradient)[dofs[i]] += k_ * g * dg[i];
    }
    if (hessian) {
      std::array<double, 36> h{};
      for (int j = 0; j < 6; ++j)
        for (int i = 0; i < 6; ++i) h[i + 6 * j] = k_ * dg[i] * dg[j];
      h[0 + 6 * 4] -= k_ * g, h[4 + 6 * 0] -= k_ * g;  // ∂²g/∂x_i∂b = −1
      h[1 + 6 * 5] -= k_ * g, h[5 + 6 * 1] -= k_ * g;  // ∂²g/∂y_i∂c = −1
      hessian->add_block(0, blocks_[k], h.data());
    }
  }
  return FormStatus::fine();
}

}  // namespace softarm::fem

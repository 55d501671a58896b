#include "fem/forms/mean_displacement_form.hpp"

#include <stdexcept>

namespace softarm::fem {

MeanDisplacementForm::MeanDisplacementForm(std::vector<int> dofs, std::vector<double> reference, double penalty)
    : dofs_(std::move(dofs)), reference_(std::move(reference)), k_(penalty) {
  if (dofs_.empty() || dofs_.size() != reference_.size())
    throw std::logic_error("MeanDisplacementForm: needs at least one dof and one reference value per dof");
  const double n = static_cast<double>(dofs_.size());
  hessian_.assign(dofs_.size() * dofs_.size(), k_ / (n * n));
}

void MeanDisplacementForm::declare_pattern(SparsePattern& pattern) { block_ = pattern.declare_block(dofs_); }

double MeanDisplacementForm::mean_displacement(const Vector& x) const {
  double sum = 0;
  for (std::size_t i = 0; i < dofs_.size(); ++i) sum += x[dofs_[i]] - reference_[i];
  return sum / static_cast<double>(dofs_.size());
}

FormStatus MeanDisplacementForm::add(const Vector& x, double* value, Vector* gradient,
                                     HessianAccumulator* hessian) const {
  const double n = static_cast<double>(dofs_.size()), m = mean_displacement(x);
  if (value) *value += 0.5 * k_ * m * m;
  if (gradient)
    for (int d : dofs_) (*gradient)[d] += k_ * m / n;
  if (hessian) hessian->add_block(0, block_, hessian_.data());
  return FormStatus::fine();
}

}  // namespace softarm::fem

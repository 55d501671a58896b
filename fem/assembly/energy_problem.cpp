#include "fem/assembly/energy_problem.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "fem/core/elapsed_seconds.hpp"
#include "fem/core/parallel.hpp"

namespace softarm::fem {

EnergyProblem::EnergyProblem(Vector reference_positions, DirichletConstraints constraints)
    : X_(std::move(reference_positions)),
      constraints_(std::move(constraints)),
      prescribed_(X_.size(), 0),
      pattern_(static_cast<int>(X_.size())) {
  for (int d : constraints_.dofs) {
    if (d < 0 || d >= X_.size()) throw std::logic_error("EnergyProblem: constrained dof out of range");
    prescribed_[d] = 1;
  }
}

Evaluation& Evaluation::operator=(Evaluation&& other) noexcept {
  energy = other.energy;
  gradient = std::move(other.gradient);
  hessian.swap(other.hessian);
  load_norm = other.load_norm;
  reaction_norm = other.reaction_norm;
  status = std::move(other.status);
  return *this;
}

void EnergyProblem::add_form(std::shared_ptr<Form> form) { forms_.push_back(std::move(form)); }

void EnergyProblem::finalize() {
  for (auto& f : forms_) f->declare_pattern(pattern_);
  pattern_.finalize();
  const SparseMatrix& K = pattern_.zero_matrix();
  const int* outer = K.outerIndexPtr();
  const int* inner = K.innerIndexPtr();
  for (int c = 0; c < K.outerSize(); ++c)
    for (int k = outer[c]; k < outer[c + 1]; ++k)
      if (prescribed_[c] || prescribed_[inner[k]])
        (inner[k] == c ? prescribed_diagonal_ : prescribed_off_diagonal_).push_back(k);
}

void EnergyProblem::apply_constraints(Vector& x, double scale) const {
  for (std::size_t k = 0; k < constraints_.dofs.size(); ++k) {
    const int d = constraints_.dofs[k];
    x[d] = X_[d] + scale * constraints_.displacement[k];
  }
}

void EnergyProblem::zero_prescribed(Vector& v) const {
  for (int d : constraints_.dofs) v[d] = 0.0;
}

Vector EnergyProblem::advanced(const Vector& x, const Vector& dx) const {
  Vector out = x + dx;
  if (inclusions_.empty()) return out;
  inclusions_.correct_update(x, dx, out);
  for (int d : constraints_.dofs) out[d] = x[d] + dx[d];
  return out;
}

Evaluation EnergyProblem::evaluate(const Vector& x, bool want_gradient, bool want_hessian) const {
  if (!pattern_.finalized()) throw std::logic_error("EnergyProblem::evaluate before finalize()");
  const AddElapsedSeconds timer(assembly_seconds_);  // every exit path counts
  ++evaluations_;
  Evaluation out;
  const int n = num_dofs();
  Vector load_gradient = Vector::Zero(want_gradient ? n : 0);
  if (want_gradient) out.gradient = Vector::Zero(n);
  std::unique_ptr<HessianAccumulator> acc;
  if (want_hessian) acc = std::make_unique<HessianAccumulator>(pattern_, thread_count());
  for (const auto& f : forms_) {
    Vector* g = want_gradient ? (f->is_load() ? &load_gradient : &out.gradient) : nullptr;
    out.status = f->add(x, &out.energy, g, acc.get());
    if (!out.status.ok) return out;
  }
  if (want_gradient) {
    zero_prescribed(load_gradient);
    out.load_norm = load_gradient.norm();
    out.gradient += load_gradient;
    double reactions = 0.0;
    for (int d : constraints_.dofs) reactions += out.gradient[d] * out.gradient[d];
    out.reaction_norm = std::sqrt(reactions);
    zero_prescribed(out.gradient);
  }
  if (want_hessian) {
    acc->finish(out.hessian);
    // Identity rows and columns for prescribed dofs (keeps symmetry and pattern).
    double* values = out.hessian.valuePtr();
    for (const int k : prescribed_diagonal_) values[k] = 1.0;
    for (const int k : prescribed_off_diagonal_) values[k] = 0.0;
  }
  return out;
}

}  // namespace softarm::fem

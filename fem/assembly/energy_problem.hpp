#pragma once
// The discrete problem: total potential energy Π(x) = Σ forms, minimised
// over the positions x subject to prescribed (Dirichlet) dofs.
//
// Prescribed dofs are kept in the system with their rows and columns
// replaced by the identity, so the pattern (and CHOLMOD's symbolic analysis)
// never changes and the matrix stays symmetric positive definite whenever
// the free block is.
#include <algorithm>
#include <memory>
#include <vector>

#include "fem/assembly/stiff_inclusions.hpp"
#include "fem/forms/form.hpp"

namespace softarm::fem {

/// x_d = X_d + scale · displacement_d for each prescribed dof d.
struct DirichletConstraints {
  std::vector<int> dofs;
  std::vector<double> displacement;  // at scale 1, mm
  void fix(int dof, double value = 0.0) {
    dofs.push_back(dof);
    displacement.push_back(value);
  }
};

struct Evaluation {
  // Eigen 3.4's SparseMatrix has no move constructor or move assignment: moving an Evaluation
  // member by member copied the Hessian (3D cells: tens of MB, three copies a Newton iteration).
  // These moves swap it instead; copies stay copies.
  Evaluation() = default;
  Evaluation(const Evaluation&) = default;
  Evaluation& operator=(const Evaluation&) = default;
  Evaluation(Evaluation&& other) noexcept { *this = std::move(other); }
  Evaluation& operator=(Evaluation&& other) noexcept;

  double energy = 0.0;
  Vector gradient;         // zero at prescribed dofs
  SparseMatrix hessian;    // identity rows/columns at prescribed dofs
  double load_norm = 0.0;      // ‖gradient of the load forms‖ over free dofs
  double reaction_norm = 0.0;  // ‖gradient at the prescribed dofs‖: the support reactions
  /// The force scale Newton's residual is measured against: applied loads or,
  /// for displacement-driven problems, the reactions they cause.
  double force_scale() const { return std::max(load_norm, reaction_norm); }
  FormStatus status;
};

class EnergyProblem {
 public:
  EnergyProblem(Vector reference_positions, DirichletConstraints constraints);
  void add_form(std::shared_ptr<Form> form);
  /// Builds the sparsity pattern; call after the last add_form.
  void finalize();

  /// Energy, and (if asked) gradient and Hessian, at x.
  Evaluation evaluate(const Vector& x, bool want_gradient, bool want_hessian) const;
  /// Sets the prescribed dofs of x for the given displacement scale.
  void apply_constraints(Vector& x, double scale) const;

  int num_dofs() const { return static_cast<int>(X_.size()); }
  const Vector& reference_positions() const { return X_; }
  const std::vector<char>& is_prescribed() const { return prescribed_; }
  const std::vector<std::shared_ptr<Form>>& forms() const { return forms_; }
  /// Zeroes the prescribed entries of a dof vector.
  void zero_prescribed(Vector& v) const;

  /// Stiff parts whose rotations the update and the predictor treat exactly (stiff_inclusions.hpp).
  void set_stiff_inclusions(StiffInclusions inclusions) { inclusions_ = std::move(inclusions); }
  const StiffInclusions& stiff_inclusions() const { return inclusions_; }
  /// x ⊕ δx: x + δx, except that each stiff inclusion's best-fit rotation is applied as a finite
  /// rotation; prescribed dofs get exactly x + δx. Without inclusions, x + δx.
  Vector advanced(const Vector& x, const Vector& dx) const;

  /// Accumulated wall time spent in evaluate() and the number of calls (benchmarks).
  double assembly_seconds() const { return assembly_seconds_; }
  int evaluations() const { return evaluations_; }

 private:
  Vector X_;
  DirichletConstraints constraints_;
  std::vector<char> prescribed_;
  // The Hessian's entries in a prescribed dof's row or column (identity there), found once by
  // finalize(): the diagonal ones, set to 1, and the others, set to 0.
  std::vector<int> prescribed_diagonal_, prescribed_off_diagonal_;
  std::vector<std::shared_ptr<Form>> forms_;
  SparsePattern pattern_;
  StiffInclusions inclusions_;
  mutable double assembly_seconds_ = 0.0;
  mutable int evaluations_ = 0;
};

}  // namespace softarm::fem

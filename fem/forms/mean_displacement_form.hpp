#pragma once
// Holds a rigid motion of a body by the mean displacement of a set of its dofs:
//     Π = ½ k m²,   m = (1/n) Σ_d (x_d − X_d),
// with gradient k m / n on every dof and the constant Hessian k / n² on every pair.
//
// Why not a single held node: a body whose energy is exactly invariant under a
// translation t (Π(x + t·v) = Π(x), v the unit translation of every node) has
// K v = 0 at every state, so a penalty on any functional m with ∇m·v ≠ 0 fixes t
// and carries no force at equilibrium (∇Π·v = 0 there forces k m ∇m·v = 0, so m = 0).
// One node held leaves "everything but that node translates" as a mode whose
// stiffness is that node's own diagonal of the tangent, tens of times softer than
// the body's softest deformation (docs/performance.md, "Segment 1's free end near
// 321 kPa"), and off equilibrium the tangent can be indefinite along it. Held by the
// mean of a whole face, the translation has the stiffness k whatever the state.
#include <vector>

#include "fem/forms/form.hpp"

namespace softarm::fem {

class MeanDisplacementForm : public Form {
 public:
  /// `dofs` and their reference values `reference` (same length, at least one);
  /// `penalty` k in N/mm on the mean displacement.
  MeanDisplacementForm(std::vector<int> dofs, std::vector<double> reference, double penalty);
  std::string name() const override { return "mean displacement hold"; }
  void declare_pattern(SparsePattern& pattern) override;
  FormStatus add(const Vector& x, double* value, Vector* gradient, HessianAccumulator* hessian) const override;

  /// m at x, mm.
  double mean_displacement(const Vector& x) const;

 private:
  std::vector<int> dofs_;
  std::vector<double> reference_;
  double k_;
  std::vector<double> hessian_;  // k / n² in every entry: constant
  int block_ = -1;
};

}  // namespace softarm::fem

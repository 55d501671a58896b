#pragma once
// Pressure in a closed chamber as the potential −p·V(x) (PolyFEM, and
// e.g. Bonet & Wood §6.5 "enclosed volume"): its gradient is the exact
// follower pressure load on the discretised chamber wall and its Hessian the
// exact load stiffness, symmetric because the load is conservative for a
// closed chamber. Dropping this stiffness is what makes solvers stall on
// pressurised tubes (see shared/spec/calculix-notes.md).
//
// Axisymmetric volume of a chamber whose (r, z) boundary is the chain of edges
// (a → b): V = Σ π (z_b − z_a)(r_a² + r_a r_b + r_b²)/3, exact for straight
// edges (the volume of revolution of each trapezoid, Pappus–Guldin).
#include "fem/forms/form.hpp"
#include "fem/mesh/mesh.hpp"

namespace softarm::fem {

class ChamberPressureForm : public Form {
 public:
  /// `chamber` indexes mesh.chambers; the pressure is read from load.chamber_pressure_MPa[chamber].
  ChamberPressureForm(const Mesh& mesh, int chamber, const LoadState& load);
  std::string name() const override { return "pressure(" + mesh_.chambers[chamber_].name + ")"; }
  bool is_load() const override { return true; }
  void declare_pattern(SparsePattern& pattern) override;
  FormStatus add(const Vector& x, double* value, Vector* gradient, HessianAccumulator* hessian) const override;

  /// Chamber volume at positions x, mm³.
  double volume(const Vector& x) const;
  /// ∂V/∂x (full dof vector).
  Vector volume_gradient(const Vector& x) const;

 private:
  double pressure() const;
  const Mesh& mesh_;
  int chamber_;
  const LoadState& load_;
  std::vector<int> blocks_;
};

}  // namespace softarm::fem

#pragma once
// Self-weight as the potential of a uniform body force:
//     Π_g = −s ∫ ρ g·x dV,   s = LoadState::gravity_scale,
// integrated over the reference configuration (mass is conserved, so ρ dV is
// the same in any configuration: a dead load). Π_g is linear in x, so its
// gradient −s f is the constant vector of consistent nodal forces
// f_a = ∫ ρ N_a g dV and its Hessian is zero.
//
// Units (the project's are mm, N, MPa): ρ in g/cm³ (Material::density_g_cm3)
// is 1e-6·ρ kg/mm³, and kg/mm³ times an acceleration in m/s² is
// kg·m/s² per mm³ = N/mm³, the body force per volume; f is then in N and
// Π_g in N·mm, like the strain energy (MPa·mm³). Hence g is given in m/s²
// (standard gravity 9.80665).
//
// Axisymmetric meshes (dim 2, (r, z)): dV includes 2πR, and only a gravity
// along the axis (x = y = 0) keeps the problem axisymmetric; the z component
// acts on the z dofs. 3D meshes: g acts on (x, y, z).
#include <Eigen/Core>
#include <vector>

#include "fem/forms/form.hpp"
#include "fem/materials/material.hpp"
#include "fem/mesh/mesh.hpp"

namespace softarm::fem {

class GravityForm : public Form {
 public:
  /// `part_materials[i]` is the material of mesh part i (its density is used);
  /// `gravity_m_s2` the acceleration of gravity. Throws std::logic_error for an
  /// axisymmetric mesh with gravity off the axis, a missing material, an
  /// element type without a Gauss rule or an inverted element.
  GravityForm(const Mesh& mesh, const std::vector<Material>& part_materials, const Eigen::Vector3d& gravity_m_s2,
              const LoadState& load);
  std::string name() const override { return "gravity"; }
  bool is_load() const override { return true; }
  void declare_pattern(SparsePattern&) override {}  // zero Hessian: couples nothing
  FormStatus add(const Vector& x, double* value, Vector* gradient, HessianAccumulator* hessian) const override;

  /// Adds the weight of a point mass carried by a face (e.g. a payload at the tip),
  /// spread over its nodes in proportion to ∫ N_a dA (`area_weights`, per node).
  /// 3D meshes only.
  void add_carried_mass(const Eigen::VectorXd& area_weights, double mass_kg);

  /// Consistent nodal forces at gravity_scale = 1, N (dof layout of x).
  const Vector& nodal_forces() const { return forces_; }

 private:
  const LoadState& load_;
  Eigen::Vector3d gravity_m_s2_;
  int dim_;
  Vector forces_;
};

}  // namespace softarm::fem

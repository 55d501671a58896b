#include "fem/forms/gravity_form.hpp"

#include <stdexcept>
#include <string>

#include "fem/elements/reference_quadrature.hpp"

namespace softarm::fem {
namespace {
constexpr double kKgPerMm3PerGcm3 = 1e-6;
}  // namespace

GravityForm::GravityForm(const Mesh& mesh, const std::vector<Material>& part_materials,
                         const Eigen::Vector3d& gravity_m_s2, const LoadState& load)
    : load_(load), gravity_m_s2_(gravity_m_s2), dim_(mesh.dim), forces_(Vector::Zero(mesh.num_nodes() * mesh.dim)) {
  if (part_materials.size() < mesh.part_names.size())
    throw std::logic_error("gravity: a material is missing for a mesh part");
  if (mesh.dim == 2 && (gravity_m_s2.x() != 0.0 || gravity_m_s2.y() != 0.0))
    throw std::logic_error("gravity: an axisymmetric body takes gravity along its axis (z) only");
  if (mesh.dim != 2 && mesh.dim != 3) throw std::logic_error("gravity: mesh dimension must be 2 or 3");
  // f_a = ∫ N_a b dV, b = ρ g the body force per volume (N/mm³) of the element's part.
  std::vector<Eigen::Vector3d> body_force;
  for (const auto& m : part_materials) body_force.push_back(kKgPerMm3PerGcm3 * m.density_g_cm3 * gravity_m_s2);
  try {
    for_each_weighted_node(mesh, [&](int e, int node, double weight) {
      const Eigen::Vector3d& b = body_force[static_cast<std::size_t>(mesh.part[e])];
      if (mesh.dim == 3)
        forces_.segment<3>(3 * node) += weight * b;
      else
        forces_[2 * node + 1] += weight * b.z();  // (r, z): only the axial component
    });
  } catch (const std::logic_error& error) {
    throw std::logic_error(std::string("gravity: ") + error.what());
  }
}

void GravityForm::add_carried_mass(const Eigen::VectorXd& area_weights, double mass_kg) {
  if (dim_ != 3) throw std::logic_error("gravity: a carried mass needs a 3D mesh");
  const double total = area_weights.sum();
  if (!(total > 0) || mass_kg <= 0) return;
  // kg · m/s² = N: the weight m g, shared by the nodes like a uniform traction.
  for (Eigen::Index n = 0; n < area_weights.size(); ++n)
    forces_.segment<3>(3 * n) += mass_kg * gravity_m_s2_ * (area_weights[n] / total);
}

FormStatus GravityForm::add(const Vector& x, double* value, Vector* gradient, HessianAccumulator*) const {
  const double s = load_.gravity_scale;
  if (value) *value -= s * forces_.dot(x);
  if (gradient) *gradient -= s * forces_;
  return FormStatus::fine();
}

}  // namespace softarm::fem

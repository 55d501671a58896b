#include "fem/forms/gravity_form.hpp"

#include <stdexcept>
#include <string>

#include "fem/elements/axisymmetric_quad.hpp"
#include "fem/elements/hexahedron.hpp"

namespace softarm::fem {
namespace {
constexpr double kKgPerMm3PerGcm3 = 1e-6;

// f_a += ∫ N_a b dV over every element, b the body force per volume (N/mm³) of its part,
// with the element family's reference points (found by argument-dependent lookup).
// Returns false, and does nothing, when the mesh's elements are not of type E.
template <class E, template <class> class Point, int Dim>
bool add_nodal_forces(const Mesh& mesh, const std::vector<Eigen::Matrix<double, Dim, 1>>& part_force, Vector& f) {
  if (mesh.dim != Dim || mesh.nodes_per_element != E::kNodes) return false;
  std::array<Point<E>, E::kGaussPoints> points;
  for (int e = 0; e < mesh.num_elements(); ++e) {
    const int* nodes = mesh.element(e);
    Eigen::Matrix<double, E::kNodes, Dim> X;
    for (int a = 0; a < E::kNodes; ++a) X.row(a) = mesh.X.row(nodes[a]);
    if (!reference_points<E>(X, points))
      throw std::logic_error("gravity: mesh element " + std::to_string(e) + " is inverted or degenerate");
    const auto& b = part_force[static_cast<std::size_t>(mesh.part[e])];
    for (const auto& p : points)
      for (int a = 0; a < E::kNodes; ++a) f.segment<Dim>(Dim * nodes[a]) += p.N[a] * p.dV * b;
  }
  return true;
}
}  // namespace

GravityForm::GravityForm(const Mesh& mesh, const std::vector<Material>& part_materials,
                         const Eigen::Vector3d& gravity_m_s2, const LoadState& load)
    : load_(load), forces_(Vector::Zero(mesh.num_nodes() * mesh.dim)) {
  if (part_materials.size() < mesh.part_names.size())
    throw std::logic_error("gravity: a material is missing for a mesh part");
  if (mesh.dim == 2 && (gravity_m_s2.x() != 0.0 || gravity_m_s2.y() != 0.0))
    throw std::logic_error("gravity: an axisymmetric body takes gravity along its axis (z) only");
  std::vector<Eigen::Vector2d> axial;  // (r, z) components for axisymmetric meshes
  std::vector<Eigen::Vector3d> full;
  for (const auto& m : part_materials) {
    full.push_back(kKgPerMm3PerGcm3 * m.density_g_cm3 * gravity_m_s2);
    axial.emplace_back(0.0, full.back().z());
  }
  const bool known = add_nodal_forces<axisym::Quad4, axisym::ReferencePoint, 2>(mesh, axial, forces_) ||
                     add_nodal_forces<axisym::Quad9, axisym::ReferencePoint, 2>(mesh, axial, forces_) ||
                     add_nodal_forces<hex::Hex8, hex::ReferencePoint, 3>(mesh, full, forces_) ||
                     add_nodal_forces<hex::Hex27, hex::ReferencePoint, 3>(mesh, full, forces_);
  if (!known)
    throw std::logic_error("gravity: unsupported element with " + std::to_string(mesh.nodes_per_element) +
                           " nodes in dimension " + std::to_string(mesh.dim));
}

FormStatus GravityForm::add(const Vector& x, double* value, Vector* gradient, HessianAccumulator*) const {
  const double s = load_.gravity_scale;
  if (value) *value -= s * forces_.dot(x);
  if (gradient) *gradient -= s * forces_;
  return FormStatus::fine();
}

}  // namespace softarm::fem

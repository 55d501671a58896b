#pragma once
// One loop over the Gauss points of a mesh's reference configuration, for
// every element family (axisymmetric Quad4/Quad9, Hex8/Hex20/Hex27): the body-force
// and volume integrals (gravity, mass, part volumes) are written once against
// it instead of once per element type.
#include <stdexcept>
#include <string>

#include "fem/elements/axisymmetric_quad.hpp"
#include "fem/elements/hexahedron.hpp"
#include "fem/mesh/mesh.hpp"

namespace softarm::fem {
namespace detail {
template <class E, template <class> class Point, int Dim, class Visit>
bool visit_reference_points(const Mesh& mesh, Visit& visit) {
  if (mesh.dim != Dim || mesh.nodes_per_element != E::kNodes) return false;
  std::array<Point<E>, E::kGaussPoints> points;
  for (int e = 0; e < mesh.num_elements(); ++e) {
    const int* nodes = mesh.element(e);
    Eigen::Matrix<double, E::kNodes, Dim> X;
    for (int a = 0; a < E::kNodes; ++a) X.row(a) = mesh.X.row(nodes[a]);
    if (!reference_points<E>(X, points))
      throw std::logic_error("mesh element " + std::to_string(e) + " is inverted or degenerate");
    for (const auto& p : points)
      for (int a = 0; a < E::kNodes; ++a) visit(e, nodes[a], p.N[a] * p.dV);
  }
  return true;
}
}  // namespace detail

/// Calls visit(element, node, N_a dV) for every node a of every element at every
/// Gauss point, dV the reference volume weight (2πR included for axisymmetric
/// meshes), so Σ over the calls of an element is its volume. Throws
/// std::logic_error for an inverted element or an unknown element type.
template <class Visit>
void for_each_weighted_node(const Mesh& mesh, Visit&& visit) {
  const bool known = detail::visit_reference_points<axisym::Quad4, axisym::ReferencePoint, 2>(mesh, visit) ||
                     detail::visit_reference_points<axisym::Quad9, axisym::ReferencePoint, 2>(mesh, visit) ||
                     detail::visit_reference_points<hex::Hex8, hex::ReferencePoint, 3>(mesh, visit) ||
                     detail::visit_reference_points<hex::Hex20, hex::ReferencePoint, 3>(mesh, visit) ||
                     detail::visit_reference_points<hex::Hex27, hex::ReferencePoint, 3>(mesh, visit);
  if (!known)
    throw std::logic_error("unsupported element with " + std::to_string(mesh.nodes_per_element) +
                           " nodes in dimension " + std::to_string(mesh.dim));
}

/// Volume of each mesh part (indexed like part_names), mm³.
inline std::vector<double> part_volumes_mm3(const Mesh& mesh) {
  std::vector<double> volume(mesh.part_names.size(), 0.0);
  for_each_weighted_node(mesh, [&](int e, int, double w) { volume[static_cast<std::size_t>(mesh.part[e])] += w; });
  return volume;
}

}  // namespace softarm::fem

#include "fem/forms/make_elastic_form.hpp"

#include <stdexcept>

#include "fem/elements/axisymmetric_quad.hpp"
#include "fem/elements/hexahedron.hpp"
#include "fem/forms/projected_dilatation_form.hpp"

namespace softarm::fem {
namespace {
// Axisymmetric quadrilaterals: (r, z) per node, the five components of F that vary in axisymmetry.
template <class E>
using AxisymmetricForm = ProjectedDilatationForm<E, axisym::ReferencePoint, 2, axisym::kActive, axisym::kActiveComponents>;
// Hexahedra: (x, y, z) per node, all nine components of F.
template <class E>
using SolidForm = ProjectedDilatationForm<E, hex::ReferencePoint, 3, hex::kActive, hex::kActiveComponents>;
}  // namespace

std::shared_ptr<ElasticForm> make_elastic_form(const Mesh& mesh, std::vector<Material> part_materials,
                                               VolumetricTreatment treatment, ElementIntegration integration) {
  const int n = mesh.nodes_per_element;
  if (integration == ElementIntegration::reduced) {
    if (mesh.dim == 3 && n == hex::Hex20::kNodes)
      return std::make_shared<SolidForm<hex::Hex20Reduced>>(mesh, std::move(part_materials), treatment);
    throw std::logic_error("elastic form: reduced integration exists only for the 20-node hexahedron");
  }
  if (mesh.dim == 2 && n == axisym::Quad4::kNodes)
    return std::make_shared<AxisymmetricForm<axisym::Quad4>>(mesh, std::move(part_materials), treatment);
  if (mesh.dim == 2 && n == axisym::Quad9::kNodes)
    return std::make_shared<AxisymmetricForm<axisym::Quad9>>(mesh, std::move(part_materials), treatment);
  if (mesh.dim == 3 && n == hex::Hex8::kNodes)
    return std::make_shared<SolidForm<hex::Hex8>>(mesh, std::move(part_materials), treatment);
  if (mesh.dim == 3 && n == hex::Hex20::kNodes)
    return std::make_shared<SolidForm<hex::Hex20>>(mesh, std::move(part_materials), treatment);
  if (mesh.dim == 3 && n == hex::Hex27::kNodes)
    return std::make_shared<SolidForm<hex::Hex27>>(mesh, std::move(part_materials), treatment);
  throw std::logic_error("elastic form: no element for a " + std::to_string(mesh.dim) + "D mesh with " +
                         std::to_string(n) + " nodes per element");
}

}  // namespace softarm::fem

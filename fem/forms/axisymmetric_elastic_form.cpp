#include "fem/forms/axisymmetric_elastic_form.hpp"

#include "fem/elements/axisymmetric_quad.hpp"
#include "fem/forms/projected_dilatation_form.hpp"

namespace softarm::fem {
namespace {
// The shared projected-dilatation form on axisymmetric quadrilaterals: (r, z) per
// node, the five components of F that vary in axisymmetry.
template <class E>
using AxisymmetricElasticForm =
    ProjectedDilatationForm<E, axisym::ReferencePoint, 2, axisym::kActive, axisym::kActiveComponents>;
}  // namespace

std::shared_ptr<ElasticForm> make_axisymmetric_elastic_form(const Mesh& mesh, std::vector<Material> part_materials,
                                                            VolumetricTreatment treatment) {
  if (mesh.dim != 2) throw std::logic_error("axisymmetric elastic form needs a 2D (r, z) mesh");
  if (mesh.nodes_per_element == axisym::Quad4::kNodes)
    return std::make_shared<AxisymmetricElasticForm<axisym::Quad4>>(mesh, std::move(part_materials), treatment);
  if (mesh.nodes_per_element == axisym::Quad9::kNodes)
    return std::make_shared<AxisymmetricElasticForm<axisym::Quad9>>(mesh, std::move(part_materials), treatment);
  throw std::logic_error("axisymmetric elastic form: unsupported element with " +
                         std::to_string(mesh.nodes_per_element) + " nodes");
}

}  // namespace softarm::fem

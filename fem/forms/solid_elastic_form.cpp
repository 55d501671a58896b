#include "fem/forms/solid_elastic_form.hpp"

#include "fem/elements/hexahedron.hpp"
#include "fem/forms/projected_dilatation_form.hpp"

namespace softarm::fem {
namespace {
// The shared projected-dilatation form on hexahedra: (x, y, z) per node, all nine components of F.
template <class E>
using SolidElasticForm = ProjectedDilatationForm<E, hex::ReferencePoint, 3, hex::kActive, hex::kActiveComponents>;
}  // namespace

std::shared_ptr<ElasticForm> make_solid_elastic_form(const Mesh& mesh, std::vector<Material> part_materials,
                                                     VolumetricTreatment treatment) {
  if (mesh.dim != 3) throw std::logic_error("solid elastic form needs a 3D mesh");
  if (mesh.nodes_per_element == hex::Hex8::kNodes)
    return std::make_shared<SolidElasticForm<hex::Hex8>>(mesh, std::move(part_materials), treatment);
  if (mesh.nodes_per_element == hex::Hex27::kNodes)
    return std::make_shared<SolidElasticForm<hex::Hex27>>(mesh, std::move(part_materials), treatment);
  throw std::logic_error("solid elastic form: unsupported element with " + std::to_string(mesh.nodes_per_element) +
                         " nodes");
}

}  // namespace softarm::fem

#pragma once
// The elastic form of a mesh (elastic_form.hpp), its element family chosen from the mesh: the one
// place that instantiates projected_dilatation_form.hpp for every element.
#include <memory>
#include <vector>

#include "fem/forms/elastic_form.hpp"

namespace softarm::fem {

/// The elastic form of a mesh, its element chosen by dimension and nodes per element:
/// axisymmetric Q1/P0 (2D, 4 nodes) or Q2/P1 (2D, 9), Hex8/P0 (3D, 8), Hex20/P1 (3D, 20) or Hex27/P1 (3D, 27).
/// `part_materials[i]` is the material of mesh part i. Throws std::logic_error for other
/// meshes, for meshes with inverted elements and for `reduced` integration of anything but Hex20.
std::shared_ptr<ElasticForm> make_elastic_form(
    const Mesh& mesh, std::vector<Material> part_materials,
    VolumetricTreatment treatment = VolumetricTreatment::projected_dilatation,
    ElementIntegration integration = ElementIntegration::full);

}  // namespace softarm::fem

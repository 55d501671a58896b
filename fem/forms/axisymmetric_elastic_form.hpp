#pragma once
// Strain energy of an axisymmetric body of quadrilaterals (Q1 or Q2, chosen
// by the mesh's nodes per element); the formulation is described in
// elastic_form.hpp.
#include <memory>
#include <vector>

#include "fem/forms/elastic_form.hpp"
#include "fem/materials/material.hpp"
#include "fem/mesh/mesh.hpp"

namespace softarm::fem {

/// `part_materials[i]` is the material of mesh part i. Throws std::logic_error for
/// meshes that are not axisymmetric quadrilaterals or have inverted elements.
std::shared_ptr<ElasticForm> make_axisymmetric_elastic_form(
    const Mesh& mesh, std::vector<Material> part_materials,
    VolumetricTreatment treatment = VolumetricTreatment::projected_dilatation);

}  // namespace softarm::fem

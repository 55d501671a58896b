#pragma once
// Strain energy of a three-dimensional body of hexahedra (Hex8 or Hex27, chosen
// by the mesh's nodes per element), with exactly the projected-dilatation energy
// of the axisymmetric form (axisymmetric_elastic_form.hpp; both are instances of
// projected_dilatation_form.hpp): Hex8 with a constant dilatation (H1/P0, mean
// dilatation), Hex27 with discontinuous linears (H2/P1).
#include <memory>
#include <vector>

#include "fem/forms/elastic_form.hpp"
#include "fem/materials/material.hpp"
#include "fem/mesh/mesh.hpp"

namespace softarm::fem {

/// `part_materials[i]` is the material of mesh part i. Throws std::logic_error for
/// meshes that are not 3D hexahedra (8 or 27 nodes) or have inverted elements.
std::shared_ptr<ElasticForm> make_solid_elastic_form(
    const Mesh& mesh, std::vector<Material> part_materials,
    VolumetricTreatment treatment = VolumetricTreatment::projected_dilatation);

}  // namespace softarm::fem

#pragma once
// Strain energy of an axisymmetric body of quadrilaterals (Q1 or Q2, chosen
// by the mesh's nodes per element).
//
// Near-incompressible laws (those with the isochoric/volumetric split) use a
// projected-dilatation (three-field, Hu–Washizu) formulation with the
// pressure and dilatation condensed per element: the isochoric energy is
// integrated at the Gauss points, the volumetric energy with θ, the L²
// projection of J onto the element's dilatation space,
//     Π_e = ∫ W̄(C) dV + ∫ U(θ) dV,   θ = Π_h J,
// constants for Q1 (the mean-dilatation / F-bar method of Nagtegaal et al.
// 1974 and Simo, Taylor & Pister 1985: Q1/P0) and discontinuous linears for
// Q2 (Q2/P1, inf-sup stable). Because it is the exact derivative of a single
// energy the tangent is symmetric. Laws without the split (the ABS rings,
// compressible) use the plain displacement formulation.
//
// Why Q2/P1 by default: Q1/P0 still locks where near-incompressible silicone
// is bonded to a rigid ring (the extension of the thesis RRA keeps growing by
// ~0.5 % per uniform refinement instead of converging; see the benchmark),
// whereas Q2/P1 converges.
//
// The "pointwise" treatment integrates U(J) at every Gauss point; it locks
// and exists only so the benchmark can show by how much.
#include <memory>
#include <vector>

#include "fem/forms/form.hpp"
#include "fem/materials/material.hpp"
#include "fem/mesh/mesh.hpp"

namespace softarm::fem {

enum class VolumetricTreatment { projected_dilatation, pointwise };

/// Per-element results for reports and VTU output.
struct ElementResult {
  double max_principal_stretch = 1.0;
  double min_principal_stretch = 1.0;
  double max_principal_cauchy_MPa = 0.0;   // largest principal Cauchy stress over the Gauss points
  double max_principal_log_strain = 0.0;
  double dilatation = 1.0;                 // mean of the projected J over the element
};

/// The strain-energy form of a solid body, with its post-processing.
class ElasticForm : public Form {
 public:
  std::string name() const override { return "elastic"; }
  virtual std::vector<ElementResult> element_results(const Vector& x) const = 0;
  /// Name of the element formulation in use (for reports).
  virtual std::string element_name() const = 0;
};

/// `part_materials[i]` is the material of mesh part i. Throws std::logic_error for
/// meshes that are not axisymmetric quadrilaterals or have inverted elements.
std::shared_ptr<ElasticForm> make_axisymmetric_elastic_form(
    const Mesh& mesh, std::vector<Material> part_materials,
    VolumetricTreatment treatment = VolumetricTreatment::projected_dilatation);

}  // namespace softarm::fem

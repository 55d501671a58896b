#pragma once
// Strain energy of an axisymmetric body of bilinear quadrilaterals.
//
// Near-incompressible laws (those with the isochoric/volumetric split) use the
// mean-dilatation formulation: the isochoric energy is integrated at the Gauss
// points, the volumetric energy with one dilatation per element,
//     Π_e = ∫ W̄(C) dV + V_e U(J̄),   J̄ = v_e / V_e,   v_e = ∫ J dV,
// which is the F-bar method with F̄ = (J̄/J)^(1/3) F (de Souza Neto et al.
// 1996; Simo, Taylor & Pister 1985 for Q1/P0 with the pressure condensed per
// element). It removes volumetric locking of Q1, and because it is the exact
// derivative of a single energy the tangent stays symmetric. Laws without the
// split (the ABS rings, compressible) use the plain displacement formulation.
//
// The "pointwise" treatment integrates U(J) at every Gauss point; it locks
// and exists only so the benchmark can show by how much.
#include <array>
#include <memory>
#include <vector>

#include "fem/elements/axisymmetric_quad.hpp"
#include "fem/forms/form.hpp"
#include "fem/materials/material.hpp"
#include "fem/mesh/mesh.hpp"

namespace softarm::fem {

enum class VolumetricTreatment { mean_dilatation, pointwise };

/// Per-element results for reports and VTU output.
struct ElementResult {
  double max_principal_stretch = 1.0;
  double min_principal_stretch = 1.0;
  double max_principal_cauchy_MPa = 0.0;   // largest principal Cauchy stress over the Gauss points
  double max_principal_log_strain = 0.0;
  double dilatation = 1.0;                 // J̄
};

class AxisymmetricElasticForm : public Form {
 public:
  /// `part_materials[i]` is the material of mesh part i.
  AxisymmetricElasticForm(const Mesh& mesh, std::vector<Material> part_materials,
                          VolumetricTreatment treatment = VolumetricTreatment::mean_dilatation);
  std::string name() const override { return "elastic"; }
  void declare_pattern(SparsePattern& pattern) override;
  FormStatus add(const Vector& x, double* value, Vector* gradient, HessianAccumulator* hessian) const override;

  std::vector<ElementResult> element_results(const Vector& x) const;
  const std::vector<Material>& materials() const { return materials_; }

 private:
  struct ElementEnergy;
  FormStatus element(int e, const Vector& x, bool want_gradient, bool want_hessian, ElementEnergy& out) const;

  const Mesh& mesh_;
  std::vector<Material> materials_;
  VolumetricTreatment treatment_;
  std::vector<std::array<axisym::ReferencePoint, axisym::kGaussPoints>> reference_;
  std::vector<double> reference_volume_;
  std::vector<int> blocks_;
};

}  // namespace softarm::fem

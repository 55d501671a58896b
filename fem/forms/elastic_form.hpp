#pragma once
// The strain-energy form of a solid body, axisymmetric or 3D: every element
// family is an instance of projected_dilatation_form.hpp, made by make_elastic_form.hpp.
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
// is bonded to a rigid ring: at 50 kPa the thesis RRA's extension moves by
// −0.001, +0.036, +0.046 mm over refinements 1→4, growing instead of
// shrinking, whereas Q2/P1 moves by −0.095 then +0.014 mm (bench_rra_levels).
//
// The "pointwise" treatment integrates U(J) at every Gauss point; it locks
// and exists only so the benchmark can show by how much.
#include <memory>
#include <string>
#include <vector>

#include "fem/forms/form.hpp"
#include "fem/materials/material.hpp"
#include "fem/mesh/mesh.hpp"

namespace softarm::fem {

enum class VolumetricTreatment { projected_dilatation, pointwise };

/// Gauss rule of the element: `full` (2×2×2 for linear, 3×3×3 for quadratic
/// hexahedra) or `reduced` (2×2×2 for the 20-node serendipity hexahedron, as
/// C3D20R; no other element has a reduced rule here).
enum class ElementIntegration { full, reduced };

/// Per-element results for reports and VTU output.
struct ElementResult {
  double max_principal_stretch = 1.0;
  double min_principal_stretch = 1.0;
  double max_principal_cauchy_MPa = 0.0;   // largest principal Cauchy stress over the Gauss points
  double max_principal_log_strain = 0.0;
  double dilatation = 1.0;                 // mean of the projected J over the element
  // Volume means over the Gauss points (each weighted by its reference dV): the integrand of a
  // region average (fem/post/region_average.hpp), which converges where a point value does not.
  double mean_principal_stretch = 1.0, mean_principal_cauchy_MPa = 0.0, mean_principal_log_strain = 0.0;
};

/// Where a state asks more of a law than it can give: the Gauss points at which the law is not
/// Drucker stable (dτ:dε ≤ 0 for some isochoric strain increment, fem/materials/drucker_stability.hpp)
/// at the isochoric principal stretches λ̂_a = λ_a J^(-1/3) the point sees. Only the laws with the
/// isochoric/volumetric split (the silicones) are checked: the stiff rings stay near rest.
struct MaterialInstability {
  int unstable_points = 0;  // 0: every point is stable
  int checked_points = 0;   // the Gauss points of the split laws' parts
  int element = -1;         // of the unstable point with the largest stretch (element_corner_node: where)
  double max_stretch = 1.0, min_stretch = 1.0;  // λ̂ there, largest and smallest
  bool found() const { return unstable_points > 0; }
};

/// The strain-energy form of a solid body, with its post-processing.
class ElasticForm : public Form {
 public:
  std::string name() const override { return "elastic"; }
  virtual std::vector<ElementResult> element_results(const Vector& x) const = 0;
  virtual MaterialInstability material_instability(const Vector& x) const = 0;
  /// A corner node of element e, to say where it is.
  virtual int element_corner_node(int e) const = 0;
  /// Name of the element formulation in use (for reports).
  virtual std::string element_name() const = 0;
};

}  // namespace softarm::fem

#pragma once
// Equilibrium of one cell section (cell_section.hpp) of the spatial rod, the
// biaxial counterpart of section_equilibrium.hpp. Unknowns: the reference
// stretch λ0 and the stretch gradient g ∈ R² across the section, so that the
// fibre at ξ has stretch λ = λ0 + g·ξ. With the director-frame curvature
// (κ1, κ2) of a Kirchhoff rod, g = (−κ2, κ1) (spatial_rod.hpp). With P(λ) the
// fibre law of each material, f_k the chambers' axial forces at ξ_k, N the
// external axial force (tension > 0) and μ the first moment the fibres must
// carry (μ = (−m2, m1) for the external moment m = (m1, m2) in the directors):
//     R0 = ∫ P dA − Σ f_k − N = 0
//     R  = ∫ ξ P dA − Σ f_k ξ_k − μ = 0
// Newton with the exact symmetric tangent [[∫P', ∫ξᵀP'], [∫ξP', ∫ξξᵀP']]; one
// that is not positive definite (a fibre law past its uniaxial Drucker limit)
// is a limit point of the section and is reported, not stepped over.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "fem/reduced/cell_section.hpp"
#include "fem/reduced/section_equilibrium.hpp"

namespace softarm::fem {

struct BiaxialSectionState {
  double stretch = 1;                                   // λ0 at the section's reference point
  Eigen::Vector2d gradient = Eigen::Vector2d::Zero();  // g, 1/mm
  bool ok = true;
  std::string failure;  // why not ok
};

/// Solves R = 0 from `guess`; forces in N, first moments in N·mm.
BiaxialSectionState solve_biaxial_section(const CellSection& section, const SectionLaws& laws,
                                          const std::vector<double>& chamber_force_N, double axial_force_N,
                                          const Eigen::Vector2d& fibre_moment_Nmm, BiaxialSectionState guess);

/// Largest and smallest fibre stretch of each material over the section at a state.
FibreExtremes fibre_extremes(const CellSection& section, const BiaxialSectionState& state);

}  // namespace softarm::fem

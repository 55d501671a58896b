#pragma once
// Equilibrium of one rod section (rod_section.hpp) under its chamber forces and
// the external loads of the part beyond it. Unknowns: the axis stretch λ0 and
// the curvature κ (per reference length); fibre stretch λ(y) = λ0 − κ·y.
// With P(λ) the fibre law of each material (fibre_law.hpp), f_k = c·p_k·A_k the
// chambers' axial forces at y_k, N the external force along the tangent
// (tension > 0) and M the external moment about the section's reference point
// (counter-clockwise > 0, the sense in which κ > 0 turns the axis):
//     R1 = ∫ P dA − Σ f_k − N = 0          (axial force)
//     R2 = ∫ y P dA − Σ f_k y_k + M = 0     (moment; a fibre at +y lies on the inside of a κ > 0 bend)
// (with ring confinement, rod_section.hpp, the held wall's P is its confined
// law's and f_k acts on the rings' inner area: R is then the gradient of the
// section's energy minus the pressure's work p·V, confined_wall.hpp)
// solved by Newton with the exact 2×2 tangent. A tangent that is not positive
// definite (a fibre law past its uniaxial Drucker limit) is a limit point of
// the section and is reported, not stepped over.
#include <string>
#include <vector>

#include "fem/reduced/fibre_law.hpp"
#include "fem/reduced/rod_section.hpp"

namespace softarm::fem {

struct SectionLaws {
  const FibreLaw* tube = nullptr;
  const FibreLaw* sheath = nullptr;  // may be null for a lone RRA
};

struct SectionState {
  double stretch = 1;     // λ0 on the reference point
  double curvature = 0;   // κ, 1/mm
  bool ok = true;
  std::string failure;    // why not ok
};

/// Why fibre stretches in [lo, hi] leave the tube law's table (empty if they do not).
std::string fibre_range_failure(const SectionLaws& laws, double lo, double hi);

/// Solves R = 0 from `guess`; forces in N, moment in N·mm.
SectionState solve_section(const RodSection& section, const SectionLaws& laws, const std::vector<double>& chamber_force_N,
                           double axial_force_N, double moment_Nmm, SectionState guess);

/// Largest and smallest fibre stretch of a material over the section at a state.
struct FibreExtremes {
  double tube_max = 1, tube_min = 1, sheath_max = 1, sheath_min = 1;
  /// Widens the extremes by a fibre of stretch λ holding tube and/or sheath material.
  void include(double stretch, bool tube, bool sheath);

 private:
  bool have_tube_ = false, have_sheath_ = false;
};
FibreExtremes fibre_extremes(const RodSection& section, const SectionState& state);

}  // namespace softarm::fem

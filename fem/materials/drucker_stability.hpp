#pragma once
// Drucker stability of a hyperelastic law as Abaqus checks it for an
// incompressible fit, and the nominal stress along the standard test paths.
//
// Under incompressibility the state is fixed by two log strains ε1, ε2
// (ε3 = −ε1 − ε2). With
//   w(ε1, ε2) = W̄(e^{2ε1}, e^{2ε2}, e^{−2ε1−2ε2})      (isochoric energy at J = 1)
// the Kirchhoff stress differences are ∂w/∂ε1 = τ1 − τ3, ∂w/∂ε2 = τ2 − τ3, so
// dτ:dε = dεᵀ H dε with H the 2×2 Hessian of w: the law is Drucker stable at a
// state iff H is positive definite. H comes from Jet<3> (exact, no finite
// differences). Stability depends only on the set of principal stretches, so
// e.g. uniaxial compression at λ is equibiaxial tension at λ^(-1/2).
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "fem/materials/hyperelastic_law.hpp"

namespace softarm::fem {

/// The homogeneous test paths (λ > 1 tension, λ < 1 compression).
enum class LoadingMode {
  uniaxial,     // (λ, λ^-1/2, λ^-1/2)
  equibiaxial,  // (λ, λ, λ^-2)
  planar,       // (λ, 1, 1/λ)  (pure shear)
};
inline constexpr std::array<LoadingMode, 3> all_loading_modes{LoadingMode::uniaxial, LoadingMode::equibiaxial,
                                                             LoadingMode::planar};
std::string mode_name(LoadingMode mode);

/// (ε1, ε2) = (ln λ1, ln λ2) of the path at stretch λ.
Eigen::Vector2d path_log_strains(LoadingMode mode, double lambda);

/// w(ε1, ε2) as a Jet in (ε1, ε2, unused): g = (τ1 − τ3, τ2 − τ3, 0), h = dτ/dε.
Jet3 incompressible_energy(const HyperelasticLaw& law, double eps1, double eps2);

/// 2×2 Drucker matrix H = ∂²w/∂ε∂ε at (ε1, ε2).
Eigen::Matrix2d drucker_matrix(const HyperelasticLaw& law, double eps1, double eps2);

/// H positive definite at (ε1, ε2) (false also when H is not finite): the law is Drucker stable at
/// the isochoric principal stretches (e^ε1, e^ε2, e^(−ε1−ε2)), whichever state they come from.
bool drucker_stable_at(const HyperelasticLaw& law, double eps1, double eps2);

/// H positive definite on the path at λ (false also when H is not finite).
bool drucker_stable(const HyperelasticLaw& law, LoadingMode mode, double lambda);

/// Nominal (1st Piola-Kirchhoff, force per reference area) stress along the
/// loading direction under incompressibility, MPa. For all three paths the
/// face normal to direction 3 is traction free (τ3 = 0 fixes the pressure), so
/// P1 = σ1/λ = (τ1 − τ3)/λ = (1/λ) ∂w/∂ε1 (J = 1). Uniaxial Ogden:
/// P = Σ (2μ_i/α_i)(λ^(α_i−1) − λ^(−α_i/2−1)).
double nominal_stress(const HyperelasticLaw& law, LoadingMode mode, double lambda);

/// Contiguous Drucker-stable stretch interval of one path that contains λ = 1.
struct ModeStability {
  std::string mode;
  bool stable_at_rest = false;  // false: unstable at λ = 1, the interval is empty (NaN bounds)
  double lambda_min = 0, lambda_max = 0;
  bool bounded_below = false;  // true: λ_min is a stability boundary, not the end of the scan
  bool bounded_above = false;
};

/// Scans λ on a log grid over [lambda_lo, lambda_hi] (0 < lo < 1 < hi) outward
/// from λ = 1, step ≈ 1e-3 in ln λ, and refines each boundary by bisection to
/// a relative 1e-7 in λ. An unstable window narrower than the grid step could
/// be stepped over; the real fits have smooth, wide boundaries.
std::vector<ModeStability> drucker_stability(const HyperelasticLaw& law, double lambda_lo = 0.1,
                                             double lambda_hi = 10.0);

}  // namespace softarm::fem

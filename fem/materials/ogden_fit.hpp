#pragma once
// Least-squares fit of an N-term Ogden law (N = 1..3) to uniaxial nominal
// stress by variable projection (Golub & Pereyra 1973): for exponents α the
// moduli μ(α) = argmin ||B(α)μ − P|| are a linear least-squares problem
// (B_ri = φ(λ_r; α_i), uniaxial_closed_form.hpp), so only the N exponents are
// searched, minimising the projected residual r(α) = P − B(α)μ(α) by
// Levenberg–Marquardt with Kaufman's (1975) Jacobian
//   ∂r/∂α_i ≈ −(I − B B⁺) (∂φ_i/∂α_i) μ_i,
// from every N-subset of an exponent grid (the SSE has many local minima).
#include <Eigen/Core>

namespace softarm::fem {

struct OgdenFit {
  Eigen::VectorXd mu;     // MPa, Abaqus convention, ordered by increasing alpha
  Eigen::VectorXd alpha;
  double sse = 0;         // Σ (P_fit − P)², MPa²
  int starts = 0;         // LM runs made
};

/// Exponents are kept within 1e-3 ≤ |α| ≤ max_abs_alpha (≥ 1). The bound is
/// needed: on uniaxial data the SSE can keep falling as one |α| grows with its
/// μ → 0 (a term ~λ^(|α|−1) that only bends the last points), so without it the
/// "optimum" runs off to infinity. Among the runs' end points the lowest SSE
/// with Σμ > 0 (a valid law) wins, else the lowest SSE.
OgdenFit fit_ogden(const Eigen::VectorXd& stretch, const Eigen::VectorXd& stress, int terms, double max_abs_alpha);

}  // namespace softarm::fem

#pragma once
// Nominal stress of incompressible uniaxial tension, λ1 = λ, λ2 = λ3 = λ^(-1/2),
// for the law families that material fitting uses. Every law here is linear
// in its moduli, so the stress is P(λ) = Σ_k c_k φ_k(λ) with basis functions φ_k:
//
//   Ī1-based laws (Neo-Hookean eq 4, Yeoh eq 2, W̄ = Σ C_i0 (Ī1 − 3)^i):
//     P = 2(λ − λ^-2) ∂W̄/∂Ī1,  Ī1 − 3 = λ² + 2/λ − 3,
//     φ_i = 2(λ − λ^-2) · i (Ī1 − 3)^(i−1)                    (coefficient C_i0)
//   Ogden (eq 3, Abaqus μ convention W̄ = Σ 2μ_i/α_i² (Σ_a λ̄_a^α_i − 3)):
//     φ(λ; α) = (2/α)(λ^(α−1) − λ^(−α/2−1))                    (coefficient μ_i)
//
// fem::nominal_stress() gives the same stresses from the laws themselves
// (test_material_fit checks that they agree).
#include <Eigen/Core>

namespace softarm::fem {

/// Columns φ_1..φ_terms of the Ī1 polynomial (1 term: Neo-Hookean C10; 3: Yeoh C10, C20, C30).
Eigen::MatrixXd invariant_polynomial_basis(const Eigen::VectorXd& stretch, int terms);

/// Ogden basis φ(λ; α) and its derivative ∂φ/∂α (α ≠ 0).
double ogden_basis(double stretch, double alpha);
double ogden_basis_dalpha(double stretch, double alpha);

/// Columns φ(λ; α_i), one per exponent.
Eigen::MatrixXd ogden_basis(const Eigen::VectorXd& stretch, const Eigen::VectorXd& alpha);

}  // namespace softarm::fem

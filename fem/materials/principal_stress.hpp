#pragma once
// Stress and consistent tangent of a law written in the eigenvalues of C.
//
// The law gives W(c1, c2, c3) as a Jet, i.e. f_a = ∂W/∂c_a and f_ab = ∂²W/∂c_a∂c_b.
// In the principal frame of C (c_a, N_a = n_a ⊗ n_a):
//   S = 2 Σ f_a N_a,                                     (2nd Piola-Kirchhoff)
//   ℂ = 2 ∂S/∂C:  ℂ_aabb = 4 f_ab,
//                 ℂ_abab = ℂ_abba = γ_ab = 2 (f_a − f_b)/(c_a − c_b)   (a ≠ b),
// and γ_ab → 2 (f_aa − f_ab) as c_b → c_a (exact limit, see the .cpp for when it is used).
// Then P = F S and A_iJkL = ∂P_iJ/∂F_kL = δ_ik S_JL + F_iI ℂ_IJKL F_kK.
// A law that is Hooke's law in the Green-Lagrange strain (HyperelasticLaw::green_strain_hooke,
// Saint Venant-Kirchhoff) has S and ℂ in tensor form: its points skip the eigenvalues of C.
#include <Eigen/Core>
#include <array>
#include <optional>

#include "fem/materials/hyperelastic_law.hpp"

namespace softarm::fem {

using Mat3 = Eigen::Matrix3d;
using Tangent9 = Eigen::Matrix<double, 9, 9>;  // A(3*i+J, 3*k+L) = ∂P_iJ/∂F_kL

/// W, P and the tangent on N of F's components (row 3i+J of the row-major 9-vector of F): A's row
/// and column r belong to component active[r].
template <int N>
struct PrincipalStressOn {
  double W = 0;
  Mat3 P = Mat3::Zero();
  Eigen::Matrix<double, N, N> A = Eigen::Matrix<double, N, N>::Zero();
};
using PrincipalStress = PrincipalStressOn<9>;  // every component: A(3i+J, 3k+L) = ∂P_iJ/∂F_kL
inline constexpr std::array<int, 9> kAllComponents{0, 1, 2, 3, 4, 5, 6, 7, 8};

/// Energy, first Piola-Kirchhoff stress P = ∂W/∂F and tangent A = ∂P/∂F of law.principal_energy at F.
/// Returns std::nullopt when det F <= 0 or any eigenvalue of C is not positive (inverted material),
/// and when the energy or its derivatives are not finite there (e.g. overflow at absurd stretch),
/// so that the caller can cut the load step back. No heap allocation.
std::optional<PrincipalStress> evaluate_principal(const HyperelasticLaw& law, const Mat3& F, bool with_tangent);

/// The same with A only on the components `active` of F, each entry by the full tangent's formula
/// (equal to it within a rounding; for all nine, in order, the same code): an axisymmetric element's
/// F varies in five (F_rr, F_rz, F_zr, F_zz, F_θθ), and the other 56 of the 81 entries are work it
/// would throw away. Instantiated for N = 5 and 9.
template <int N>
std::optional<PrincipalStressOn<N>> evaluate_principal(const HyperelasticLaw& law, const Mat3& F, bool with_tangent,
                                                       const std::array<int, N>& active);

/// Cauchy stress of the principal part: σ = P Fᵀ / det F (helper for post-processing).
Mat3 cauchy_stress(const Mat3& P, const Mat3& F);

/// Relative eigenvalue gap |c_a − c_b| / max(c_a, c_b) below which the shear
/// tangent uses the exact equal-eigenvalue limit (justified in the .cpp).
inline constexpr double equal_eigenvalue_tolerance = 1e-5;

}  // namespace softarm::fem

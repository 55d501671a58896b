#include "fem/materials/principal_stress.hpp"

#include <Eigen/LU>  // determinant
#include <algorithm>
#include <cmath>

#include "fem/materials/symmetric_eigen3.hpp"

namespace softarm::fem {
namespace {

using Vec3 = Eigen::Vector3d;

/// Shear modulus of the principal-frame tangent, γ_ab = ℂ_abab = ℂ_abba (a ≠ b).
///
/// For distinct eigenvalues it is the divided difference 2 (f_a − f_b)/(c_a − c_b).
/// As c_b → c_a it tends to 2 (f_aa − f_ab) (W is symmetric, so f_b(c_a, c_b) =
/// f_a(c_b, c_a)); we use the symmetrised form f_aa + f_bb − 2 f_ab, whose error
/// at a gap r = |c_a − c_b|/c is O(r²) because the odd terms cancel about the
/// midpoint. The divided difference instead loses about K·ε/r to roundoff
/// (ε = 2.2e-16; K = |terms summed in f_a| / |f_a|, ~1 for neo-Hookean but
/// ~1e3 for the Dragon Skin Ogden fits, whose terms of size μ_i/α_i ≈ 74 MPa
/// cancel to ≈ 0.1 MPa). Balancing K ε / r against C r² (C ~ 1–10 for the
/// exponents we meet) gives r* = (K ε / 2C)^(1/3) ≈ 5e-6 … 2e-5: the switch at
/// r = 1e-5 keeps either branch within ~2e-8 relative even for the worst fits,
/// whereas a switch at 1e-8 would let the divided difference lose ~1e-5.
/// When the two eigenvalues are exactly equal this is the only formula that is
/// defined, and it is exact — no perturbation of the stretches.
double shear_modulus(double ca, double cb, double fa, double fb, double faa, double fbb, double fab) {
  const double gap = std::abs(ca - cb);
  if (gap <= equal_eigenvalue_tolerance * std::max(ca, cb)) return faa + fbb - 2.0 * fab;
  return 2.0 * (fa - fb) / (ca - cb);
}

/// W, P and A of Hooke's law in E = (C − I)/2 without the eigenvalues of C:
///   S = λ tr E I + 2μ E,  P = F S,
///   A_iJkL = δ_ik S_JL + F_iI ℂ_IJKL F_kK,  ℂ_IJKL = λ δ_IJ δ_KL + μ (δ_IK δ_JL + δ_IL δ_JK),
/// so F ℂ F gives λ F_iJ F_kL + μ (FFᵀ)_ik δ_JL + μ F_iL F_kJ. The same W as the principal form.
template <int N>
std::optional<PrincipalStressOn<N>> evaluate_green_strain_hooke(const GreenStrainHooke& law, const Mat3& F,
                                                                bool with_tangent, const std::array<int, N>& active) {
  const double lambda = law.lambda_MPa, mu = law.mu_MPa;
  const Mat3 E = 0.5 * (F.transpose() * F - Mat3::Identity());
  const double trace = E.trace();
  PrincipalStressOn<N> out;
  out.W = 0.5 * lambda * trace * trace + mu * E.squaredNorm();
  if (!std::isfinite(out.W)) return std::nullopt;
  const Mat3 S = lambda * trace * Mat3::Identity() + 2.0 * mu * E;
  out.P = F * S;
  if (!with_tangent) return out;
  const Mat3 b = F * F.transpose();
  for (int c = 0; c < N; ++c) {
    const int k = active[c] / 3, L = active[c] % 3;
    for (int r = 0; r < N; ++r) {
      const int i = active[r] / 3, J = active[r] % 3;
      out.A(r, c) = (i == k ? S(J, L) : 0.0) + lambda * F(i, J) * F(k, L) + (J == L ? mu * b(i, k) : 0.0) +
                    mu * F(i, L) * F(k, J);
    }
  }
  return out;
}

}  // namespace

template <int N>
std::optional<PrincipalStressOn<N>> evaluate_principal(const HyperelasticLaw& law, const Mat3& F, bool with_tangent,
                                                       const std::array<int, N>& active) {
  const double J = F.determinant();
  if (!(J > 0.0)) return std::nullopt;

  if (const auto hooke = law.green_strain_hooke()) return evaluate_green_strain_hooke<N>(*hooke, F, with_tangent, active);

  const Mat3 C = F.transpose() * F;
  Vec3 c;
  Mat3 Q;  // column a = n_a
  if (!symmetric_eigen3(C, c, Q) || !(c.minCoeff() > 0.0)) return std::nullopt;

  const Jet3 W = law.principal_energy_at(c[0], c[1], c[2]);
  const Vec3& f = W.g;
  const Mat3& fh = W.h;
  if (!std::isfinite(W.v) || !f.allFinite() || (with_tangent && !fh.allFinite())) return std::nullopt;

  PrincipalStressOn<N> out;
  out.W = W.v;
  const Mat3 S = Q * (2.0 * f).asDiagonal() * Q.transpose();
  out.P = F * S;
  if (!with_tangent) return out;

  // Material part F_iI ℂ_IJKL F_kK written with G = F Q (column a = F n_a):
  //  - normal terms Σ_ab 4 f_ab M_a M_bᵀ with M_a(3i+J) = G_ia Q_Ja;
  //  - shear terms: for each pair a < b, ℂ_abab and ℂ_abba (and their (b,a)
  //    images) combine into γ_ab Y Yᵀ with Y(3i+J) = G_ia Q_Jb + G_ib Q_Ja.
  // Each on the active components' rows alone.
  const Mat3 G = F * Q;
  Eigen::Matrix<double, N, 3> M;
  for (int r = 0; r < N; ++r)
    for (int a = 0; a < 3; ++a) M(r, a) = G(active[r] / 3, a) * Q(active[r] % 3, a);
  out.A.noalias() = M.lazyProduct((4.0 * fh).lazyProduct(M.transpose()));  // small: avoid the blocked GEMM path

  for (int a = 0; a < 3; ++a) {
    for (int b = a + 1; b < 3; ++b) {
      const double gamma = shear_modulus(c[a], c[b], f[a], f[b], fh(a, a), fh(b, b), fh(a, b));
      Eigen::Matrix<double, N, 1> Y;
      for (int r = 0; r < N; ++r) {
        const int i = active[r] / 3, Jr = active[r] % 3;
        Y[r] = G(i, a) * Q(Jr, b) + G(i, b) * Q(Jr, a);
      }
      out.A.noalias() += gamma * Y * Y.transpose();
    }
  }

  // Geometric part δ_ik S_JL.
  for (int r = 0; r < N; ++r)
    for (int s = 0; s < N; ++s)
      if (active[r] / 3 == active[s] / 3) out.A(r, s) += S(active[r] % 3, active[s] % 3);
  return out;
}

template std::optional<PrincipalStressOn<5>> evaluate_principal<5>(const HyperelasticLaw&, const Mat3&, bool,
                                                                   const std::array<int, 5>&);
template std::optional<PrincipalStressOn<9>> evaluate_principal<9>(const HyperelasticLaw&, const Mat3&, bool,
                                                                   const std::array<int, 9>&);

std::optional<PrincipalStress> evaluate_principal(const HyperelasticLaw& law, const Mat3& F, bool with_tangent) {
  return evaluate_principal<9>(law, F, with_tangent, kAllComponents);
}

Mat3 cauchy_stress(const Mat3& P, const Mat3& F) { return P * F.transpose() / F.determinant(); }

}  // namespace softarm::fem

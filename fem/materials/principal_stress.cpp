#include "fem/materials/principal_stress.hpp"

#include <Eigen/LU>  // determinant
#include <algorithm>
#include <cmath>

#include "fem/materials/symmetric_eigen3.hpp"

namespace softarm::fem {
namespace {

using Vec3 = Eigen::Vector3d;
using Vec9 = Eigen::Matrix<double, 9, 1>;
using Mat93 = Eigen::Matrix<double, 9, 3>;

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
std::optional<PrincipalStress> evaluate_green_strain_hooke(const GreenStrainHooke& law, const Mat3& F,
                                                          bool with_tangent) {
  const double lambda = law.lambda_MPa, mu = law.mu_MPa;
  const Mat3 E = 0.5 * (F.transpose() * F - Mat3::Identity());
  const double trace = E.trace();
  PrincipalStress out;
  out.W = 0.5 * lambda * trace * trace + mu * E.squaredNorm();
  if (!std::isfinite(out.W)) return std::nullopt;
  const Mat3 S = lambda * trace * Mat3::Identity() + 2.0 * mu * E;
  out.P = F * S;
  if (!with_tangent) return out;
  const Mat3 b = F * F.transpose();
  for (int k = 0; k < 3; ++k)
    for (int L = 0; L < 3; ++L)
      for (int i = 0; i < 3; ++i)
        for (int J = 0; J < 3; ++J)
          out.A(3 * i + J, 3 * k + L) = (i == k ? S(J, L) : 0.0) + lambda * F(i, J) * F(k, L) +
                                        (J == L ? mu * b(i, k) : 0.0) + mu * F(i, L) * F(k, J);
  return out;
}

}  // namespace

std::optional<PrincipalStress> evaluate_principal(const HyperelasticLaw& law, const Mat3& F, bool with_tangent) {
  const double J = F.determinant();
  if (!(J > 0.0)) return std::nullopt;

  if (const auto hooke = law.green_strain_hooke()) return evaluate_green_strain_hooke(*hooke, F, with_tangent);

  const Mat3 C = F.transpose() * F;
  Vec3 c;
  Mat3 Q;  // column a = n_a
  if (!symmetric_eigen3(C, c, Q) || !(c.minCoeff() > 0.0)) return std::nullopt;

  const Jet3 W = law.principal_energy_at(c[0], c[1], c[2]);
  const Vec3& f = W.g;
  const Mat3& fh = W.h;
  if (!std::isfinite(W.v) || !f.allFinite() || (with_tangent && !fh.allFinite())) return std::nullopt;

  PrincipalStress out;
  out.W = W.v;
  const Mat3 S = Q * (2.0 * f).asDiagonal() * Q.transpose();
  out.P = F * S;
  if (!with_tangent) return out;

  // Material part F_iI ℂ_IJKL F_kK written with G = F Q (column a = F n_a):
  //  - normal terms Σ_ab 4 f_ab M_a M_bᵀ with M_a(3i+J) = G_ia Q_Ja;
  //  - shear terms: for each pair a < b, ℂ_abab and ℂ_abba (and their (b,a)
  //    images) combine into γ_ab Y Yᵀ with Y(3i+J) = G_ia Q_Jb + G_ib Q_Ja.
  const Mat3 G = F * Q;
  Mat93 M;
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i < 3; ++i) M.block<3, 1>(3 * i, a) = G(i, a) * Q.col(a);
  out.A.noalias() = M.lazyProduct((4.0 * fh).lazyProduct(M.transpose()));  // small: avoid the blocked GEMM path

  for (int a = 0; a < 3; ++a) {
    for (int b = a + 1; b < 3; ++b) {
      const double gamma = shear_modulus(c[a], c[b], f[a], f[b], fh(a, a), fh(b, b), fh(a, b));
      Vec9 Y;
      for (int i = 0; i < 3; ++i) Y.segment<3>(3 * i) = G(i, a) * Q.col(b) + G(i, b) * Q.col(a);
      out.A.noalias() += gamma * Y * Y.transpose();
    }
  }

  // Geometric part δ_ik S_JL.
  for (int i = 0; i < 3; ++i) out.A.block<3, 3>(3 * i, 3 * i) += S;
  return out;
}

Mat3 cauchy_stress(const Mat3& P, const Mat3& F) { return P * F.transpose() / F.determinant(); }

}  // namespace softarm::fem

#include "fem/materials/principal_stress.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

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

// Eigen-decomposition of a symmetric 3×3 C. Axisymmetric kinematics give a
// block-diagonal C (no coupling of the hoop direction): then one Jacobi
// rotation diagonalises the (r, z) block exactly and cheaply (Golub & Van Loan
// §8.5.2), about 3× faster than the general iterative solver at every Gauss point.
bool symmetric_eigen(const Mat3& C, Vec3& c, Mat3& Q) {
  if (C(0, 2) == 0.0 && C(1, 2) == 0.0) {
    const double a = C(0, 0), b = C(0, 1), d = C(1, 1);
    double cs = 1.0, sn = 0.0, t = 0.0;
    if (b != 0.0) {
      const double tau = (d - a) / (2.0 * b);
      t = (tau >= 0.0 ? 1.0 : -1.0) / (std::abs(tau) + std::sqrt(1.0 + tau * tau));
      cs = 1.0 / std::sqrt(1.0 + t * t);
      sn = t * cs;
    }
    c << a - t * b, d + t * b, C(2, 2);
    Q << cs, sn, 0.0, -sn, cs, 0.0, 0.0, 0.0, 1.0;
    return true;
  }
  // Iterative (QL) solver rather than computeDirect: the closed-form cubic
  // loses accuracy in the eigenvectors of nearly equal eigenvalues.
  Eigen::SelfAdjointEigenSolver<Mat3> eig;
  eig.compute(C, Eigen::ComputeEigenvectors);
  if (eig.info() != Eigen::Success) return false;
  c = eig.eigenvalues();
  Q = eig.eigenvectors();  // column a = n_a
  return true;
}

}  // namespace

std::optional<PrincipalStress> evaluate_principal(const HyperelasticLaw& law, const Mat3& F, bool with_tangent) {
  const double J = F.determinant();
  if (!(J > 0.0)) return std::nullopt;

  const Mat3 C = F.transpose() * F;
  Vec3 c;
  Mat3 Q;  // column a = n_a
  if (!symmetric_eigen(C, c, Q) || !(c.minCoeff() > 0.0)) return std::nullopt;

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

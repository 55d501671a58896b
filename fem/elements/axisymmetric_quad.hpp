#pragma once
// Axisymmetric quadrilaterals in the (r, z) half-plane: the bilinear Q1
// (4 nodes, 2×2 Gauss) and the biquadratic Q2 (9 nodes, 3×3 Gauss).
//
// The deformation gradient of an axisymmetric motion, in the ordering
// (r, z, θ), is
//     F = | ∂r/∂R  ∂r/∂Z  0   |
//         | ∂z/∂R  ∂z/∂Z  0   |
//         | 0      0      r/R |
// (e.g. Bonet & Wood, Nonlinear Continuum Mechanics for FEA, §9). The
// hoop stretch r/R couples the radial displacement into the third principal
// direction; it is what makes a pressurised tube stretch circumferentially.
//
// Each element also carries the space onto which the dilatation J is
// projected for the near-incompressible treatment (see
// elastic_form.hpp): constants for Q1 (Q1/P0, mean dilatation)
// and discontinuous linears {1, R, Z} for Q2 (Q2/P1, inf-sup stable).
//
// Node order: corners counter-clockwise, then (Q2) mid-edge nodes of edges
// 0-1, 1-2, 2-3, 3-0, then the centre: VTK's quad / biquadratic quad order.
#include <Eigen/Core>
#include <Eigen/LU>
#include <array>
#include <cmath>

namespace softarm::fem::axisym {

constexpr double kTwoPi = 6.283185307179586;
using Mat3 = Eigen::Matrix3d;

/// Only five components of F vary in axisymmetry: F_rR, F_rZ, F_zR, F_zZ and
/// F_θΘ, i.e. rows 3i+J = 0, 1, 3, 4, 8 of the 9-vector (row-major) of F.
/// Elements work in this reduced space, which cuts the cost of Bᵀ A B by ~3×.
constexpr int kActive = 5;
inline constexpr std::array<int, kActive> kActiveComponents{0, 1, 3, 4, 8};

/// Bilinear quadrilateral with a constant dilatation.
struct Quad4 {
  static constexpr int kNodes = 4, kGaussPoints = 4, kDilatationModes = 1;
  static constexpr const char* name = "Q1/P0 (mean dilatation)";
  static void shape(double xi, double eta, double* N, double* dN_dxi, double* dN_deta) {
    constexpr double xn[4] = {-1, 1, 1, -1}, en[4] = {-1, -1, 1, 1};
    for (int a = 0; a < 4; ++a) {
      N[a] = 0.25 * (1 + xn[a] * xi) * (1 + en[a] * eta);
      dN_dxi[a] = 0.25 * xn[a] * (1 + en[a] * eta);
      dN_deta[a] = 0.25 * en[a] * (1 + xn[a] * xi);
    }
  }
  static void gauss_point(int q, double& xi, double& eta, double& w) {
    constexpr double g = 0.5773502691896257;  // 1/√3
    constexpr double xs[4] = {-g, g, g, -g}, es[4] = {-g, -g, g, g};
    xi = xs[q], eta = es[q], w = 1.0;
  }
};

/// Biquadratic (9-node Lagrange) quadrilateral with a linear dilatation.
struct Quad9 {
  static constexpr int kNodes = 9, kGaussPoints = 9, kDilatationModes = 3;
  static constexpr const char* name = "Q2/P1 (projected dilatation)";
  static void shape(double xi, double eta, double* N, double* dN_dxi, double* dN_deta) {
    // 1D quadratic Lagrange polynomials on {-1, 0, 1} and their derivatives.
    auto L = [](double s, double* l, double* dl) {
      l[0] = 0.5 * s * (s - 1), l[1] = 1 - s * s, l[2] = 0.5 * s * (s + 1);
      dl[0] = s - 0.5, dl[1] = -2 * s, dl[2] = s + 0.5;
    };
    double lx[3], dlx[3], ly[3], dly[3];
    L(xi, lx, dlx);
    L(eta, ly, dly);
    // (i, j) index of node a in the 1D polynomials (0: −1, 1: 0, 2: +1).
    constexpr int I[9] = {0, 2, 2, 0, 1, 2, 1, 0, 1}, J[9] = {0, 0, 2, 2, 0, 1, 2, 1, 1};
    for (int a = 0; a < 9; ++a) {
      N[a] = lx[I[a]] * ly[J[a]];
      dN_dxi[a] = dlx[I[a]] * ly[J[a]];
      dN_deta[a] = lx[I[a]] * dly[J[a]];
    }
  }
  static void gauss_point(int q, double& xi, double& eta, double& w) {
    constexpr double g = 0.7745966692414834;  // √(3/5)
    constexpr double s[3] = {-g, 0.0, g}, ws[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
    xi = s[q % 3], eta = s[q / 3], w = ws[q % 3] * ws[q / 3];
  }
};

/// Reference-configuration data of one Gauss point (computed once per mesh).
template <class E>
struct ReferencePoint {
  std::array<double, E::kNodes> N{};              // shape functions
  std::array<double, E::kNodes> dN_dR{}, dN_dZ{};  // reference gradients
  double R = 0.0;                                 // reference radius
  double dV = 0.0;                                // 2π R det(∂X/∂ξ) w: full-revolution volume weight
  Eigen::Matrix<double, E::kDilatationModes, 1> phi;  // dilatation basis at this point
};

template <class E>
using NodalCoordinates = Eigen::Matrix<double, E::kNodes, 2>;
template <class E>
using GradientOperator = Eigen::Matrix<double, kActive, 2 * E::kNodes>;  // δF (active) = B δx_e

/// Precomputes the Gauss-point data of an element with reference nodal coordinates
/// X (rows (R, Z)). Returns false if the element is inverted or degenerate at a
/// Gauss point (a mesh error, not a solver event).
template <class E>
bool reference_points(const NodalCoordinates<E>& X, std::array<ReferencePoint<E>, E::kGaussPoints>& out) {
  // The dilatation basis {1, R − R̄, Z − Z̄} is centred on the element for conditioning.
  const Eigen::RowVector2d centre = X.colwise().mean();
  for (int q = 0; q < E::kGaussPoints; ++q) {
    double xi, eta, w;
    E::gauss_point(q, xi, eta, w);
    std::array<double, E::kNodes> dN_dxi{}, dN_deta{};
    ReferencePoint<E>& p = out[q];
    E::shape(xi, eta, p.N.data(), dN_dxi.data(), dN_deta.data());
    Eigen::Matrix2d Jac = Eigen::Matrix2d::Zero();  // Jac(i, k) = ∂X_i/∂ξ_k
    double Z = 0.0;
    p.R = 0.0;
    for (int a = 0; a < E::kNodes; ++a) {
      Jac(0, 0) += X(a, 0) * dN_dxi[a];
      Jac(0, 1) += X(a, 0) * dN_deta[a];
      Jac(1, 0) += X(a, 1) * dN_dxi[a];
      Jac(1, 1) += X(a, 1) * dN_deta[a];
      p.R += p.N[a] * X(a, 0);
      Z += p.N[a] * X(a, 1);
    }
    const double det = Jac.determinant();
    if (!(det > 0.0) || !(p.R > 0.0)) return false;
    const Eigen::Matrix2d inv = Jac.inverse();
    for (int a = 0; a < E::kNodes; ++a) {
      // ∂N/∂X_i = Σ_k ∂N/∂ξ_k ∂ξ_k/∂X_i
      p.dN_dR[a] = dN_dxi[a] * inv(0, 0) + dN_deta[a] * inv(1, 0);
      p.dN_dZ[a] = dN_dxi[a] * inv(0, 1) + dN_deta[a] * inv(1, 1);
    }
    p.dV = kTwoPi * p.R * det * w;
    p.phi[0] = 1.0;
    if constexpr (E::kDilatationModes == 3) {
      p.phi[1] = p.R - centre[0];
      p.phi[2] = Z - centre[1];
    }
  }
  return true;
}

/// Deformation gradient at a Gauss point from current nodal coordinates x.
template <class E>
Mat3 deformation_gradient(const ReferencePoint<E>& p, const NodalCoordinates<E>& x) {
  Mat3 F = Mat3::Zero();
  double r = 0.0;
  for (int a = 0; a < E::kNodes; ++a) {
    F(0, 0) += x(a, 0) * p.dN_dR[a];
    F(0, 1) += x(a, 0) * p.dN_dZ[a];
    F(1, 0) += x(a, 1) * p.dN_dR[a];
    F(1, 1) += x(a, 1) * p.dN_dZ[a];
    r += x(a, 0) * p.N[a];
  }
  F(2, 2) = r / p.R;
  return F;
}

/// δF (active components) = B δx_e, with the element dofs ordered (r_0, z_0, r_1, z_1, ...).
template <class E>
GradientOperator<E> gradient_operator(const ReferencePoint<E>& p) {
  GradientOperator<E> B = GradientOperator<E>::Zero();
  for (int a = 0; a < E::kNodes; ++a) {
    B(0, 2 * a) = p.dN_dR[a];      // δF_rR
    B(1, 2 * a) = p.dN_dZ[a];      // δF_rZ
    B(2, 2 * a + 1) = p.dN_dR[a];  // δF_zR
    B(3, 2 * a + 1) = p.dN_dZ[a];  // δF_zZ
    B(4, 2 * a) = p.N[a] / p.R;    // δF_θΘ = δr / R
  }
  return B;
}

/// out += s Bᵀ v for v over the active components (F_rR, F_rZ, F_zR, F_zZ, F_θΘ): the r-dof of
/// node a meets components {0, 1, 4}, the z-dof {2, 3} (gradient_operator), not the dense product.
template <class E, class Out>
void add_Bt_times(const ReferencePoint<E>& p, const Eigen::Matrix<double, kActive, 1>& v, double s, Out& out) {
  for (int a = 0; a < E::kNodes; ++a) {
    out[2 * a] += s * (p.dN_dR[a] * v[0] + p.dN_dZ[a] * v[1] + p.N[a] / p.R * v[4]);
    out[2 * a + 1] += s * (p.dN_dR[a] * v[2] + p.dN_dZ[a] * v[3]);
  }
}

/// Upper triangle (row <= column) of K += Bᵀ D B for a symmetric 5×5 D, using the structure of B:
/// the r-dof of node a touches rows {0, 1, 4} (∂N/∂R, ∂N/∂Z, N/R) and the z-dof rows {2, 3}. About
/// four times cheaper than the dense product. K is row-major so that each row's update runs over
/// contiguous columns; the form mirrors the sum over an element's points once (as the hexahedron's).
template <class E, class UpperMatrix>
void add_BtDB_upper(const ReferencePoint<E>& p, const Eigen::Matrix<double, kActive, kActive>& D, UpperMatrix& K) {
  static_assert(UpperMatrix::IsRowMajor, "add_BtDB_upper accumulates into a row-major matrix");
  constexpr int n = E::kNodes, m = 2 * n;
  Eigen::Matrix<double, kActive, m, Eigen::RowMajor> DB;  // D B, column by column
  for (int b = 0; b < n; ++b) {
    const double br = p.dN_dR[b], bz = p.dN_dZ[b], bh = p.N[b] / p.R;
    DB.col(2 * b) = D.col(0) * br + D.col(1) * bz + D.col(4) * bh;
    DB.col(2 * b + 1) = D.col(2) * br + D.col(3) * bz;
  }
  for (int a = 0; a < n; ++a) {
    const double ar = p.dN_dR[a], az = p.dN_dZ[a], ah = p.N[a] / p.R;
    const int r = 2 * a, z = r + 1;
    K.row(r).tail(m - r).noalias() +=
        ar * DB.row(0).tail(m - r) + az * DB.row(1).tail(m - r) + ah * DB.row(4).tail(m - r);
    K.row(z).tail(m - z).noalias() += ar * DB.row(2).tail(m - z) + az * DB.row(3).tail(m - z);
  }
}

}  // namespace softarm::fem::axisym

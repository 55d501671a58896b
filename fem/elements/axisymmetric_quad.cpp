#include "fem/elements/axisymmetric_quad.hpp"

#include <Eigen/LU>
#include <cmath>

namespace softarm::fem::axisym {
namespace {
constexpr double g = 0.5773502691896257;  // 1/√3
constexpr std::array<double, 4> xi_gp{-g, g, g, -g};
constexpr std::array<double, 4> eta_gp{-g, -g, g, g};
constexpr std::array<double, 4> xi_node{-1, 1, 1, -1};
constexpr std::array<double, 4> eta_node{-1, -1, 1, 1};
}  // namespace

bool reference_points(const Eigen::Matrix<double, kNodes, 2>& X, std::array<ReferencePoint, kGaussPoints>& out) {
  for (int q = 0; q < kGaussPoints; ++q) {
    std::array<double, kNodes> dN_dxi{}, dN_deta{};
    ReferencePoint& p = out[q];
    for (int a = 0; a < kNodes; ++a) {
      p.N[a] = 0.25 * (1 + xi_node[a] * xi_gp[q]) * (1 + eta_node[a] * eta_gp[q]);
      dN_dxi[a] = 0.25 * xi_node[a] * (1 + eta_node[a] * eta_gp[q]);
      dN_deta[a] = 0.25 * eta_node[a] * (1 + xi_node[a] * xi_gp[q]);
    }
    Eigen::Matrix2d J = Eigen::Matrix2d::Zero();  // J(i, k) = ∂X_i/∂ξ_k
    p.R = 0.0;
    for (int a = 0; a < kNodes; ++a) {
      J(0, 0) += X(a, 0) * dN_dxi[a];
      J(0, 1) += X(a, 0) * dN_deta[a];
      J(1, 0) += X(a, 1) * dN_dxi[a];
      J(1, 1) += X(a, 1) * dN_deta[a];
      p.R += p.N[a] * X(a, 0);
    }
    const double det = J.determinant();
    if (!(det > 0.0) || !(p.R > 0.0)) return false;
    const Eigen::Matrix2d Jinv = J.inverse();
    for (int a = 0; a < kNodes; ++a) {
      // ∂N/∂X_i = Σ_k ∂N/∂ξ_k ∂ξ_k/∂X_i
      p.dN_dR[a] = dN_dxi[a] * Jinv(0, 0) + dN_deta[a] * Jinv(1, 0);
      p.dN_dZ[a] = dN_dxi[a] * Jinv(0, 1) + dN_deta[a] * Jinv(1, 1);
    }
    p.dV = kTwoPi * p.R * det;  // Gauss weights are 1 for the 2×2 rule
  }
  return true;
}

Mat3 deformation_gradient(const ReferencePoint& p, const Eigen::Matrix<double, kNodes, 2>& x) {
  Mat3 F = Mat3::Zero();
  double r = 0.0;
  for (int a = 0; a < kNodes; ++a) {
    F(0, 0) += x(a, 0) * p.dN_dR[a];
    F(0, 1) += x(a, 0) * p.dN_dZ[a];
    F(1, 0) += x(a, 1) * p.dN_dR[a];
    F(1, 1) += x(a, 1) * p.dN_dZ[a];
    r += x(a, 0) * p.N[a];
  }
  F(2, 2) = r / p.R;
  return F;
}

GradientOperator gradient_operator(const ReferencePoint& p) {
  GradientOperator B = GradientOperator::Zero();
  for (int a = 0; a < kNodes; ++a) {
    B(0, 2 * a) = p.dN_dR[a];      // δF_rR
    B(1, 2 * a) = p.dN_dZ[a];      // δF_rZ
    B(2, 2 * a + 1) = p.dN_dR[a];  // δF_zR
    B(3, 2 * a + 1) = p.dN_dZ[a];  // δF_zZ
    B(4, 2 * a) = p.N[a] / p.R;    // δF_θΘ = δr / R
  }
  return B;
}

}  // namespace softarm::fem::axisym

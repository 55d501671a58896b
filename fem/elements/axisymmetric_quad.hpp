#pragma once
// Bilinear axisymmetric quadrilateral (Q1) kinematics in the (r, z) half-plane.
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
// Everything here is per Gauss point and allocation-free.
#include <Eigen/Core>
#include <array>

namespace softarm::fem::axisym {

constexpr int kNodes = 4;
constexpr int kDofs = 8;          // (u_r, u_z) per node
constexpr int kGaussPoints = 4;   // 2 × 2 Gauss–Legendre
constexpr double kTwoPi = 6.283185307179586;

using Mat3 = Eigen::Matrix3d;
using ElementVector = Eigen::Matrix<double, kDofs, 1>;
using ElementMatrix = Eigen::Matrix<double, kDofs, kDofs>;
/// Only five components of F vary in axisymmetry: F_rR, F_rZ, F_zR, F_zZ and
/// F_θΘ, i.e. rows 3i+J = 0, 1, 3, 4, 8 of the 9-vector (row-major) of F.
/// Elements work in this reduced space, which cuts the cost of Bᵀ A B by ~3×.
constexpr int kActive = 5;
constexpr std::array<int, kActive> kActiveComponents{0, 1, 3, 4, 8};
/// Maps element dofs to the five active components of δF.
using GradientOperator = Eigen::Matrix<double, kActive, kDofs>;

/// Reference-configuration data of one Gauss point (computed once per mesh).
struct ReferencePoint {
  std::array<double, kNodes> N{};            // shape functions
  std::array<double, kNodes> dN_dR{}, dN_dZ{};  // reference gradients
  double R = 0.0;                            // reference radius
  double dV = 0.0;                           // 2π R det(∂X/∂ξ) w: full-revolution volume weight
};

/// Precomputes the Gauss-point data of an element with reference nodal coordinates
/// X (4 rows of (R, Z)). Returns false if the element is inverted or degenerate at
/// a Gauss point (a mesh error, not a solver event).
bool reference_points(const Eigen::Matrix<double, kNodes, 2>& X, std::array<ReferencePoint, kGaussPoints>& out);

/// Deformation gradient at a Gauss point from current nodal coordinates x (4 × 2).
Mat3 deformation_gradient(const ReferencePoint& p, const Eigen::Matrix<double, kNodes, 2>& x);

/// δF (active components) = B δx_e, with the element dofs ordered (r_0, z_0, r_1, z_1, ...).
GradientOperator gradient_operator(const ReferencePoint& p);

}  // namespace softarm::fem::axisym

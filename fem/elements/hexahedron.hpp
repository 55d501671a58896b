#pragma once
// Hexahedra in (X, Y, Z) on ξ ∈ [−1, 1]³: the trilinear Hex8 (2×2×2 Gauss),
// the triquadratic Lagrange Hex27 and the 20-node serendipity Hex20 (both
// 3×3×3 Gauss) (e.g. Hughes, The Finite Element Method, §3.5 and §3.7).
//
// Each element carries the space onto which the dilatation J is projected for
// the near-incompressible treatment (projected_dilatation_form.hpp): constants
// for Hex8 (H1/P0, mean dilatation) and discontinuous linears
// {1, X − X̄, Y − Ȳ, Z − Z̄} for Hex27 (H2/P1, inf-sup stable) and Hex20
// (the pairing of Abaqus' and CalculiX's hybrid C3D20H, with full integration
// against hourglass modes).
//
// Node order is VTK's. Hex8 (VTK_HEXAHEDRON = 12): the bottom face ζ = −1
// counter-clockwise seen from +ζ, (−1,−1), (1,−1), (1,1), (−1,1), then the top
// face ζ = +1 in the same order. Hex27 (VTK_TRIQUADRATIC_HEXAHEDRON = 29):
// corners 0–7 as Hex8; mid-edge nodes 8–19 on the edges (0,1), (1,2), (2,3),
// (3,0), (4,5), (5,6), (6,7), (7,4), (0,4), (1,5), (2,6), (3,7); face centres
// 20–25 on the faces ξ = −1, ξ = +1, η = −1, η = +1, ζ = −1, ζ = +1; node 26 at
// the centre. Hex20 (VTK_QUADRATIC_HEXAHEDRON = 25) is Hex27 without nodes
// 20–26, which is also the node order of Abaqus' C3D20. (The prose of vtkTriQuadraticHexahedron.h lists the faces in
// another order, but its drawing and its parametric coordinates, which
// ParaView uses, are the order above.)
#include <Eigen/Core>
#include <Eigen/LU>
#include <array>

#include "fem/elements/hex_btdb_kernel.hpp"

namespace softarm::fem::hex {

using Mat3 = Eigen::Matrix3d;

/// All nine components of F vary in 3D: the active set is the whole row-major 9-vector.
constexpr int kActive = 9;
inline constexpr std::array<int, kActive> kActiveComponents{0, 1, 2, 3, 4, 5, 6, 7, 8};

namespace detail {
/// 1D Lagrange polynomial of degree `order` (1 or 2) through {−1, 1} or {−1, 0, 1},
/// the one that is 1 at node coordinate c ∈ {−1, 0, 1}, and its derivative at s.
template <int order>
void line_shape(double s, int c, double& l, double& dl) {
  if constexpr (order == 1) {
    l = 0.5 * (1 + c * s), dl = 0.5 * c;
  } else if (c == 0) {
    l = 1 - s * s, dl = -2 * s;
  } else {
    l = 0.5 * s * (s + c), dl = s + 0.5 * c;
  }
}

/// Gauss–Legendre point q of the (order+1)³ tensor rule: exact for degree 2·order + 1 per direction.
template <int order>
void tensor_gauss_point(int q, Eigen::Vector3d& xi, double& w) {
  constexpr int n = order + 1;
  constexpr double g1 = 0.5773502691896257, g2 = 0.7745966692414834;  // 1/√3, √(3/5)
  constexpr double s1[2] = {-g1, g1}, w1[2] = {1.0, 1.0};
  constexpr double s2[3] = {-g2, 0.0, g2}, w2[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  const double* s = order == 1 ? s1 : s2;
  const double* ws = order == 1 ? w1 : w2;
  const int i = q % n, j = (q / n) % n, k = q / (n * n);
  xi << s[i], s[j], s[k];
  w = ws[i] * ws[j] * ws[k];
}

/// Tensor-product shape functions N_a = l(ξ) l(η) l(ζ) and their ξ-gradients.
template <int order, int nodes>
void tensor_shape(const int (&ref)[nodes][3], const Eigen::Vector3d& xi, double* N, Eigen::Matrix<double, nodes, 3>& dN) {
  for (int a = 0; a < nodes; ++a) {
    double l[3], dl[3];
    for (int d = 0; d < 3; ++d) line_shape<order>(xi[d], ref[a][d], l[d], dl[d]);
    N[a] = l[0] * l[1] * l[2];
    dN(a, 0) = dl[0] * l[1] * l[2];
    dN(a, 1) = l[0] * dl[1] * l[2];
    dN(a, 2) = l[0] * l[1] * dl[2];
  }
}
}  // namespace detail

/// Trilinear hexahedron with a constant dilatation.
struct Hex8 {
  static constexpr int kNodes = 8, kGaussPoints = 8, kDilatationModes = 1, kOrder = 1;
  static constexpr const char* name = "H1/P0 (mean dilatation)";
  static constexpr int kReference[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                           {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  static void shape(const Eigen::Vector3d& xi, double* N, Eigen::Matrix<double, kNodes, 3>& dN) {
    detail::tensor_shape<kOrder>(kReference, xi, N, dN);
  }
  static void gauss_point(int q, Eigen::Vector3d& xi, double& w) { detail::tensor_gauss_point<kOrder>(q, xi, w); }
};

/// Triquadratic (27-node Lagrange) hexahedron with a linear dilatation.
struct Hex27 {
  static constexpr int kNodes = 27, kGaussPoints = 27, kDilatationModes = 4, kOrder = 2;
  static constexpr const char* name = "H2/P1 (projected dilatation)";
  static constexpr int kReference[27][3] = {
      {-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1},  // corners
      {0, -1, -1},  {1, 0, -1},  {0, 1, -1}, {-1, 0, -1},                                              // bottom edges
      {0, -1, 1},   {1, 0, 1},   {0, 1, 1},  {-1, 0, 1},                                               // top edges
      {-1, -1, 0},  {1, -1, 0},  {1, 1, 0},  {-1, 1, 0},                                               // vertical edges
      {-1, 0, 0},   {1, 0, 0},   {0, -1, 0}, {0, 1, 0},  {0, 0, -1},  {0, 0, 1},                       // face centres
      {0, 0, 0}};                                                                                      // centre
  static void shape(const Eigen::Vector3d& xi, double* N, Eigen::Matrix<double, kNodes, 3>& dN) {
    detail::tensor_shape<kOrder>(kReference, xi, N, dN);
  }
  static void gauss_point(int q, Eigen::Vector3d& xi, double& w) { detail::tensor_gauss_point<kOrder>(q, xi, w); }
};

/// 20-node serendipity hexahedron with a linear dilatation: about half the
/// nodes of Hex27 on the same mesh, quadratic along every edge.
struct Hex20 {
  static constexpr int kNodes = 20, kGaussPoints = 27, kDilatationModes = 4, kOrder = 2;
  static constexpr const char* name = "H2s/P1 (serendipity, projected dilatation)";
  /// Corners: N = ⅛ (1 + ξξ_a)(1 + ηη_a)(1 + ζζ_a)(ξξ_a + ηη_a + ζζ_a − 2);
  /// mid-edge nodes (one reference coordinate 0, say ξ_a): N = ¼ (1 − ξ²)(1 + ηη_a)(1 + ζζ_a).
  static void shape(const Eigen::Vector3d& xi, double* N, Eigen::Matrix<double, kNodes, 3>& dN) {
    for (int a = 0; a < kNodes; ++a) {
      const int* c = Hex27::kReference[a];
      int zero = -1;  // the direction along which a mid-edge node sits at 0
      for (int d = 0; d < 3; ++d)
        if (c[d] == 0) zero = d;
      if (zero < 0) {
        double f[3], s = -2.0;
        for (int d = 0; d < 3; ++d) f[d] = 1 + c[d] * xi[d], s += c[d] * xi[d];
        N[a] = 0.125 * f[0] * f[1] * f[2] * s;
        for (int d = 0; d < 3; ++d) {
          const double others = f[(d + 1) % 3] * f[(d + 2) % 3];
          dN(a, d) = 0.125 * c[d] * others * (s + f[d]);
        }
      } else {
        const int d1 = (zero + 1) % 3, d2 = (zero + 2) % 3;
        const double b = 1 - xi[zero] * xi[zero], f1 = 1 + c[d1] * xi[d1], f2 = 1 + c[d2] * xi[d2];
        N[a] = 0.25 * b * f1 * f2;
        dN(a, zero) = -0.5 * xi[zero] * f1 * f2;
        dN(a, d1) = 0.25 * b * c[d1] * f2;
        dN(a, d2) = 0.25 * b * f1 * c[d2];
      }
    }
  }
  static void gauss_point(int q, Eigen::Vector3d& xi, double& w) { detail::tensor_gauss_point<kOrder>(q, xi, w); }
};

/// Hex20 integrated at the 2×2×2 Gauss points: the element of Abaqus' and
/// CalculiX's C3D20R. The rule is exact for the trilinear part of the
/// integrands only, so a lone element has spurious zero-energy modes besides
/// its six rigid-body modes; in a mesh of two or more elements per direction
/// they do not communicate (Bathe, Finite Element Procedures, §5.5.6; Abaqus
/// Analysis User's Guide: C3D20R needs no hourglass control). With the linear
/// dilatation of Hex20 the four modes of θ are fitted to eight points, which is
/// what keeps the pair free of volumetric locking. About 3.4× fewer
/// constitutive evaluations and BᵀDB products than the 27-point Hex20.
struct Hex20Reduced : Hex20 {
  static constexpr int kGaussPoints = 8;
  static constexpr const char* name = "H2s/P1 reduced (serendipity, 2x2x2 Gauss as C3D20R, projected dilatation)";
  static void gauss_point(int q, Eigen::Vector3d& xi, double& w) { detail::tensor_gauss_point<1>(q, xi, w); }
};

/// Reference-configuration data of one Gauss point (computed once per mesh).
template <class E>
struct ReferencePoint {
  std::array<double, E::kNodes> N{};                // shape functions
  Eigen::Matrix<double, E::kNodes, 3> dN_dX;        // dN_dX(a, J) = ∂N_a/∂X_J
  double dV = 0.0;                                  // det(∂X/∂ξ) w
  Eigen::Matrix<double, E::kDilatationModes, 1> phi;  // dilatation basis at this point
};

template <class E>
using NodalCoordinates = Eigen::Matrix<double, E::kNodes, 3>;
template <class E>
using GradientOperator = Eigen::Matrix<double, kActive, 3 * E::kNodes>;  // δF (row-major 9-vector) = B δx_e

/// Precomputes the Gauss-point data of an element with reference nodal coordinates X
/// (rows (X, Y, Z)). Returns false if the element is inverted or degenerate at a Gauss point.
template <class E>
bool reference_points(const NodalCoordinates<E>& X, std::array<ReferencePoint<E>, E::kGaussPoints>& out) {
  // The dilatation basis {1, X − X̄, Y − Ȳ, Z − Z̄} is centred on the element for conditioning.
  const Eigen::RowVector3d centre = X.colwise().mean();
  for (int q = 0; q < E::kGaussPoints; ++q) {
    Eigen::Vector3d xi;
    double w;
    E::gauss_point(q, xi, w);
    ReferencePoint<E>& p = out[q];
    Eigen::Matrix<double, E::kNodes, 3> dN_dxi;
    E::shape(xi, p.N.data(), dN_dxi);
    const Mat3 Jac = X.transpose() * dN_dxi;  // Jac(i, k) = ∂X_i/∂ξ_k
    const double det = Jac.determinant();
    if (!(det > 0.0)) return false;
    p.dN_dX = dN_dxi * Jac.inverse();  // ∂N/∂X_J = Σ_k ∂N/∂ξ_k ∂ξ_k/∂X_J
    p.dV = det * w;
    p.phi[0] = 1.0;
    if constexpr (E::kDilatationModes == 4) {
      Eigen::RowVector3d Xq = Eigen::RowVector3d::Zero();
      for (int a = 0; a < E::kNodes; ++a) Xq += p.N[a] * X.row(a);
      p.phi.template tail<3>() = (Xq - centre).transpose();
    }
  }
  return true;
}

/// Deformation gradient F_iJ = Σ_a x_ai ∂N_a/∂X_J at a Gauss point.
template <class E>
Mat3 deformation_gradient(const ReferencePoint<E>& p, const NodalCoordinates<E>& x) {
  return x.transpose() * p.dN_dX;
}

/// δF (row-major 9-vector) = B δx_e, element dofs ordered (x_0, y_0, z_0, x_1, ...):
/// dof (a, i) touches rows 3i + J with weight ∂N_a/∂X_J.
template <class E>
GradientOperator<E> gradient_operator(const ReferencePoint<E>& p) {
  GradientOperator<E> B = GradientOperator<E>::Zero();
  for (int a = 0; a < E::kNodes; ++a)
    for (int i = 0; i < 3; ++i)
      for (int J = 0; J < 3; ++J) B(3 * i + J, 3 * a + i) = p.dN_dX(a, J);
  return B;
}

/// out += s Bᵀ v for v over F's nine components (row-major): dof (a, i) meets components 3i + J
/// with weight ∂N_a/∂X_J (gradient_operator), so out(3a + i) += s Σ_J ∂N_a/∂X_J v(3i + J): the three
/// non-zeros of each column of B rather than the dense product (a third of its multiplications, and
/// no B to build at each point).
template <class E, class Out>
void add_Bt_times(const ReferencePoint<E>& p, const Eigen::Matrix<double, kActive, 1>& v, double s, Out& out) {
  for (int a = 0; a < E::kNodes; ++a)
    for (int i = 0; i < 3; ++i)
      out[3 * a + i] += s * (p.dN_dX(a, 0) * v[3 * i] + p.dN_dX(a, 1) * v[3 * i + 1] + p.dN_dX(a, 2) * v[3 * i + 2]);
}

/// Upper triangle (row <= column) of K += Bᵀ D B for a symmetric 9×9 D, using the structure of B
/// (three non-zeros per column, see gradient_operator): 3× fewer operations than the dense product.
/// K is row-major so that each row's update runs over contiguous columns (vectorised); the form
/// mirrors the sum over an element's points once (the element's hot loop: 19 % of a 3CA cell run's
/// samples when each point wrote both triangles entry by entry, 12 % as here on SSE2). K's lower
/// triangle is scratch: the kernel may write a few entries left of the diagonal. On a processor with
/// AVX the loops run four doubles wide, rounding as on SSE2 (hex_btdb_kernel.hpp).
template <class E, class UpperMatrix>
void add_BtDB_upper(const ReferencePoint<E>& p, const Eigen::Matrix<double, kActive, kActive>& D, UpperMatrix& K) {
  static_assert(UpperMatrix::IsRowMajor, "add_BtDB_upper accumulates into a row-major matrix");
  static_assert(UpperMatrix::RowsAtCompileTime == 3 * E::kNodes && UpperMatrix::ColsAtCompileTime == 3 * E::kNodes,
                "add_BtDB_upper accumulates into the element's fixed-size matrix");
#ifdef SOFTARM_KERNEL_AVX
  if (detail::processor_has_avx()) return detail::add_BtDB_upper_avx<E::kNodes>(p.dN_dX.data(), D.data(), K.data());
#endif
  detail::add_BtDB_upper_sse2<E::kNodes>(p.dN_dX.data(), D.data(), K.data());
}

}  // namespace softarm::fem::hex

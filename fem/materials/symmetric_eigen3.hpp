#pragma once
// Eigenvalues and eigenvectors of a symmetric 3×3 matrix (C = FᵀF at every Gauss point of a law
// written in the eigenvalues of C), at the accuracy of the iterative solver and about the cost of
// the closed form where the eigenvalues lie apart.
#include <Eigen/Core>

namespace softarm::fem {

/// Relative gap between the eigenvalues, (c_b − c_a)/c_max, from which the closed form is kept. Its
/// eigenvectors (cross products of rows of C − c I) lose accuracy as ε/gap: measured over rotated
/// spectra, a residual ‖CQ − QΛ‖/‖C‖ of 1e-14 at gap 1e-3, 1e-13 at 1e-4, 1e-12 at 1e-5.
inline constexpr double closed_form_eigenvalue_gap = 1e-3;

/// C = Q diag(c) Qᵀ, column a of Q the unit eigenvector of c_a. Three paths, each at the iterative
/// solver's accuracy:
///  - C block-diagonal in (x, y) and z (axisymmetric kinematics): one Jacobi rotation of the block;
///  - eigenvalues apart by at least closed_form_eigenvalue_gap: the closed form (Eigen's
///    computeDirect: the characteristic cubic's trigonometric roots);
///  - otherwise the iterative solver (Householder tridiagonalisation and QL).
/// False when the solver fails or C is not finite.
bool symmetric_eigen3(const Eigen::Matrix3d& C, Eigen::Vector3d& c, Eigen::Matrix3d& Q);

/// The eigenvalues of symmetric C, ascending, by symmetric_eigen3's paths (the iterative solver's,
/// values only, where those fail): for the stretches and stresses the elements report at every Gauss
/// point.
Eigen::Vector3d ascending_eigenvalues(const Eigen::Matrix3d& C);

}  // namespace softarm::fem

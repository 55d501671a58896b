#pragma once
// Richardson extrapolation of a mesh-convergence series with an observed order
// (Roache 1998, "Verification and Validation in Computational Science and
// Engineering", §5.4 and §5.10 for non-constant refinement ratios): a result f
// that converges as f(h) = f∞ + C·h^q is measured on three meshes h1 > h2 > h3,
// and the three unknowns f∞, C and q are solved for. With constant ratio r the
// order has the closed form q = ln((f1 − f2)/(f2 − f3)) / ln r; with the ratios
// 1 : 1/2 : 1/3 of mesh.axial_level 1, 2, 3 it is the root of
//     (f1 − f2)/(f2 − f3) = (h1^q − h2^q)/(h2^q − h3^q),
// whose right-hand side rises monotonically in q, so bisection finds it.
//
// Used where the 3D references have no finer mesh to compare with (issue 6: "error
// against a converged reference, Richardson extrapolation across 3D refinements").
// No extrapolation is returned where the series does not converge monotonically
// (differences of opposite sign, or an order outside [0.1, 10]): there the
// assumption f = f∞ + C·h^q does not hold and the finest value is all there is.
#include <optional>

namespace softarm::fem {

struct RichardsonEstimate {
  double limit;   // f∞, the value at h → 0
  double order;   // q, the observed order of convergence
  /// |f∞ − f3|: the finest mesh's estimated discretisation error.
  double finest_error;
};

/// f1, f2, f3 measured at mesh sizes h1 > h2 > h3 > 0 (any unit: only the ratios matter).
std::optional<RichardsonEstimate> richardson_extrapolate(double h1, double f1, double h2, double f2, double h3,
                                                         double f3);

/// f∞ for a known order q from two meshes h1 > h2 (Richardson's original formula).
double richardson_with_order(double h1, double f1, double h2, double f2, double order);

}  // namespace softarm::fem

#pragma once
// Where does the equilibrium path fold? The load of a limit point, estimated at a converged
// state from the tangent's lowest eigenvalues and their rates along the path.
//
// Near a fold (a maximum of the load along the path) at load t*, the eigenvalue of the mode that
// goes unstable falls as λ(t) ≈ c √(t* − t) (Thompson & Hunt, "A General Theory of Elastic
// Stability", 1973, ch. 3: a limit point is a simple zero of λ with λ² linear in t). Hence
//     t* ≈ t − λ / (2 dλ/dt).
// For a simple eigenvalue with unit mode m, dλ/dt = mᵀ (dK/dt) m, the derivative of K taken along
// the path: x moves by v = dx/dt = −K⁻¹ ∂r/∂t as t does (r the residual). dK/dt is a central
// difference of the tangent along (v, 1): two assemblies and no further factorisation.
//
// Why: a thin end cap over a narrow chamber bore can fold (balloon at the axis) with the tangent's
// lowest eigenvalue still that of the whole actuator's stretching, far from zero, and with the
// chamber's dp/dV still high: neither the lowest eigenvalue's ratio to its value at rest nor dp/dV
// sees it, but the second or third eigenvalue falls to zero (issue 38, Dragon Skin 10, wall 0.9 r_b,
// cap 0.05 r_b: 4.0e-3, then 1.7e-3 N/mm at 39.80 and 39.95 kPa, the path stopping at 39.98).
#include <functional>
#include <vector>

#include "fem/assembly/energy_problem.hpp"
#include "fem/solver/linear_solver.hpp"

namespace softarm::fem {

struct FoldEstimate {
  bool found = false;        // a falling eigenvalue among those computed
  double load = 0.0;         // t*, in the units of set_load's argument
  double eigenvalue = 0.0;   // λ of the mode that folds, at x (the tangent's units)
  double rate = 0.0;         // dλ/dt along the path
  int mode_index = -1;       // 0: the lowest
  Eigen::VectorXd mode;      // unit vector, zero at prescribed dofs
  int eigenvalues_computed = 0;
};

/// The nearest fold ahead of the converged state x at load t. set_load(t) puts the load level t
/// on the problem's forms (the caller restores its own afterwards). Looks at the `modes` lowest
/// eigenpairs of the tangent (positive definite at x, else nothing is found); `solver` is
/// refactorised.
FoldEstimate estimate_fold(const EnergyProblem& problem, LinearSolver& solver, const Vector& x, double t,
                           const std::function<void(double)>& set_load, int modes = 4);

}  // namespace softarm::fem

#include "fem/solver/fold_estimate.hpp"

#include <algorithm>
#include <cmath>

#include "fem/solver/lowest_modes.hpp"

namespace softarm::fem {

FoldEstimate estimate_fold(const EnergyProblem& problem, LinearSolver& solver, const Vector& x, double t,
                           const std::function<void(double)>& set_load, int modes) {
  FoldEstimate out;
  set_load(t);
  const Evaluation e = problem.evaluate(x, true, true);
  if (!e.status.ok || solver.factorize(e.hessian) != LinearSolver::Status::positive_definite) return out;
  const LowestModes lowest = lowest_modes(solver, e.hessian, problem.is_prescribed(), modes);
  out.eigenvalues_computed = static_cast<int>(lowest.eigenvalues.size());

  // The path tangent v = dx/dt = −K⁻¹ ∂r/∂t. The residual is affine in the load level, so a
  // one-sided difference of unit step is exact up to round-off.
  set_load(t + 1.0);
  Vector dr_dt = problem.evaluate(x, true, false).gradient - e.gradient;
  problem.zero_prescribed(dr_dt);
  Vector v = -solver.solve(dr_dt);
  problem.zero_prescribed(v);

  // dK/dt by a central difference along (v, 1), small enough to resolve a fold a hair ahead:
  // the nodes move by at most 1e-6 of the body's size.
  const Vector& X = problem.reference_positions();
  const double size = std::max(X.cwiseAbs().maxCoeff(), 1e-300);
  const double h = 1e-6 * size / std::max(v.cwiseAbs().maxCoeff(), 1e-300);
  set_load(t + h);
  const Evaluation plus = problem.evaluate(x + h * v, false, true);
  set_load(t - h);
  const Evaluation minus = problem.evaluate(x - h * v, false, true);
  set_load(t);
  if (!plus.status.ok || !minus.status.ok) return out;

  for (std::size_t i = 0; i < lowest.eigenvalues.size(); ++i) {
    const double lambda = lowest.eigenvalues[i];
    const Vector& m = lowest.modes[i];
    const double rate = m.dot(plus.hessian * m - minus.hessian * m) / (2.0 * h);
    if (!(lambda > 0.0) || !(rate < 0.0)) continue;  // only a falling eigenvalue folds ahead
    const double t_star = t - lambda / (2.0 * rate);  // λ² linear in t
    if (!out.found || t_star < out.load) {
      out.found = true;
      out.load = t_star;
      out.eigenvalue = lambda;
      out.rate = rate;
      out.mode_index = static_cast<int>(i);
      out.mode = m;
    }
  }
  return out;
}

}  // namespace softarm::fem

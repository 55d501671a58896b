#pragma once
// Newton–Raphson on the total potential energy with a backtracking line
// search. Convergence (deal.II step-44 style): the residual normalised by the
// larger of the first iteration's residual and the load's force scale, AND
// either the update normalised by the displacement, or the error that the last
// two full steps' contraction leaves at most (remaining_error.hpp), within the
// update tolerance, or the energy norm |δx·r| normalised by its first value;
// or the same with the residual within its tolerance once the floor that rounding
// the positions leaves is taken off (residual_beyond_roundoff, near the tolerance);
// or, when the residual sits on its round-off floor, update and energy norm
// both below tolerance, or the update below
// tolerance and the residual no longer falling, within 100× its tolerance, or beyond the floor that
// rounding the positions leaves by no more (residual_beyond_roundoff). One row per iteration is kept for the
// convergence table.
#include <ostream>
#include <vector>

#include "fem/assembly/energy_problem.hpp"
#include "fem/solver/failure.hpp"
#include "fem/solver/linear_solver.hpp"

namespace softarm::fem {

/// What of the residual r at positions x (tangent K) the round-off floor cannot explain:
/// ‖ max(|r| − kRoundoffFloorFactor ε |K| |x|, 0) ‖, entrywise (summation and the constitutive
/// evaluation add to the ulp of each position, hence the factor). Newton accepts a residual within
/// 100× its tolerance whose part beyond this is within the tolerance, once the state has settled by
/// the update criteria; and one that has stopped falling once its full step is below the update
/// tolerance and this is within 100× the residual tolerance.
inline constexpr double kRoundoffFloorFactor = 10.0;
double residual_beyond_roundoff(const SparseMatrix& K, const Vector& x, const Vector& r);

struct NewtonSettings {
  int max_iterations = 20;
  double residual_tolerance = 1e-8;   // ‖r‖ / max(‖r₀‖, ‖f_load‖, ‖reactions‖)
  // Newton converges quadratically, so once an update is 1e-6 of the
  // displacement the remaining error is ~1e-12 (deal.II step-44 uses the same
  // 1e-6 for the update, with 1e-9 on the residual).
  double update_tolerance = 1e-6;     // ‖δx‖ / max(‖x − X‖, 1e-3 mm), or the remaining-error bound
  double energy_tolerance = 1e-12;    // |δx·r| / |δx₀·r₀|
  int max_line_search = 12;
  double divergence_factor = 1e6;     // ‖r‖ > factor · scale → diverged
  // An indefinite tangent (far from equilibrium, or past a bifurcation) is solved
  // with a shifted Cholesky (LinearSolver::factorize_shifted: a descent direction,
  // one more supernodal factorisation) instead of an exact LU. The LU of a 3D
  // tangent costs minutes (UMFPACK on the 45k-dof 3CA), the shift seconds; at a
  // stable equilibrium the tangent is positive definite, so convergence stays
  // quadratic. The 2D scenes keep LU (cheap there, and exact next to limit points).
  bool shift_indefinite_tangent = false;
  // Solve each Newton step first by CG preconditioned with the last Cholesky factor
  // (LinearSolver::solve_reusing_factor), to the forcing tolerance min(1e-2, ‖r‖/scale)
  // of an inexact Newton method (Eisenstat & Walker 1996: the residual still falls
  // quadratically), and factorise only when that fails. Within a load step, and between
  // steps of a smooth path, the tangent changes little; a 3D factorisation costs
  // seconds, a solve with it a tenth of that. The 3D scenes' default.
  bool reuse_factor = false;
  // Give up (Failure::unstable_branch) once this many iterations on an indefinite tangent failed to
  // halve the best residual so far, with no iteration between that halved it (a positive definite
  // one that did not leaves the count as it is); 0: never. At a stable equilibrium the tangent is
  // positive definite; a run of indefinite ones that makes no progress means the iterates are on no
  // stable branch, as past a limit point, where the step would otherwise spend all max_iterations
  // (the thesis 3CA near its 316 kPa maximum: 4 failed steps × 2 attempts × 20 iterations, three
  // quarters of the run). Shifted steps that still halve the best residual go on (the thesis 3CA's
  // step to 241 kPa, given up at 4.3e-4, now converges; on the SPL pose past half its pressures
  // such tries slow down short of convergence and are given up a few iterations later). With the
  // guard on, an equilibrium reached on an indefinite tangent (a maximum: shifted steps leave alone
  // a negative mode that the residual has no part in) is unstable_branch too. The 3D scenes use 4.
  int max_indefinite_iterations = 0;
  // Stiff parts (the ABS rings and connectors) rotate exactly under the update instead of
  // being stretched by its linearisation (fem/assembly/stiff_inclusions.hpp). Newton itself
  // only calls EnergyProblem::advanced; the 3D scenes read this to hand the problem its stiff
  // parts. Their default: the thesis 3CA's gravity step 14 → 7 iterations, the SPL pose
  // (Hex8 preview) 91 → 43 Newton iterations and 87 → 48 s.
  bool rotate_stiff_parts = false;
};

struct NewtonRow {
  int iteration;
  double residual, update, energy_norm, step_length;
  bool positive_definite;
  int cg_iterations;  // 0: the step came from a fresh factorisation
};

struct NewtonReport {
  bool converged = false;
  Failure failure = Failure::none;
  std::string message;
  int failed_element = -1;  // with inverted_element: the first element turned inside out
  int iterations = 0;
  bool tangent_positive_definite = true;  // at the last factorisation
  std::vector<NewtonRow> rows;
  Evaluation last;                         // evaluation at the returned x
};

/// Factorises a tangent the way these settings ask: shifted Cholesky or LU where it is indefinite.
LinearSolver::Status factorize_tangent(LinearSolver& solver, const SparseMatrix& K, const NewtonSettings& settings);

/// Solves ∇Π(x) = 0 from the given x (whose prescribed dofs are already set).
/// On failure x is left at the last accepted iterate.
NewtonReport solve_newton(const EnergyProblem& problem, Vector& x, LinearSolver& solver, const NewtonSettings& settings);

void print_convergence_table(std::ostream& out, const NewtonReport& report);

}  // namespace softarm::fem

#include "fem/solver/volume_control.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <optional>

#include "fem/core/number_text.hpp"
#include "fem/solver/preconditioned_cg.hpp"

namespace softarm::fem {
namespace {

std::string fmt(double v) { return number_text(v, 5); }

// The two solves of a bordered Newton step without factorising K, which past the maximum is
// indefinite (LU: 3 s per iteration on the thesis 3CA in Hex20, 5 s in Hex27). Adding
// α∇V(∇V·δx + c) = 0 to the first row leaves the bordered system's solution as it is:
//   (K + α∇V∇Vᵀ) a = −r − αc∇V,   (K + α∇V∇Vᵀ) b = P∇V,   δλ = (−c − ∇V·a)/(∇V·b),   δx = a + δλ b,
// with c = V − V*. By the matrix determinant lemma K + α∇V∇Vᵀ is positive definite where K's
// one negative eigenvalue is in a mode that changes the volume and α > 1/|∇VᵀK⁻¹∇V| (past a
// ballooning maximum, which is what volume control is for). CG solves it, preconditioned by the
// Cholesky factor of the tangent where volume control started (an equilibrium of pressure
// control, positive definite); the rank-one term adds one outlying eigenvalue, one more CG
// iteration. dλ/dV follows by Sherman–Morrison: with t = ∇Vᵀ(K + α∇V∇Vᵀ)⁻¹∇V,
// ∇VᵀK⁻¹∇V = t / (1 − αt). Where CG fails (a negative eigenvalue the volume does not see, or
// the budget) the iteration factorises K as before. CG spends its whole budget here, without the
// early give-up of the other solves on a held factor (preconditioned_cg.hpp): that rule projects
// from the mean rate since the first iteration, which the rank-one term's outlier slows until CG
// has found it, and the fallback is an LU of the indefinite K, dearer than the budget in time
// and in memory (in the design's first verification, one end cell's LU, 15,444 unknowns, took
// the process's resident memory from about 730 to 944 MB: docs/performance.md).
struct AugmentedSolves {
  bool wanted = false;   // VolumeControlSettings::augmented_cg
  bool prepared = false;
  LinearSolver factor;   // Cholesky of the tangent at the start
  double alpha = 0;      // 100 / ∇VᵀK₀⁻¹∇V: outlier eigenvalue ~100 of the preconditioned operator
  int budget = 0;        // CG iterations per solve: about an LU's cost for both (prepare)
  int last_iterations = 0;  // of the last iteration's two solves (the convergence table shows them)

  /// From the tangent K₀ and ∇V at the starting equilibrium (the first iteration of the first
  /// volume step, so K₀ is assembled once), or at a later iterate where CG failed and K₀ factorised
  /// positive definite; unusable where K₀ is not positive definite.
  void prepare(const SparseMatrix& K0, const Vector& g) {
    prepared = true;
    alpha = 0;
    if (factor.factorize(K0) != LinearSolver::Status::positive_definite) return;
    const double compliance = g.dot(factor.solve(g));
    if (!(compliance > 0) || !std::isfinite(compliance)) return;
    alpha = 100 / compliance;
    // About an LU's cost for both solves: three times the iterations that cost half a Cholesky
    // factorisation, twice as many where the sweeps read the factor's single-precision copy (each at
    // half the time). The thesis 3CA's free end cell: its 3 LUs gone (docs/performance.md).
    budget = (factor.single_precision_sweeps() ? 6 : 3) * factor.reuse_cg_budget();
  }
  bool solve(const SparseMatrix& K, const Vector& g, const Vector& rhs, double tolerance, Vector& d) {
    if (!(alpha > 0)) return false;
    const LinearOperator apply = [&](const Vector& p) { return Vector(K * p + (alpha * g.dot(p)) * g); };
    const int before = factor.cg_iterations;
    const bool solved = factor.solve_reusing_factor(apply, rhs, tolerance, budget, /*give_up_early=*/false, d);
    last_iterations += factor.cg_iterations - before;
    return solved;
  }
};

/// Adds the augmented solves' costs to the path's solver, whose totals the reports read.
void add_costs(LinearSolver& to, const LinearSolver& from) {
  to.analyse_seconds += from.analyse_seconds;
  to.factorize_seconds += from.factorize_seconds;
  to.solve_seconds += from.solve_seconds;
  to.factorizations += from.factorizations;
  to.cg_iterations += from.cg_iterations;
}

/// Newton on (x, λ) for V(x) = target from (x, level); only on convergence are x and
/// level updated and `state` set (with dλ/dV from the last iteration's tangent).
bool solve_constrained(const EnergyProblem& problem, Vector& x, double& level, LinearSolver& solver,
                       AugmentedSolves& aug, const VolumeControlProblem& vp, double target,
                       const VolumeControlSettings& s, VolumeControlState& state) {
  Vector xt = x;
  double lt = level;
  double scale0 = 0, best_residual = std::numeric_limits<double>::infinity();
  int best_iteration = 0;
  bool positive_definite = true, by_cg = false;
  double slope = std::numeric_limits<double>::quiet_NaN();
  double previous_relative = std::numeric_limits<double>::infinity(), last_update = std::numeric_limits<double>::infinity();
  if (s.verbose)
    std::cout << "  volume step to V = " << fmt(target) << " mm³\n    it   |r|/scale   |V-V*|/V*   level      tangent\n";
  for (int it = 0; it < s.max_iterations; ++it) {
    vp.apply_level(lt);
    const Evaluation e = problem.evaluate(xt, true, true);
    if (!e.status.ok) {
      if (s.verbose) std::cout << "    " << it << "  evaluation failed: " << e.status.reason << "\n";
      return false;
    }
    const double constraint = vp.volume(xt) - target;
    const double r = e.gradient.norm();
    if (it == 0) scale0 = std::max({r, e.force_scale(), 1e-12});
    const double relative = r / std::max(scale0, e.force_scale());
    if (s.verbose)
      std::cout << "    " << it << "  " << number_text(relative, 3) << "  " << number_text(std::abs(constraint / target), 3)
                << "  " << fmt(lt) << "  "
                << (it == 0 ? std::string()
                    : by_cg ? "CG (augmented) " + std::to_string(aug.last_iterations)
                            : std::string(positive_definite ? "SPD" : "indefinite"))
                << "\n";
    // Converged: the residual within its tolerance, or on its round-off floor as Newton's (within 100
    // times the tolerance, no longer halving, the update settled): a ballooning Dragon Skin 10 RRA
    // with a 0.45 mm cap sat at 5e-8 for ten iterations with the volume exact, and every volume step
    // was refused until volume control stalled.
    const bool at_floor = it >= 2 && relative <= 100 * s.residual_tolerance && relative > 0.5 * previous_relative &&
                          last_update <= s.update_tolerance;
    if ((relative <= s.residual_tolerance || at_floor) && std::abs(constraint) <= s.volume_tolerance * std::abs(target)) {
      x = xt;
      level = lt;
      state = {lt, target + constraint, it, positive_definite, slope};  // V(x) without evaluating it again
      return true;
    }
    // Newton with the exact tangent converges quadratically or not at all: a residual 100
    // times above the best one so far, or no new best in 4 iterations, means it has left the
    // solution's basin (by the thesis 3CA's top, Hex27, such iterations wandered between 1e-4
    // and 1e-2 for 10-15 more LUs of 5 s each, until an element inverted).
    const bool diverging = it >= 3 && relative > 100 * best_residual;
    if (it >= 1 && relative < best_residual) best_residual = relative, best_iteration = it;
    if (diverging || it - best_iteration >= 4) {
      if (s.verbose) std::cout << "    not converging: the residual is above its best, of iteration " << best_iteration << "\n";
      return false;
    }
    Vector g = vp.volume_gradient(xt);
    problem.zero_prescribed(g);
    const double P = vp.pressure_per_level_MPa;
    Vector a, b;
    double gb = 0, pivot = 0;  // ∇V·K⁻¹(P∇V), and the ∇V·b that δλ divides by
    // Inexact Newton (Eisenstat & Walker): CG to a hundredth of the relative residual, at most
    // 1e-6, which keeps the convergence quadratic near the solution.
    const double forcing = std::clamp(1e-2 * relative, 1e-12, 1e-6);
    if (aug.wanted && !aug.prepared) aug.prepare(e.hessian, g);
    aug.last_iterations = 0;
    by_cg = aug.solve(e.hessian, g, Vector(-e.gradient - (aug.alpha * constraint) * g), forcing, a) &&
            aug.solve(e.hessian, g, Vector(P * g), forcing, b);
    if (by_cg) {
      pivot = g.dot(b);
      gb = pivot / (1 - aug.alpha * pivot / P);
      positive_definite = gb > 0;  // K is not factorised: only dp/dV < 0 certifies it indefinite
    } else {
      const LinearSolver::Status status = solver.factorize(e.hessian);
      if (status == LinearSolver::Status::singular) return false;
      positive_definite = status == LinearSolver::Status::positive_definite;
      a = solver.solve(-e.gradient);
      b = solver.solve(P * g);
      gb = pivot = g.dot(b);
      // CG failed on a tangent still positive definite: the starting one is too far from here (a
      // path handed over well ahead of its maximum). This one preconditions the iterations to come.
      if (aug.wanted && positive_definite) aug.prepare(e.hessian, g);
    }
    if (!a.allFinite() || !b.allFinite() || !(std::abs(pivot) > 0) || !std::isfinite(gb)) return false;
    slope = 1 / gb;  // dλ/dV along the path: δλ = (δV − ∇V·a)/(∇V·b)
    const double dl = (-constraint - g.dot(a)) / pivot;
    const Vector dx = a + dl * b;
    last_update = dx.norm() / std::max((xt - problem.reference_positions()).norm(), 1e-3);
    previous_relative = relative;
    xt = problem.advanced(xt, dx);
    lt += dl;
    if (!std::isfinite(lt)) return false;
  }
  return false;
}

/// The vertex of the parabola λ(V) through the state `best` and its neighbours, where it is
/// concave (none at either end of the states).
struct Vertex {
  double volume, level;
};
std::optional<Vertex> vertex_around(const std::vector<VolumeControlState>& states, std::size_t best) {
  if (best == 0 || best + 1 >= states.size()) return std::nullopt;
  const auto& s0 = states[best - 1];
  const auto& s1 = states[best];
  const auto& s2 = states[best + 1];
  const double d01 = (s1.level - s0.level) / (s1.volume - s0.volume);
  const double d12 = (s2.level - s1.level) / (s2.volume - s1.volume);
  const double curvature = (d12 - d01) / (s2.volume - s0.volume);  // λ'' / 2
  if (!(curvature < 0)) return std::nullopt;
  const double slope_at_1 = d01 + curvature * (s1.volume - s0.volume);  // λ' at V1
  const double dv = -slope_at_1 / (2 * curvature);
  return Vertex{s1.volume + dv, s1.level + slope_at_1 * dv + curvature * dv * dv};
}

}  // namespace

VolumeControlResult follow_volume(const EnergyProblem& problem, Vector& x, double& level, LinearSolver& solver,
                                  const VolumeControlProblem& vp, double initial_volume_step,
                                  const VolumeControlState* previous, const VolumeControlSettings& settings) {
  VolumeControlResult out;
  if (previous) out.states.push_back(*previous);
  double step = initial_volume_step;
  const double min_step = initial_volume_step / 64;  // six halvings: a stall costs at most ~6 × 20 iterations
  Vector best_x = x;
  double best_level = level;
  out.states.push_back({level, vp.volume(x), 0, true});
  std::size_t best = out.states.size() - 1;
  const std::size_t first = out.states.size();  // states before this one were given, not computed
  Vector step_start_x = x, before_best_x;  // the state each step starts from; the one before the best
  int retraces = 0;
  AugmentedSolves aug;
  aug.wanted = settings.augmented_cg;
  while (static_cast<int>(out.states.size() - first) < settings.max_steps) {
    VolumeControlState state;
    const double target = out.states.back().volume + step;
    if (!solve_constrained(problem, x, level, solver, aug, vp, target, settings, state)) {
      step /= 2;
      if (step < min_step) {
        out.passed_peak = best > 0 && level < (1 - settings.drop_fraction) * best_level;
        out.message = std::string(out.passed_peak ? "past the maximum, " : "") + "volume control stalled at V = " +
                      fmt(out.states.back().volume) + " mm³ (level " + fmt(out.states.back().level) + ")";
        break;
      }
      continue;
    }
    out.newton_iterations += state.iterations;
    out.states.push_back(state);
    if (level > best_level) {
      best_level = level;
      best_x = x;
      best = out.states.size() - 1;
      before_best_x = step_start_x;
    }
    step_start_x = x;
    // K indefinite where dλ/dV is still positive: a mode the volume does not see has gone unstable
    // (a bifurcation). Pressure control's path turns off the traced branch there, so a maximum
    // further along it is not this path's. (A guard for paths handed over ahead of their maximum:
    // none of the scenes' tests meets one.)
    if (settings.stop_at_bifurcation && !state.tangent_positive_definite && state.level_slope_per_mm3 > 0) {
      out.message = "the tangent lost positive definiteness at level " + fmt(level) +
                    " with the pressure still rising (a bifurcation)";
      break;
    }
    if (level >= settings.level_ceiling) {
      out.message = std::string(settings.level_ceiling >= 1 ? "the pressure rose back to the full load" :
                                "the pressure rose to level " + fmt(settings.level_ceiling)) +
                    " at V = " + fmt(out.states.back().volume) + " mm³";
      break;
    }
    // Past the maximum: the level has fallen clearly below it, or it has fallen at a state
    // where the tangent itself says dλ/dV < 0 (the thesis 3CA's top, Hex27: a fall of 0.011 %
    // on an indefinite tangent, then no volume step converged).
    const bool fell = level < (1 - settings.drop_fraction) * best_level;
    const bool descending = level < best_level && state.level_slope_per_mm3 < 0;
    // A maximum bracketed by steps too long to place it: the pressure fell far past it, or the
    // parabola's vertex lies well above every traced state (steps grown on an easy climb, or a
    // path handed over well ahead of its maximum). Such a vertex is off: a Dragon Skin 30 end cap
    // of 0.05, handed over at 87.16 kPa and fallen to 99.50 %, gave 87.57 kPa against 87.83 by
    // creeping pressure control; a thin neo-Hookean tube's first step from 30 kPa landed just past
    // its top, and the vertex through 30 and 30.64 kPa was 30.70 against 30.65. The top is traced
    // again from the state before the largest with quarter steps, at most max_retraces times (from
    // the starting state itself where that is the largest: the state before it has no x here).
    const auto top = (fell || descending) ? vertex_around(out.states, best) : std::nullopt;
    const bool coarse = level < (1 - settings.retrace_fall_fraction) * best_level ||
                        (top && top->level > (1 + settings.retrace_vertex_fraction) * best_level);
    if ((fell || descending) && retraces < settings.max_retraces && coarse) {
      ++retraces;
      const std::size_t from = best >= first ? best - 1 : best;
      step = (out.states[from + 1].volume - out.states[from].volume) / 4;
      if (from < best) best_x = before_best_x;
      out.states.resize(from + 1);
      best = from;
      best_level = level = out.states[best].level;
      x = step_start_x = best_x;
      vp.apply_level(level);
      continue;
    }
    if ((fell || descending) && best > 0) {
      out.passed_peak = true;
      out.message = "the pressure passed its maximum and fell to " + fmt(level / best_level * 100) + " % of it" +
                    (fell ? "" : ", where the tangent gives dp/dV < 0");
      break;
    }
    if (state.iterations <= 4) step *= 1.5;
  }
  if (out.message.empty())
    out.message = "no maximum within " + std::to_string(settings.max_steps) + " volume steps";
  out.peak_level = best_level;
  out.peak_volume = out.states[best].volume;
  if (out.passed_peak)
    if (const auto top = vertex_around(out.states, best)) out.peak_volume = top->volume, out.peak_level = top->level;
  out.states.erase(out.states.begin(), out.states.begin() + static_cast<std::ptrdiff_t>(first - 1));  // from the start
  add_costs(solver, aug.factor);
  x = best_x;
  level = best_level;
  vp.apply_level(level);
  return out;
}

}  // namespace softarm::fem

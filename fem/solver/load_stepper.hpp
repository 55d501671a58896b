#pragma once
// Adaptive load stepping along a load level λ ∈ [0, 1] (FEBio's step
// controller): lands exactly on every requested output level, grows the step
// after easy convergence, shrinks it after hard convergence, and on any typed
// failure restores the last converged state and cuts the step back. The
// predictor extrapolates the last three converged states (a parabola in λ; the
// secant through two at the start of the path), with the path's slope where the
// caller gives it (a cubic, or on the second step a parabola, each taken where it
// agrees with the prediction without the slope); if Newton fails
// from the predicted state the step is retried from the last state, except after
// an unstable branch (only indefinite tangents: no equilibrium near that load),
// after which the steps halve their distance to that level instead of trying it again
// (where a predicted start failed so: a plain one may fail merely by overshooting).
// A path that cannot be continued returns what it reached and why.
#include <array>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "fem/solver/newton.hpp"

namespace softarm::fem {

struct StepSettings {
  double initial_increment = 0.1;   // first Δλ
  double min_increment = 1e-5;      // below this the path is declared stuck
  double max_increment = 0.25;
  // Converged in ≤ this: grow Δλ. 5, not 4: with the 1e-8 residual tolerance a
  // quadratically converging step often needs 5 iterations, and at 4 the thesis 3CA,
  // once cut back after its first step, crept along at Δλ ≈ 0.016 (5 iterations
  // each, neither easy nor hard) for the whole curve.
  int easy_iterations = 5;
  int hard_iterations = 9;          // converged in ≥ this: shrink Δλ
  double growth = 1.5, shrink = 0.7, cutback = 0.25;
  bool verbose = false;             // print the Newton convergence table of every step
};

struct PathStatistics {
  int steps = 0, newton_iterations = 0, cutbacks = 0;
  int second_starts = 0;  // steps retried from the last converged state after the predicted start failed
  int halved_steps = 0;   // steps cut to half the distance to a level where Newton met only indefinite tangents
  std::vector<double> failed_levels;  // levels where every start failed, in the order tried
};

struct PathResult {
  bool completed = false;
  double reached_level = 0.0;       // last converged λ
  Failure failure = Failure::none;  // last failure when not completed
  std::string message;
  int failed_element = -1;  // with inverted_element: the element
  /// The caller stopped the path before a step (PathCallbacks::stop_before): not completed, and no
  /// failure; x is the converged state at reached_level, and next_level the level it would have tried.
  bool stopped = false;
  double next_level = 0.0;
  PathStatistics stats;
};

struct PathCallbacks {
  /// Sets the loads (pressures, prescribed-displacement scale, …) for level λ.
  std::function<void(double level)> apply_load;
  /// Called after each converged step; `is_output` marks requested levels.
  std::function<void(double level, const Vector& x, bool is_output, const NewtonReport& report)> on_converged;
  /// Called after on_converged with the increment the controller will try next: with the
  /// converged states, what a resumed path needs to go on as this one would (PathStart).
  std::function<void(double next_increment, const PathStatistics& stats)> on_increment = {};
  /// Asked before each step with the level it would try and the path's statistics so far (the
  /// levels every start failed at among them): true stops the path at the converged state it holds
  /// (PathResult::stopped), for a caller that sees a limit point ahead and would rather pass it
  /// another way than try steps beyond it (fem/scenes/pressure_path.cpp).
  std::function<bool(double next_level, const PathStatistics& stats)> stop_before = {};
  /// The path's slope dx/dλ at the state on_converged was last given (empty where the caller has
  /// none): the predictor's cubic (extrapolate_with_slope) and second-step parabola
  /// (extrapolate_second_step) take it.
  std::function<Vector()> slope = {};
};

/// Where a path starts: at rest (level 0, no history, the initial increment), or where an
/// earlier run of the same problem stopped (a checkpoint, fem/scenes/path_log.hpp): x is then
/// the converged state at `level`, and `earlier` up to two converged states before it, oldest
/// first, for the predictor. The step controller's other memory (a level where Newton met only
/// indefinite tangents) is not kept: it only saves attempts near a limit point.
struct PathStart {
  double level = 0.0;
  double increment = 0.0;  // ≤ 0: StepSettings::initial_increment
  std::vector<std::pair<double, Vector>> earlier;
  PathStatistics stats;    // of the path up to `level`, carried on
  bool resumed = false;    // the outputs at or below `level` were reached by the earlier run
};

/// The level of the next step from `level` towards the output level `target` with
/// the step controller's current increment (lands exactly on `target`, leaves no sliver).
double next_step_level(double level, double increment, double target);

/// The predicted state at level `target` from converged states at distinct levels: the
/// Lagrange parabola through (levels[i], states[i]), i = 0, 1, 2, or with two states the
/// secant. A bending actuator's points move on arcs: the secant's error grows with the
/// square of the step, the parabola's with its cube (thesis 3CA, Δλ = 0.1: 11° of bend per
/// step, and the secant's start had an indefinite tangent).
Vector extrapolate_state(const std::vector<double>& levels, const std::vector<const Vector*>& states, double target);

/// The predicted state at `target` from converged states x0, x1, x2 at levels l0 < l1 < l2 and the
/// path's slope t2 = dx/dλ at x2: the cubic q(λ) = x2 + t2 s + a s² + b s³ (s = λ − l2) through all
/// three. Its error grows with the fourth power of the step, the parabola's with the third; the slope
/// costs one solve with the tangent at x2, which dp/dV takes there anyway (pressure_path.cpp).
Vector extrapolate_with_slope(const std::array<double, 3>& levels, const std::array<const Vector*, 3>& states,
                              const Vector& slope, double target);

/// The cubic where it agrees with the parabola, the parabola where not: the cubic's prediction is
/// taken where it lies within kSlopePredictorAgreement of the parabola's step from x2 (‖cubic −
/// parabola‖ ≤ 0.1 ‖parabola − x2‖). Near a limit point the slope grows without bound and the cubic
/// overshoots: on the thesis 3CA's free end cell, taken everywhere, it cost 255 Newton iterations
/// and 53 shifted attempts against 244 and 43; with this test 234 and 43 (bench_speed --item tca).
inline constexpr double kSlopePredictorAgreement = 0.1;
Vector predict_with_slope(const std::array<double, 3>& levels, const std::array<const Vector*, 3>& states,
                          const Vector& slope, double target);

/// A path's second step, with two converged states x0, x1 at levels l0 < l1 and the path's slope t1 =
/// dx/dλ at x1: the parabola q(λ) = x1 + t1 s + a s² (s = λ − l1) through x0. The secant's error grows
/// with the square of the step, this parabola's with its cube.
Vector extrapolate_second_step(const std::array<double, 2>& levels, const std::array<const Vector*, 2>& states,
                               const Vector& slope, double target);

/// The parabola with the slope where it lies within kSecondStepAgreement of the secant's step from x1,
/// the secant where not (or where the slope is not finite), as predict_with_slope guards its cubic.
/// The thesis RRA's step from 20.7 to 41.4 kPa: the parabola 0.13 of the secant's step from it, 9 → 5
/// Newton iterations and 2 → 1 LUs (the secant's start lies on an indefinite tangent).
inline constexpr double kSecondStepAgreement = 0.5;
Vector predict_second_step(const std::array<double, 2>& levels, const std::array<const Vector*, 2>& states,
                           const Vector& slope, double target);

/// Follows the path from the converged state x at `start.level` (0 by default) through the
/// sorted output levels above it (the last is the end).
PathResult follow_load_path(const EnergyProblem& problem, Vector& x, LinearSolver& solver,
                            const std::vector<double>& output_levels, const PathCallbacks& callbacks,
                            const NewtonSettings& newton, const StepSettings& steps, const PathStart& start = {});

}  // namespace softarm::fem

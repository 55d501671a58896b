#include "fem/solver/load_stepper.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <stdexcept>

namespace softarm::fem {

/// The level of the next step towards `target`: one full increment, except that
/// the step never leaves a sliver before the output level. Within 1.3 increments it
/// lands (a 30 % longer step converges as well as the secant predictor allows),
/// within two it goes half way: on the thesis 3CA the plain rule took a 0.09 step and
/// then a 0.01 one to every output level, each costing a whole Newton solve.
double next_step_level(double level, double increment, double target) {
  const double remaining = target - level;
  if (remaining <= 1.3 * increment) return target;
  if (remaining < 2.0 * increment) return level + 0.5 * remaining;
  return level + increment;
}

Vector extrapolate_state(const std::vector<double>& levels, const std::vector<const Vector*>& states, double target) {
  const std::size_t n = levels.size();
  Vector x = Vector::Zero(states.front()->size());
  for (std::size_t i = 0; i < n; ++i) {
    double weight = 1;  // Lagrange basis polynomial i at the target
    for (std::size_t j = 0; j < n; ++j)
      if (j != i) weight *= (target - levels[j]) / (levels[i] - levels[j]);
    x += weight * *states[i];
  }
  return x;
}

PathResult follow_load_path(const EnergyProblem& problem, Vector& x, LinearSolver& solver,
                            const std::vector<double>& output_levels, const PathCallbacks& callbacks,
                            const NewtonSettings& newton, const StepSettings& settings, const PathStart& start) {
  PathResult result;
  result.stats = start.stats;
  double level = start.level, previous_level = start.level, older_level = start.level;
  Vector previous_x = x, older_x;
  int history = 0;  // converged states before x that the predictor may use (0, 1 or 2)
  if (start.earlier.size() > 2) throw std::logic_error("follow_load_path: at most two earlier states");
  for (const auto& [earlier_level, earlier_x] : start.earlier) {
    if (history >= 1) older_x = std::move(previous_x), older_level = previous_level;
    previous_x = earlier_x, previous_level = earlier_level;
    ++history;
  }
  double increment = start.increment > 0 ? start.increment : settings.initial_increment;
  constexpr double kLandingTolerance = 1e-12;
  std::size_t next_output = 0;  // the first output level above a resumed start (from rest: the first)
  if (start.resumed)
    while (next_output < output_levels.size() && output_levels[next_output] - level <= kLandingTolerance) ++next_output;
  result.reached_level = level;
  constexpr double kNoCeiling = std::numeric_limits<double>::infinity();
  double ceiling = kNoCeiling;  // lowest level of an unstable-branch failure not yet passed
  int halvings = 0;             // steps cut to half the distance to the ceiling since it was set
  bool failed_from_prediction = false;  // the last failed attempt started from the predictor

  // One step to next_level: with the secant predictor first, then (if that
  // fails and a predictor was used) from the last converged state.
  auto try_step = [&](double next_level, bool lands) {
    for (int attempt = 0; attempt < 2; ++attempt) {
      const bool predict = attempt == 0 && history >= 1 && level > previous_level;
      if (attempt == 1) ++result.stats.second_starts;
      Vector trial = x;
      if (predict && history >= 2 && previous_level > older_level)
        trial = extrapolate_state({older_level, previous_level, level}, {&older_x, &previous_x, &x}, next_level);
      else if (predict)
        trial = extrapolate_state({previous_level, level}, {&previous_x, &x}, next_level);
      problem.apply_constraints(trial, next_level);
      NewtonReport report = solve_newton(problem, trial, solver, newton);
      result.stats.newton_iterations += report.iterations;
      if (settings.verbose) {
        std::cout << "  step to level " << std::defaultfloat << std::setprecision(6) << next_level
                  << (predict ? "" : " (no predictor)") << "\n";
        print_convergence_table(std::cout, report);
      }
      if (!report.converged) {
        result.failure = report.failure;
        result.message = report.message;
        result.failed_element = report.failed_element;
        failed_from_prediction = predict;
        if (!predict) return false;  // the plain start failed too: nothing else to retry
        // Newton met only indefinite tangents: there is no stable equilibrium near this load
        // (past a limit point), wherever it starts from; the cut-back, not a second start, is
        // what helps. On the thesis 3CA the plain start failed too in all 4 such retries.
        if (report.failure == Failure::unstable_branch) return false;
        continue;
      }
      if (history >= 1) older_x = std::move(previous_x), older_level = previous_level;
      previous_x = x;
      previous_level = level;
      history = std::min(history + 1, 2);
      x = std::move(trial);
      level = next_level;
      ++result.stats.steps;
      result.reached_level = level;
      if (lands) ++next_output;
      if (callbacks.on_converged) callbacks.on_converged(level, x, lands, report);
      if (report.iterations <= settings.easy_iterations) increment = std::min(increment * settings.growth, settings.max_increment);
      if (report.iterations >= settings.hard_iterations) increment *= settings.shrink;
      if (callbacks.on_increment) callbacks.on_increment(increment, result.stats);
      return true;
    }
    return false;
  };

  while (next_output < output_levels.size()) {
    const double target = output_levels[next_output];
    double next_level = next_step_level(level, increment, target);
    // Below a level where Newton met only indefinite tangents, halve the distance to it
    // instead of trying it again: near a limit point every failed try costs a run of
    // shifted factorisations, a converged half step a few cheap iterations (thesis 3CA:
    // 2 of its 4 failed tries at 310 kPa were repeats). A failure far from a limit point
    // (a bad predictor) is passed once the distance is small or halved kMaxHalvings times.
    constexpr int kMaxHalvings = 6;
    if (ceiling - level < 2 * settings.min_increment || halvings >= kMaxHalvings) ceiling = kNoCeiling;
    if (level + 0.5 * (ceiling - level) < next_level) {
      next_level = level + 0.5 * (ceiling - level);
      ++halvings;
      ++result.stats.halved_steps;
    }
    const bool lands = target - next_level <= kLandingTolerance;

    callbacks.apply_load(next_level);
    if (try_step(next_level, lands)) continue;
    result.stats.failed_levels.push_back(next_level);
    // Only a predicted start that failed says the path has no stable state near that level: a
    // plain start (the first step from rest, 0.1 of the SPL pose's pressures) may fail merely by
    // overshooting, and halving up to it cost that run 4 steps before 0.2 converged at once.
    if (result.failure == Failure::unstable_branch && failed_from_prediction && next_level < ceiling)
      ceiling = next_level, halvings = 0;
    // Every attempt failed: cut back from the last converged state.
    ++result.stats.cutbacks;
    increment = (next_level - level) * settings.cutback;
    if (increment < settings.min_increment) {
      callbacks.apply_load(level);
      return result;
    }
  }
  result.completed = true;
  result.failure = Failure::none;
  result.message.clear();
  result.failed_element = -1;
  return result;
}

}  // namespace softarm::fem

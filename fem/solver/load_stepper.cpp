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

Vector extrapolate_with_slope(const std::array<double, 3>& levels, const std::array<const Vector*, 3>& states,
                              const Vector& slope, double target) {
  // With s measured from l2, the residues R_i = x_i − x2 − t2 s_i (i = 0, 1) are a s_i² + b s_i³:
  // two equations for a and b, the same 2×2 system for every component.
  const double s0 = levels[0] - levels[2], s1 = levels[1] - levels[2], s = target - levels[2];
  const Vector& x2 = *states[2];
  const Vector R0 = *states[0] - x2 - s0 * slope, R1 = *states[1] - x2 - s1 * slope;
  const double det = s0 * s0 * s1 * s1 * (s1 - s0);
  const Vector a = (s1 * s1 * s1 * R0 - s0 * s0 * s0 * R1) / det;
  const Vector b = (s0 * s0 * R1 - s1 * s1 * R0) / det;
  return x2 + s * slope + (s * s) * a + (s * s * s) * b;
}

Vector extrapolate_second_step(const std::array<double, 2>& levels, const std::array<const Vector*, 2>& states,
                               const Vector& slope, double target) {
  // With s measured from l1, x0 − x1 − t1 s0 = a s0².
  const double s0 = levels[0] - levels[1], s = target - levels[1];
  const Vector& x1 = *states[1];
  const Vector a = (*states[0] - x1 - s0 * slope) / (s0 * s0);
  return x1 + s * slope + (s * s) * a;
}

namespace {
/// The prediction with the path's slope where it is finite and lies within `agreement` of the step
/// the one without it takes from `last` (the newest converged state), else the one without.
Vector agreeing_or_plain(Vector with_slope, Vector plain, const Vector& last, double agreement) {
  if (with_slope.allFinite() && (with_slope - plain).norm() <= agreement * (plain - last).norm()) return with_slope;
  return plain;
}
}  // namespace

Vector predict_second_step(const std::array<double, 2>& levels, const std::array<const Vector*, 2>& states,
                           const Vector& slope, double target) {
  return agreeing_or_plain(extrapolate_second_step(levels, states, slope, target),
                           extrapolate_state({levels[0], levels[1]}, {states[0], states[1]}, target), *states[1],
                           kSecondStepAgreement);
}

Vector predict_with_slope(const std::array<double, 3>& levels, const std::array<const Vector*, 3>& states,
                          const Vector& slope, double target) {
  return agreeing_or_plain(extrapolate_with_slope(levels, states, slope, target),
                           extrapolate_state({levels[0], levels[1], levels[2]}, {states[0], states[1], states[2]}, target),
                           *states[2], kSlopePredictorAgreement);
}

namespace {
constexpr double kLandingTolerance = 1e-12;
constexpr double kNoCeiling = std::numeric_limits<double>::infinity();

/// The path's state between steps: the converged state x at `level` and up to two before it (the
/// predictor's), the increment, and the ceiling: the lowest level of an unstable-branch failure not
/// yet passed, with the halvings towards it since it was set.
class PathFollower {
 public:
  PathFollower(const EnergyProblem& problem, Vector& x, LinearSolver& solver, const PathCallbacks& callbacks,
               const NewtonSettings& newton, const StepSettings& settings, const PathStart& start, PathResult& result)
      : problem_(problem), x_(x), solver_(solver), callbacks_(callbacks), newton_(newton), settings_(settings),
        result_(result), level_(start.level), previous_level_(start.level), older_level_(start.level), previous_x_(x) {
    if (start.earlier.size() > 2) throw std::logic_error("follow_load_path: at most two earlier states");
    for (const auto& [earlier_level, earlier_x] : start.earlier) {
      if (history_ >= 1) older_x_ = std::move(previous_x_), older_level_ = previous_level_;
      previous_x_ = earlier_x, previous_level_ = earlier_level;
      ++history_;
    }
    increment_ = start.increment > 0 ? start.increment : settings.initial_increment;
    result_.reached_level = level_;
  }

  std::size_t landed() const { return landed_; }  // output levels landed on in this call

  /// The next level towards `target`: a full increment (never leaving a sliver), but below a ceiling
  /// half the distance to it instead of trying it again: near a limit point every failed try costs a
  /// run of shifted factorisations, a converged half step a few cheap iterations (thesis 3CA: 2 of its
  /// 4 failed tries at 310 kPa were repeats). A failure far from a limit point (a bad predictor) is
  /// passed once the distance is small or halved kMaxHalvings times.
  double next_level(double target) {
    double next = next_step_level(level_, increment_, target);
    constexpr int kMaxHalvings = 6;
    if (ceiling_ - level_ < 2 * settings_.min_increment || halvings_ >= kMaxHalvings) ceiling_ = kNoCeiling;
    if (level_ + 0.5 * (ceiling_ - level_) < next) {
      next = level_ + 0.5 * (ceiling_ - level_);
      ++halvings_;
      ++result_.stats.halved_steps;
    }
    return next;
  }

  /// One step to `next`: from the predicted state first (secant, parabola, or the cubic with the
  /// path's slope), then, if that fails and a predictor was used, from the last converged state.
  bool try_step(double next, bool lands) {
    for (int attempt = 0; attempt < 2; ++attempt) {
      const bool predict = attempt == 0 && history_ >= 1 && level_ > previous_level_;
      if (attempt == 1) ++result_.stats.second_starts;
      Vector trial = predict ? predicted(next) : x_;
      problem_.apply_constraints(trial, next);
      NewtonReport report = solve_newton(problem_, trial, solver_, newton_);
      result_.stats.newton_iterations += report.iterations;
      if (settings_.verbose) {
        std::cout << "  step to level " << std::defaultfloat << std::setprecision(6) << next
                  << (predict ? "" : " (no predictor)") << "\n";
        print_convergence_table(std::cout, report);
      }
      if (report.converged) {
        accept(std::move(trial), next, lands, report);
        return true;
      }
      result_.failure = report.failure;
      result_.message = report.message;
      result_.failed_element = report.failed_element;
      failed_from_prediction_ = predict;
      if (!predict) return false;  // the plain start failed too: nothing else to retry
      // Newton met only indefinite tangents: there is no stable equilibrium near this load (past a
      // limit point), wherever it starts from; the cut-back, not a second start, is what helps. On
      // the thesis 3CA the plain start failed too in all 4 such retries.
      if (report.failure == Failure::unstable_branch) return false;
    }
    return false;
  }

  /// After every attempt at `next` failed: the ceiling where the predicted start met only unstable
  /// states, and the increment cut back from the last converged state; false where it falls below
  /// the smallest (the load is set back to the last converged level).
  bool cut_back(double next) {
    result_.stats.failed_levels.push_back(next);
    // Only a predicted start that failed says the path has no stable state near that level: a plain
    // start (the first step from rest, 0.1 of the SPL pose's pressures) may fail merely by
    // overshooting, and halving up to it cost that run 4 steps before 0.2 converged at once.
    if (result_.failure == Failure::unstable_branch && failed_from_prediction_ && next < ceiling_)
      ceiling_ = next, halvings_ = 0;
    ++result_.stats.cutbacks;
    increment_ = (next - level_) * settings_.cutback;
    if (increment_ >= settings_.min_increment) return true;
    callbacks_.apply_load(level_);
    return false;
  }

 private:
  const EnergyProblem& problem_;
  Vector& x_;
  LinearSolver& solver_;
  const PathCallbacks& callbacks_;
  const NewtonSettings& newton_;
  const StepSettings& settings_;
  PathResult& result_;
  double level_, previous_level_, older_level_;
  Vector previous_x_, older_x_;
  Vector slope_;  // dx/dλ at x_ where the caller gives it (PathCallbacks::slope), else empty
  int history_ = 0;  // converged states before x that the predictor may use (0, 1 or 2)
  double increment_ = 0;
  double ceiling_ = kNoCeiling;
  int halvings_ = 0;
  bool failed_from_prediction_ = false;  // the last failed attempt started from the predictor
  std::size_t landed_ = 0;

  Vector predicted(double next) const {
    if (history_ >= 2 && previous_level_ > older_level_) {
      if (slope_.size() == x_.size())
        return predict_with_slope({older_level_, previous_level_, level_}, {&older_x_, &previous_x_, &x_}, slope_, next);
      return extrapolate_state({older_level_, previous_level_, level_}, {&older_x_, &previous_x_, &x_}, next);
    }
    if (slope_.size() == x_.size())
      return predict_second_step({previous_level_, level_}, {&previous_x_, &x_}, slope_, next);
    return extrapolate_state({previous_level_, level_}, {&previous_x_, &x_}, next);
  }

  /// The converged trial becomes the state; the increment grows after an easy step, shrinks after a
  /// hard one.
  void accept(Vector trial, double next, bool lands, const NewtonReport& report) {
    if (history_ >= 1) older_x_ = std::move(previous_x_), older_level_ = previous_level_;
    previous_x_ = x_;
    previous_level_ = level_;
    history_ = std::min(history_ + 1, 2);
    x_ = std::move(trial);
    level_ = next;
    ++result_.stats.steps;
    result_.reached_level = level_;
    if (lands) ++landed_;
    if (callbacks_.on_converged) callbacks_.on_converged(level_, x_, lands, report);
    slope_ = callbacks_.slope ? callbacks_.slope() : Vector();
    if (report.iterations <= settings_.easy_iterations)
      increment_ = std::min(increment_ * settings_.growth, settings_.max_increment);
    if (report.iterations >= settings_.hard_iterations) increment_ *= settings_.shrink;
    if (callbacks_.on_increment) callbacks_.on_increment(increment_, result_.stats);
  }
};
}  // namespace

PathResult follow_load_path(const EnergyProblem& problem, Vector& x, LinearSolver& solver,
                            const std::vector<double>& output_levels, const PathCallbacks& callbacks,
                            const NewtonSettings& newton, const StepSettings& settings, const PathStart& start) {
  PathResult result;
  result.stats = start.stats;
  PathFollower path(problem, x, solver, callbacks, newton, settings, start, result);
  std::size_t first_output = 0;  // the first output level above a resumed start (from rest: the first)
  if (start.resumed)
    while (first_output < output_levels.size() && output_levels[first_output] - start.level <= kLandingTolerance)
      ++first_output;
  while (first_output + path.landed() < output_levels.size()) {
    const double target = output_levels[first_output + path.landed()];
    const double next_level = path.next_level(target);
    const bool lands = target - next_level <= kLandingTolerance;
    if (callbacks.stop_before && callbacks.stop_before(next_level, result.stats)) {
      result.stopped = true;
      result.next_level = next_level;
      result.message = "stopped before the step to level " + std::to_string(next_level);
      return result;
    }
    callbacks.apply_load(next_level);
    if (path.try_step(next_level, lands)) continue;
    if (!path.cut_back(next_level)) return result;
  }
  result.completed = true;
  result.failure = Failure::none;
  result.message.clear();
  result.failed_element = -1;
  return result;
}

}  // namespace softarm::fem

#include "engine/workspace/reach.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "engine/optimiser/optimiser.hpp"
#include "fem/scenes/chamber_stretch.hpp"
#include "studies/workspace.hpp"
#include "fem/core/angles.hpp"

namespace softarm::engine {
namespace {
using fem::kDeg;
constexpr double kAxisLever_mm = 100;  // ℓ: the axis' angle weighed as the travel of a point this far along it

struct Pose {
  bool ok = false;
  Eigen::Vector3d tip = Eigen::Vector3d::Zero(), axis = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> centreline;
  std::array<double, 3> chamber_stretch{1, 1, 1};
};

Pose pose(const fem::SplPressureCells& cells, const std::array<double, 9>& p, const ReachSettings& settings,
          bool with_stretch = false) {
  const fem::SpatialCellRodState s = fem::pose_at_pressures(cells, p, nullptr, settings.payload_kg);
  if (!s.ok) return {};
  Pose out{true, s.position.back(), -s.frame.back().col(2), s.position, {1, 1, 1}};
  if (with_stretch && settings.design)
    out.chamber_stretch = fem::chamber_axis_stretch(*settings.design, cells.rays.front().rod, s);
  return out;
}

double axis_error_rad(const ReachTarget& t, const Eigen::Vector3d& axis) {
  if (!t.axis) return 0;
  return std::acos(std::clamp(axis.dot(t.axis->normalized()), -1.0, 1.0));
}

/// |Δr|² + (ℓθ)², mm².
double misfit(const ReachTarget& t, const Eigen::Vector3d& tip, const Eigen::Vector3d& axis) {
  const double angle = axis_error_rad(t, axis);
  return (tip - t.position_mm).squaredNorm() + kAxisLever_mm * kAxisLever_mm * angle * angle;
}

std::array<double, 9> as_pressures(const std::vector<double>& x) {
  std::array<double, 9> p{};
  std::copy_n(x.begin(), 9, p.begin());
  return p;
}

/// The largest difference of two pressure vectors in any chamber (kPa): how distinct two starts or
/// two solutions are.
double largest_difference(const std::array<double, 9>& a, const std::array<double, 9>& b) {
  double largest = 0;
  for (int k = 0; k < 9; ++k) largest = std::max(largest, std::abs(a[k] - b[k]));
  return largest;
}

/// The sampled poses nearest the target, each a quarter of P or more from the others in some chamber.
std::vector<std::array<double, 9>> start_points(const fem::SplPressureCells& cells, const ReachTarget& target,
                                                const ReachSettings& settings) {
  studies::WorkspaceSettings ws;
  ws.samples = settings.seed_samples;
  ws.payload_kg = settings.payload_kg;
  const studies::WorkspaceResult w = studies::sweep_workspace(cells, ws);
  std::vector<const studies::WorkspacePoint*> ranked;
  for (const auto& p : w.points)
    if (p.ok) ranked.push_back(&p);
  std::sort(ranked.begin(), ranked.end(), [&](auto* a, auto* b) {
    return misfit(target, a->tip_mm, a->tip_axis) < misfit(target, b->tip_mm, b->tip_axis);
  });
  std::vector<std::array<double, 9>> starts;
  for (const auto* p : ranked) {
    const bool distinct = std::all_of(starts.begin(), starts.end(), [&](const auto& s) {
      return largest_difference(s, p->pressure_kPa) >= 0.25 * cells.max_pressure_kPa;
    });
    if (distinct) starts.push_back(p->pressure_kPa);
    if (static_cast<int>(starts.size()) == settings.starts) break;
  }
  return starts;
}

bool reached(const ReachSolution& s, const ReachSettings& settings) {
  return s.distance_mm <= settings.tolerance_mm && s.axis_error_deg <= settings.tolerance_deg;
}

/// The nine pressures as the searches' variables: each chamber up to its segment's reach (the cells'
/// burst where lower than P), so that the whole box has poses and a search meets no cliff of failed
/// evaluations (on the thesis arm that took a target SLSQP missed by 133 mm from 4 starts to 64 mm).
optimise::Problem reach_bounds(const fem::SplPressureCells& cells) {
  optimise::Problem problem;
  const std::array<const char*, 9> names = {"p1", "p2", "p3", "p4", "p5", "p6", "p7", "p8", "p9"};
  for (int k = 0; k < 9; ++k)
    problem.variables.push_back(
        {names[k], optimise::VariableKind::continuous, 0.0, fem::segment_reach_kPa(cells, k / 3), {}, -1, "kPa"});
  return problem;
}

/// The solution at pressures p: its pose, tip, axis, distances and chamber stretches.
ReachSolution solve_at(const fem::SplPressureCells& cells, const ReachTarget& target, const ReachSettings& settings,
                       const std::array<double, 9>& p, int& evaluations) {
  ReachSolution out;
  out.pressure_kPa = p;
  const Pose s = pose(cells, p, settings, true);
  ++evaluations;
  out.chamber_stretch = s.chamber_stretch;
  out.tip_mm = s.tip;
  out.tip_axis = s.axis;
  out.centreline_mm = s.centreline;
  out.distance_mm = s.ok ? (s.tip - target.position_mm).norm() : INFINITY;
  out.axis_error_deg = s.ok ? axis_error_rad(target, s.axis) * kDeg : INFINITY;
  return out;
}

ReachSolution solve_from(const fem::SplPressureCells& cells, const ReachTarget& target, const ReachSettings& settings,
                         const std::array<double, 9>& start, int& evaluations) {
  optimise::Problem problem = reach_bounds(cells);
  problem.evaluate = [&](const std::vector<double>& x) {
    const Pose s = pose(cells, as_pressures(x), settings);
    optimise::Evaluation e;
    e.ok = s.ok;
    if (!s.ok) e.failure_reason = "no equilibrium within the cells' reach";
    else e.objective = misfit(target, s.tip, s.axis);
    return e;
  };
  optimise::Options options;
  options.algorithm = settings.algorithm;
  options.max_evaluations = settings.max_evaluations;
  options.relative_tolerance = 1e-10;
  options.finite_difference_step = 1e-5;
  options.x0.assign(start.begin(), start.end());
  const optimise::Result r = optimise::minimise(problem, options);
  evaluations += r.evaluations;
  return solve_at(cells, target, settings, as_pressures(r.x), evaluations);
}
}  // namespace

ReachResult reach(const fem::SplPressureCells& cells, const ReachTarget& target, const ReachSettings& settings) {
  const auto t0 = std::chrono::steady_clock::now();
  ReachResult out;
  std::vector<ReachSolution> found;
  for (const auto& start : start_points(cells, target, settings)) {
    found.push_back(solve_from(cells, target, settings, start, out.evaluations));
    ++out.starts;
  }
  std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.distance_mm < b.distance_mm; });
  // A near miss and no hit: SLSQP again from where it stopped, its quasi-Newton model of the misfit
  // rebuilt, while that brings the tip closer (a search stops at a kink of the tables' misfit, and a
  // fresh model often steps past it).
  for (int restart = 0; restart < settings.restarts && !found.empty() && !reached(found.front(), settings) &&
                        found.front().distance_mm < settings.restart_within_mm;
       ++restart) {
    const ReachSolution again = solve_from(cells, target, settings, found.front().pressure_kPa, out.evaluations);
    ++out.starts;
    if (!(again.distance_mm < 0.9 * found.front().distance_mm)) break;
    found.insert(found.begin(), again);
  }
  if (!found.empty() && std::isfinite(found.front().distance_mm)) out.nearest = found.front();
  for (const ReachSolution& s : found) {
    if (!reached(s, settings)) continue;
    const bool distinct = std::all_of(out.solutions.begin(), out.solutions.end(), [&](const ReachSolution& o) {
      return largest_difference(o.pressure_kPa, s.pressure_kPa) >= 0.05 * cells.max_pressure_kPa;
    });
    if (distinct) out.solutions.push_back(s);
  }
  out.reachable = !out.solutions.empty();
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

PayloadMargin payload_margin(const fem::SplPressureCells& cells, const ReachTarget& target, const ReachSettings& settings,
                             const ReachResult& found, const PayloadMarginSettings& m) {
  const auto t0 = std::chrono::steady_clock::now();
  PayloadMargin out;
  out.payload_kg = settings.payload_kg.value_or(cells.rays.front().rod.tip_mass_kg);
  if (!found.reachable) return out;
  out.heaviest = found.solutions.front();
  ReachSettings heavier = settings;
  // Continuation from one solution: the extra mass last held and its pressures, the first mass not held.
  const auto continue_from = [&](const ReachSolution& solution) {
    double held = 0, failed = -1, step = m.first_step_kg;
    ReachSolution at = solution;
    while (failed < 0 || failed - held > std::max(m.resolution_kg, m.relative_resolution * held)) {
      const double extra = failed < 0 ? std::min(held + step, m.max_extra_kg) : 0.5 * (held + failed);
      heavier.payload_kg = out.payload_kg + extra;
      const ReachSolution s = solve_from(cells, target, heavier, at.pressure_kPa, out.evaluations);
      ++out.searches;
      if (reached(s, heavier)) {
        held = extra, at = s, step *= 2;
        if (failed < 0 && held >= m.max_extra_kg) break;
      } else {
        failed = extra;
      }
    }
    if (held > out.margin_kg) {
      out.margin_kg = held;
      out.at_least = failed < 0;
      out.heaviest = at;
    }
  };
  const int branches = std::min<int>(m.max_branches, static_cast<int>(found.solutions.size()));
  for (int b = 0; b < branches; ++b) continue_from(found.solutions[b]);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace softarm::engine

#pragma once
// Inverse statics on the arm's pressure cells: the chamber pressures, each within [0, P], that put the
// tip on a target (and, where asked, its axis along a direction). Solved as
//     min over p ∈ [0, P]⁹ of  |r_tip(p) − r*|² + (ℓ·θ(p))²,
// θ the angle between the tip's axis and the target axis (where one is given) and ℓ = 100 mm (the
// angle weighed as the sideways travel of a point 100 mm along the axis), each chamber up to its
// segment's reach (P, or the cells' burst where lower), with NLopt's SLSQP on the rod's
// finite-difference gradients (engine/optimiser), from several starts: the sampled
// poses (studies/workspace.hpp) nearest the target whose pressures differ by a quarter of P or more. A
// target is reached where the tip ends within `tolerance_mm` (and the axis within `tolerance_deg`);
// every start that reaches it with pressures unlike the others' is a distinct solution (the arm has
// nine pressures for three coordinates: a target reached once is usually reached by many). A target
// no start reaches gets the nearest point any start found, said as such: not reached from that many
// starts, which is evidence, not proof, that it is out of reach: the tables are read linearly between
// levels and rays, so the misfit's gradient jumps, and a local search stops short where it does (on the
// thesis arm with a 0.2 kg payload, a wall switch 4 starts missed by 64 mm, 16 by 4.8 mm and 64 reached;
// a projected Levenberg–Marquardt, tried, did no better from 4).
#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "fem/scenes/spl_pressure_cells.hpp"

namespace softarm::engine {

struct ReachTarget {
  std::string name;                   // for the reports ("target" where not named)
  Eigen::Vector3d position_mm = Eigen::Vector3d::Zero();
  std::optional<Eigen::Vector3d> axis;  // the tip face's outward normal wanted (normalised on use)
};

struct ReachSettings {
  std::optional<double> payload_kg;   // at the tip (else the cells' tip mass)
  int starts = 16;
  int seed_samples = 2000;            // sampled poses the starts are chosen from
  double tolerance_mm = 0.5;
  double tolerance_deg = 2;
  int max_evaluations = 600;          // rod solves per start
  std::string algorithm = "nlopt:slsqp";  // engine/optimiser's names
};

struct ReachSolution {
  std::array<double, 9> pressure_kPa{};
  Eigen::Vector3d tip_mm = Eigen::Vector3d::Zero(), tip_axis = Eigen::Vector3d::Zero();
  double distance_mm = 0;
  double axis_error_deg = 0;          // 0 where no axis was asked for
  std::vector<Eigen::Vector3d> centreline_mm;
};

struct ReachResult {
  bool reachable = false;
  std::vector<ReachSolution> solutions;  // reachable: the distinct ones, nearest first
  std::optional<ReachSolution> nearest;  // the best any start found (reached or not)
  int starts = 0;                        // local searches run
  int evaluations = 0;
  double seconds = 0;
};

ReachResult reach(const fem::SplPressureCells& cells, const ReachTarget& target, const ReachSettings& settings);

}  // namespace softarm::engine

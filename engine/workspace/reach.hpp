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
  int restarts = 4;                   // a near miss with no start reaching: searches again from it ...
  double restart_within_mm = 20;      // ... where it is this close, while each gains 10 %
  std::string algorithm = "nlopt:slsqp";  // engine/optimiser's names
  std::optional<fem::SplDesign> design;  // where given, each solution's chamber stretches too
};

struct ReachSolution {
  std::array<double, 9> pressure_kPa{};
  Eigen::Vector3d tip_mm = Eigen::Vector3d::Zero(), tip_axis = Eigen::Vector3d::Zero();
  double distance_mm = 0;
  double axis_error_deg = 0;          // 0 where no axis was asked for
  std::vector<Eigen::Vector3d> centreline_mm;
  std::array<double, 3> chamber_stretch{1, 1, 1};  // per segment (fem/scenes/chamber_stretch.hpp), with a design
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

/// The payload margin at a reached target: the largest extra tip mass Δm with which the arm still puts
/// its tip on the target (within the settings' tolerances), found by continuation in the mass from
/// each distinct solution: the mass raised in steps that double from `first_step_kg` while a local
/// reach search from the last pressures that held reaches the target, then bisected between the last
/// mass held and the first not, to `resolution_kg` or `relative_resolution` of the mass held. Like
/// reachability, a margin found by local searches is evidence, not proof: a heavier mass missed may be
/// held by pressures they did not visit, and the searches need reach's whole budget: on the thesis
/// arm's first 20 sampled poses (`softarm workspace --margin-poses 20`) the median margin was 1.15 kg
/// with 600 rod solves a search, 0.29 kg with 200, at 43 s and 11 s a pose on one core. Tried and set
/// aside: one constrained search, max Δm subject to the tip within the tolerance (SLSQP, with or
/// without a trust region on the mass), which stopped short at most of those poses (medians 0 and
/// 0.25 kg).
struct PayloadMarginSettings {
  double first_step_kg = 0.1;
  double resolution_kg = 0.02;
  double relative_resolution = 0.05;
  double max_extra_kg = 5;   // the bracket's end: a margin this large is said as "at least"
  int max_branches = 2;      // the distinct solutions continued
};
struct PayloadMargin {
  double payload_kg = 0;     // the mass the target was reached with
  double margin_kg = 0;      // Δm held
  bool at_least = false;     // Δm_max held
  ReachSolution heaviest;    // the pressures that hold payload + margin on the target
  int searches = 0;          // local searches run
  int evaluations = 0;       // rod solves
  double seconds = 0;
};
PayloadMargin payload_margin(const fem::SplPressureCells& cells, const ReachTarget& target, const ReachSettings& settings,
                             const ReachResult& reached, const PayloadMarginSettings& margin = {});

}  // namespace softarm::engine

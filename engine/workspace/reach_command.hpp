#pragma once
// `softarm reach <spl scene.json | requirements.json> --target x,y,z [--axis x,y,z] [--payload-kg m]` and
// `softarm reach --tasks <tasks.json>`: the chamber pressures that put the arm's tip on each target
// (reach.hpp), on the arm's pressure cells (read from --cells where a workspace run left them, else
// run and kept there: cells_cache.hpp). Writes reach.json (per target: reachable or not, the distinct
// solutions' pressures, tips, axes, distances and the tube's peak stretch, or the nearest point
// found; for a reached target its payload margin, the extra tip mass the arm still holds there) and
// poses.vtu (each solution's centreline, for ParaView).
#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

namespace softarm::engine {

struct ReachOptions {
  std::string scene, tasks;             // scene: an spl scene config or a requirements file (arm_input.hpp)
  std::string design;                   // with a requirements file: a design run's summary.json (its optimum)
  std::string output = "out/reach";
  std::string cells;                    // default: <output>/cells.json
  std::vector<double> target_mm, axis;  // 3 each where given
  std::optional<double> payload_kg;
  std::optional<double> max_pressure_kPa;  // default: the requirements' working pressure, else the thesis' 344.7
  int divisions = 1;
  int starts = 16;
  double tolerance_mm = 0.5;
  std::string algorithm = "nlopt:slsqp";
  bool payload_margin = true;           // --no-payload-margin: skip the margins (their searches)
};

/// Registers the `reach` subcommand on `app`, its options bound to `options`; returns it.
CLI::App* add_reach_command(CLI::App& app, ReachOptions& options);

/// Runs it: 0 when every target was reached, 1 when one was not (each said in reach.json and on the
/// console). Bad options and files throw fem::InputError before anything is written.
int run_reach(ReachOptions options);

}  // namespace softarm::engine

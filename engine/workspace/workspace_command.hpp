#pragma once
// `softarm workspace <spl scene.json | requirements.json>`: where the arm can put its tip. The arm as
// arm_input.hpp reads it (a scene's design, materials, gravity (its mounting: hanging from the
// shoulder by default) and tip mass; or a requirements file's arm, bound and payload); its cells over each
// segment's pressure space (fem/scenes/spl_pressure_cells.hpp), then the poses at the workspace's
// pressure samples (studies/workspace.hpp). Writes points.csv (pressures, tip, axis, per pose),
// workspace.vtu (the tips as a point cloud with the pressures as fields), centrelines.vtu (the arm at
// rest and at the poses that bound the extent, each with its sample's index), summary.json and report.html
// (the workspace in three projections, coloured by the quantity asked for), and cells.json, the cells
// its next run (or `softarm reach --cells`) reads instead of running them (cells_cache.hpp).
#include <CLI/CLI.hpp>
#include <optional>
#include <string>

namespace softarm::engine {

struct WorkspaceOptions {
  std::string scene;                    // an spl scene config or a requirements file (arm_input.hpp)
  std::string design;                   // with a requirements file: a design run's summary.json (its optimum)
  std::string output = "out/workspace";
  std::optional<double> max_pressure_kPa;  // default: the requirements' working pressure, else the thesis' 344.7
  int samples = 10000;
  int divisions = 1;                    // the direction grid's (pressure_space.hpp)
  std::optional<double> payload_kg;
  double voxel_mm = 10;
  std::string colour_by = "pressure_sum";
  int margin_poses = 0;                 // poses whose payload margin is computed (0: none, or 24 where coloured by it)
};

/// Registers the `workspace` subcommand on `app`, its options bound to `options`; returns it.
CLI::App* add_workspace_command(CLI::App& app, WorkspaceOptions& options);

/// Runs it: 0 with the workspace written; 1 where the arm's cells could not be built (the reason printed
/// and in summary.json). Bad configs throw fem::InputError before anything is written.
int run_workspace(const WorkspaceOptions& options);

}  // namespace softarm::engine

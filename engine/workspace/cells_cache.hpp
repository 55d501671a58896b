#pragma once
// An arm's pressure cells (fem/scenes/spl_pressure_cells.hpp) kept in a JSON file, so that the
// minutes they cost are paid once per design: `softarm workspace` writes them beside its outputs and
// reads them back on its next run, `softarm reach --cells` poses on a workspace's. A file is used only
// where it was written for the same arm: the scene document less what the cells do not depend on
// (its load, output and description), the same pressure bound, grid and cell levels; else the cells
// are run again and the file replaced, and the log says why.
#include <ostream>
#include <string>

#include "fem/scenes/spl_pressure_cells.hpp"
#include "fem/scenes/scene_config.hpp"

namespace softarm::engine {

/// The cells of `config` (read from `scene_file`) over [0, max_pressure_kPa] on the grid of
/// `divisions`, from `cells_file` where it matches, else run (progress on `log`) and written to it.
/// Gravity and the tip mass are the config's either way.
fem::SplPressureCells cached_pressure_cells(const std::string& scene_file, const fem::SceneConfig& config,
                                            double max_pressure_kPa, int divisions, const std::string& cells_file,
                                            std::ostream& log);

}  // namespace softarm::engine

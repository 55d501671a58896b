#pragma once
// An arm's pressure cells (fem/scenes/spl_pressure_cells.hpp) kept in a JSON file, so that the
// minutes they cost are paid once per design: `softarm workspace` writes them beside its outputs and
// reads them back on its next run, `softarm reach --cells` poses on a workspace's. A file is used only
// where it was written for the same arm (arm_input.hpp's key: a scene document less what the cells do
// not depend on, or a requirements file and the design chosen), the same pressure bound, grid and cell
// levels; else the cells are run again and the file replaced, and the log says why.
#include <ostream>
#include <string>

#include "fem/scenes/spl_pressure_cells.hpp"
#include "engine/workspace/arm_input.hpp"

namespace softarm::engine {

/// The cells of `arm` over [0, max_pressure_kPa] on the grid of `divisions`, from `cells_file` where it
/// matches, else run (progress on `log`) and written to it. Gravity and the tip mass are the arm's
/// either way.
fem::SplPressureCells cached_pressure_cells(const ArmInput& arm, double max_pressure_kPa, int divisions,
                                            const std::string& cells_file, std::ostream& log);

}  // namespace softarm::engine

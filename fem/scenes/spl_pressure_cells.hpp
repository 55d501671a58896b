#pragma once
// An arm's cells over each segment's whole pressure space (fem/reduced/pressure_space.hpp), so that
// a pose at any nine chamber pressures within [0, P] costs a rod solve and no 3D cell. The cells of
// one design are run along the rays of the canonical direction grid: ray (a, b) puts every segment's
// chambers at P·(1, a, b) and runs the arm's cells (spl_cells.hpp) from 0 to P. A pose at pressures p
// then reads, for each segment, its canonical form (peak s, direction (a, b), map A), each cell's
// table at s on the rays about (a, b), weighted linearly between them, and maps the section's
// curvature, compliances and end turns by A. Torsion (at rest) and masses are the first ray's: they do
// not depend on the pressures.
//
// Exact on the rays' own directions (the same cells, turned or mirrored); between them it leaves out
// the response's curvature across directions, measured against cells run at directions the grid does
// not hold (tests/test_spl_pressure_cells.cpp: the short SPL's tip 2.8 % of its travel off at the
// midpoints of the one-division grid). A ray whose cells stopped short (a limit point, a stall) leaves
// the pressures beyond its reach with no pose, said as such.
#include <Eigen/Core>
#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "fem/core/parallel.hpp"
#include "fem/reduced/spatial_cell_rod.hpp"
#include "fem/scenes/spl_cell_rod.hpp"
#include "fem/scenes/spl_scene.hpp"

namespace softarm::fem {

struct SplPressureCells {
  double max_pressure_kPa = 0;             // P: every chamber's bound, every ray's peak
  int divisions = 1;                       // the direction grid's n
  std::vector<Eigen::Vector2d> directions; // direction_grid(n)
  std::vector<SplCells> rays;              // per direction: the arm's cells along it
  double seconds = 0;                      // wall time of all the rays' cells
  std::string failure;                     // why there are no cells (a ray's cells could not be built)
};

/// The cells of spec's arm (its design, materials, solver settings, gravity and tip mass) along every
/// ray of the direction grid with `divisions` steps, each from 0 to `max_pressure_kPa` with outputs every
/// 1/cell_levels of it. `adjust` and `progress` as spl_cells' (progress counts over all the rays' tasks).
SplPressureCells spl_pressure_cells(const SplSceneSpec& spec, double max_pressure_kPa, int divisions,
                                    int cell_levels = kDefaultCellLevels,
                                    const std::function<void(TcaSceneSpec&)>& adjust = {},
                                    const TaskProgress& progress = {});

/// Segment n's (0..2) highest peak s that the cells of every ray reached: P where they all completed,
/// else where the first stopped (a limit point: the design's burst on that segment). Every pressure
/// triple of that segment with its peak up to it has a rod.
double segment_reach_kPa(const SplPressureCells& cells, int n);

/// The rod of the arm at the nine chamber pressures p (kPa, chamber 3n+k of segment n): its tables hold
/// the rest state at level 0 and the state at p at level 1, to be solved at level 1. Not `ok` where a
/// pressure lies outside [0, P] or beyond the reach of a ray it reads (`why` says which).
struct PressureRod {
  SpatialCellRodSpec rod;
  bool ok = false;
  bool beyond_cells = false;  // not ok because a segment lies past where its cells reached
  std::string why;
};
PressureRod rod_at_pressures(const SplPressureCells& cells, const std::array<double, 9>& p_kPa);

/// The arm's equilibrium at pressures p under the cells' gravity and tip mass (or `tip_mass_kg` where
/// given): solve_spatial_cell_rod on rod_at_pressures, from `start` where given.
SpatialCellRodState pose_at_pressures(const SplPressureCells& cells, const std::array<double, 9>& p_kPa,
                                      const SpatialCellRodState* start = nullptr,
                                      std::optional<double> tip_mass_kg = {});

}  // namespace softarm::fem

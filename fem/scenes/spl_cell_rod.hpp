#pragma once
// The SPL pose on the spatial cell rod (fem/reduced/spatial_cell_rod.hpp): each 3CA segment's
// ring-pitch cells (tca_cell.hpp) about its first, middle and last rings, under that segment's
// own three chamber pressures ramped from 0 to their peaks; the rod then poses the arm under
// gravity in any direction and the tip mass, at rest and at every output level, in about a
// millisecond per level. Each cell's torsional stiffness comes from the same cell with
// periodic faces at rest (tca_cell.hpp, cell_torsion_stiffness). The cells take the mesh of
// the 3CA ladder's cell-rod rung (Hex20/P1 at 27 points, level 1 cross-section, level 4's
// layers), a half model where a segment's pressures are mirror-symmetric (a lone chamber,
// two equal ones, none), else the full one; they run side by side, one thread each.
// Each segment's ends are end cells through the rung's end rings (tca_end_cell.hpp), where it
// has more than twice as many rings: its top bonded to the connector above, its bottom to the
// one below, the tip's free; their turn and elongation replace the cells' over their length,
// and a bonded end's twist at rest (twist_compliance.hpp: its face held from warping, its cap
// solid) the cells' 1/GJ there (a free end carries no torque worth measuring: the tip's).
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "fem/core/parallel.hpp"
#include "fem/reduced/spatial_cell_rod.hpp"
#include "fem/scenes/solver_work.hpp"
#include "fem/scenes/spl_cell_job.hpp"
#include "fem/scenes/spl_scene.hpp"
#include "fem/scenes/tca_end_cell.hpp"

namespace softarm::fem {

/// Segment n's (0..2) 3CA scene for its cells: its design, the arm's materials, its three
/// pressures (outputs every 1/cell_levels of their ramp), the SPL's solver settings and the
/// 3CA ladder's cell-rod mesh.
TcaSceneSpec spl_segment_cell_scene(const SplSceneSpec& spec, int n, int cell_levels);

/// How segment n's (0..2) `end` is supported in the arm: bonded to its connector (the top; the bottom of
/// segments 1 and 2), or free (the tip).
EndFaceSupport spl_end_support(int n, TcaEnd end);

/// Each segment's cells as the rod's tables: the expensive part, which depends on the design,
/// the materials and each segment's pressures only (not on gravity or the tip mass).
struct SplCells {
  SpatialCellRodSpec rod;                      // with the scene's gravity and tip mass
  std::array<std::vector<int>, 3> rings;       // the cells of each segment
  std::array<bool, 3> half_model{};            // per segment's cells
  std::array<int, 3> end_rings{};              // each segment's end cells' (0: none, rigid caps)
  int cells = 0, largest_cell_dofs = 0;
  int end_cells = 0, largest_end_cell_dofs = 0;
  std::string end_cells_note;                  // the segments without end cells, and why
  double seconds = 0;                          // wall time of all the cells (run side by side)
  SolverWork work;                             // the cells' and end cells' paths' solves, summed
  std::vector<PathOutcome> outcomes;           // per end cell, then per cell, in order
  /// Per segment, over its cells and end cells: the one that stopped at the lowest pressure (its
  /// outcome, completed where every one reached its peak) and that pressure (of its most pressurised
  /// chamber: the peak where completed, the limit point's pressure where one was traced).
  std::array<PathOutcome, 3> segment_outcome{PathOutcome::completed, PathOutcome::completed, PathOutcome::completed};
  std::array<double, 3> segment_reached_kPa{};
  std::string notes;                           // the cells that stopped short, and why
  std::string failure;                         // why there are no cells (a segment without rings)
};
/// The load levels a segment's cells report at unless told otherwise: every 1/16 of the ramp.
inline constexpr int kDefaultCellLevels = 16;

/// `cell_levels`: the load levels at which the cells report (every 1/cell_levels of the ramp);
/// `adjust`, if given, changes each segment's cell scene after spl_segment_cell_scene (a benchmark's
/// other mesh or end rings). Without `with_torsion` the cells' GJ and the bonded ends' twist are not
/// measured and the rod is rigid in torsion: exact for loads in one mirror plane of every segment (a
/// planar pose twists nothing), and about a fifth of the cost saved. `spread`, if given, runs the cells
/// (spl_cell_job.hpp: over MPI ranks, each with the same arguments), else this process' threads do.
SplCells spl_cells(const SplSceneSpec& spec, int cell_levels = kDefaultCellLevels,
                   const std::function<void(TcaSceneSpec&)>& adjust = {}, bool with_torsion = true,
                   const TaskSpread& spread = {}, const TaskProgress& progress = {});

struct SplCellRodResult {
  std::vector<SplState> curve;        // rest (under gravity), then every output level the rod reached
  std::vector<SplJoint> joints;       // at the last level reached, named and ordered as the 3D scene's
  bool converged = false;             // every output level reached
  std::string diagnosis;              // why not
  PathOutcome outcome = PathOutcome::stalled;  // a cell's failure (limit point, material, element) where one stopped it
  double reached_level = 0;
  double mass_kg = 0;                 // the rod's (cells' smeared mass and connectors)
  double rod_seconds = 0;
};
/// The rod of `cells` at rest and at each of `levels` (increasing fractions of the pressures).
SplCellRodResult pose_spl_cell_rod(const SplCells& cells, const std::vector<double>& levels);

/// spl_cells, then the pose at the scene's output levels.
SplCellRodResult run_cell_rod_spl(const SplSceneSpec& spec, int cell_levels = kDefaultCellLevels);

}  // namespace softarm::fem

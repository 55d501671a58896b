#pragma once
// The 3CA on the cell rod (the fidelity ladder's cell-rod rung): its ring-pitch cells and end cells
// (tca_cell.hpp, tca_end_cell.hpp) run along the scene's pressure ramp, the bonded ends' twist at
// rest (twist_compliance.hpp), and the planar or spatial rod through them (fem/reduced).
#include <optional>
#include <string>
#include <vector>

#include "fem/core/parallel.hpp"
#include "fem/scenes/solver_work.hpp"
#include "fem/scenes/tca_cell.hpp"

namespace softarm::fem {

/// Sets spec's mesh and end cells to those of the fidelity ladder's cell-rod rung (fidelity.cpp:
/// Hex20/P1 at 27 points, level 1, level 4's layers; its end rings), where its measured error holds.
void use_cell_rod_rung(TcaSceneSpec& spec);

/// The 3CA scene on the cell rod: cells about the first, middle and last rings (fewer when
/// the design has fewer), the rod evaluated at rest and at every output pressure. Loads in one
/// plane (a mirror plane through the axis) take the planar rod (cell_rod.hpp), any others the
/// spatial one (spatial_cell_rod.hpp) with the cells' torsion; the bending angle is then the tip
/// axis' tilt from rest, signed by the pressures' bend direction. Both rods take both ends as end
/// cells through spec.cell_rod_end_rings rings where the 3CA has more than twice as many; the
/// spatial rod takes the clamped end's twist at rest too (twist_compliance.hpp).
struct CellRodTcaResult {
  std::vector<int> rings;
  int end_rings = 0;                           // the end cells' (0: none, rigid caps)
  std::string end_cells_note;                  // why none where spec.cell_rod_end_rings asked for them
  bool spatial = false;                        // the loads leave one plane: the spatial cell rod
  std::vector<CellRodState> curve;             // rest, then the outputs the rod reached
  std::optional<double> target_pressure_kPa;   // where the bending reaches spec.target_bending_deg
  bool converged = false;                      // every output reached
  std::string diagnosis;                       // why not
  /// A cell's failure where one stopped the rod (limit_point where its pressure passed a maximum, a
  /// wall ballooning in every pitch alike; material_instability; element_inversion), stalled where a
  /// cell's solver stopped, else completed; the rod reached reached_pressure_kPa.
  PathOutcome outcome = PathOutcome::completed;
  double reached_pressure_kPa = 0;
  int cell_dofs = 0;                           // of one cell
  int end_cell_dofs = 0;                       // of one end cell (0: none)
  double cell_seconds = 0, rod_seconds = 0;
  SolverWork work;                             // the cells' and end cells' paths' solves, summed
};
CellRodTcaResult run_cell_rod_tca(const TcaSceneSpec& spec, const TaskProgress& progress = {});

/// Whether spec's loads leave every mirror plane through the axis (the spatial cell rod's case).
bool tca_needs_spatial_rod(const TcaSceneSpec& spec);

/// The 3D pieces of run_cell_rod_tca: the cells about cell_rod_rings and the end cells, each run
/// along spec's pressure ramp, with the cells' torsion and the bonded end's twist at rest where
/// `with_torsion` (the spatial rod's). Gravity has no part in them (a cell carries no weight, and its
/// mirror plane comes from the pressures), so one set poses the 3CA under any gravity.
struct TcaRodCells {
  std::vector<int> rings;
  int end_rings = 0;
  std::string end_cells_note;
  bool with_torsion = false;
  std::vector<TcaCellResult> cells;
  std::vector<TcaEndCellResult> ends;
  std::vector<double> torsion;    // GJ of each cell at rest (with_torsion)
  std::vector<double> end_twist;  // twist compliance of each bonded end at rest (with_torsion; 0: free end)
  double seconds = 0;             // the cells side by side, one thread each
};
/// `progress` is told as each cell ends (parallel_tasks). `ring_cells` (optional): the pieces of an
/// earlier call for the same spec but for its end rings; its ring-pitch cells (and their torsion),
/// which do not depend on the end rings, are taken as they are and only the end cells run. Throws
/// std::logic_error where they were run about other rings or without the torsion asked for.
TcaRodCells run_tca_rod_cells(const TcaSceneSpec& spec, bool with_torsion, const TaskProgress& progress = {},
                              const TcaRodCells* ring_cells = nullptr);
/// The cell rod of spec's loads on cells run for spec's design, mesh and pressures (what
/// run_cell_rod_tca does after running them). Throws std::logic_error for loads out of one plane on
/// cells without torsion.
CellRodTcaResult pose_cell_rod_tca(const TcaSceneSpec& spec, const TcaRodCells& cells);

}  // namespace softarm::fem

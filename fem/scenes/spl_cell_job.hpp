#pragma once
// One job of an arm's cells (spl_cell_rod.hpp): a ring-pitch cell or an end cell of one segment,
// reduced to what the arm's rod and its verdict read of it (its table, how its path ended, its
// size, its torsion at rest). Small and exactly serialisable (every double in its shortest
// round-trip form), so that the jobs of one design can run in other processes and come back bit
// for bit: `mpirun -np N softarm design …` spreads them over the ranks
// (engine/design/cell_cluster.hpp) and gets the serial answer.
#include <functional>
#include <string>
#include <vector>

#include "fem/reduced/spatial_cell_rod.hpp"
#include "fem/scenes/pressure_path.hpp"
#include "fem/scenes/solver_work.hpp"
#include "fem/scenes/tca_end_cell.hpp"
#include "fem/scenes/tca_scene.hpp"

namespace softarm::fem {

struct CellJobResult {
  SpatialCellTable cell;  // a ring-pitch cell's (an end cell's job leaves it empty)
  SpatialEndTable end;    // an end cell's (a cell's job leaves it empty)
  PathOutcome outcome = PathOutcome::completed;
  double reached_pressure_kPa = 0;          // of its most pressurised chamber, where its path stopped
  double estimated_limit_pressure_kPa = 0;  // a traced limit point's pressure (0: none)
  std::string diagnosis;                    // why its path stopped short (empty when completed)
  int dofs = 0;
  bool half_model = false;
  /// A cell: its torsional stiffness GJ at rest, N·mm²; an end cell: its twist compliance at rest,
  /// rad/(N·mm). 0 where not measured; NaN where the tangent at rest is not positive definite.
  double torsion = 0;
  SolverWork work;  // its path's solves (not its torsion's)
};

/// Ring `ring`'s cell of `scene` (tca_cell.hpp) and, `with_torsion`, its GJ at rest.
CellJobResult run_cell_job(const TcaSceneSpec& scene, int ring, bool with_torsion);
/// The `end` cell of `scene` through `rings` rings, supported as `face` (tca_end_cell.hpp) and, for a
/// bonded face `with_torsion`, its twist compliance at rest (twist_compliance.hpp).
CellJobResult run_end_cell_job(const TcaSceneSpec& scene, TcaEnd end, int rings, EndFaceSupport face, bool with_torsion);

/// Exactly and back: cell_job_from_text(to_text(r)) equals r in every bit.
std::string to_text(const CellJobResult& r);
CellJobResult cell_job_from_text(const std::string& text);

/// Somewhere to run n independent tasks (this process's threads, or other processes): returns each
/// task's result in the order of the tasks. Every process that takes part calls it with the same n.
using TaskSpread = std::function<std::vector<std::string>(int n, const std::function<std::string(int i)>& task)>;

}  // namespace softarm::fem

#pragma once
// What the solves of one or more pressure paths cost (the cells of a cell rod, each its own path):
// the counts a benchmark or a summary reports beside the time. Counts are the same on every run of
// a config (factor reuse's CG budget is counted in flops, linear_solver.cpp); seconds are not.
#include <string>

#include "fem/scenes/pressure_path.hpp"

namespace softarm::fem {

struct SolverWork {
  int paths = 0;
  long long dofs = 0;  // summed over the paths
  int newton_iterations = 0;
  int factorizations = 0;          // Cholesky attempts on K (and the LUs' first tries)
  int shifted_factorizations = 0;  // Cholesky attempts on K + σI after K itself failed
  int lu_fallbacks = 0;            // LUs of an indefinite tangent (volume control)
  int cg_iterations = 0;           // on earlier factors
  double seconds = 0;              // each path's own seconds, summed: the work, not the wall time
  double longest_seconds = 0;      // the slowest path's own: a path runs on one thread, so with the
                                   // paths side by side on T threads no run ends before
                                   // max(longest_seconds, seconds / T)

  /// One path of `dofs` unknowns that took `path_seconds`.
  void add(const PressurePathResult& path, int path_dofs, double path_seconds);
  void add(const SolverWork& other);
};

/// The counts in words, for a console line or a report: "236 Newton iterations, 105 factorisations
/// (+18 shifted), 0 LUs, 2052 CG iterations" (as JSON: solver_work_json.hpp).
std::string solver_work_text(const SolverWork& work);

}  // namespace softarm::fem

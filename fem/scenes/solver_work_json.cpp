#include "fem/scenes/solver_work_json.hpp"

namespace softarm::fem {

nlohmann::json solver_work_to_json(const SolverWork& w) {
  return {{"cell_paths", w.paths},
          {"cell_dofs_summed", w.dofs},
          {"newton_iterations", w.newton_iterations},
          {"factorizations", w.factorizations},
          {"indefinite_tangents_lu", w.lu_fallbacks},
          {"shifted_cholesky_attempts", w.shifted_factorizations},
          {"cg_iterations", w.cg_iterations},
          {"cell_seconds_summed", w.seconds},
          {"longest_cell_seconds", w.longest_seconds}};
}

SolverWork solver_work_from_json(const nlohmann::json& j) {
  SolverWork w;
  w.paths = j.at("cell_paths").get<int>();
  w.dofs = j.at("cell_dofs_summed").get<long long>();
  w.newton_iterations = j.at("newton_iterations").get<int>();
  w.factorizations = j.at("factorizations").get<int>();
  w.lu_fallbacks = j.at("indefinite_tangents_lu").get<int>();
  w.shifted_factorizations = j.at("shifted_cholesky_attempts").get<int>();
  w.cg_iterations = j.at("cg_iterations").get<int>();
  w.seconds = j.at("cell_seconds_summed").get<double>();
  // A design checkpoint written before the slowest cell's time was kept has none: it stays zero.
  if (j.contains("longest_cell_seconds")) w.longest_seconds = j.at("longest_cell_seconds").get<double>();
  return w;
}

}  // namespace softarm::fem

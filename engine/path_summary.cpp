#include "engine/path_summary.hpp"

namespace softarm::engine {

nlohmann::json path_solver_json(const fem::PressurePathResult& path) {
  return {{"load_steps", path.path.stats.steps},
          {"newton_iterations", path.path.stats.newton_iterations},
          {"cutbacks", path.path.stats.cutbacks},
          {"resumed_states", path.resumed_states},
          {"factorizations", path.factorizations},
          {"indefinite_tangents_lu", path.lu_fallbacks},
          {"shifted_cholesky_attempts", path.shifted_factorizations},
          {"steps_solved_on_earlier_factor", path.reused_solves},
          {"cg_iterations", path.cg_iterations},
          {"analyse_s", path.analyse_s},
          {"factorize_s", path.factorize_s},
          {"solve_s", path.solve_s},
          {"factor_gflop", 1e-9 * path.factor_flops},
          {"factor_nonzeros_million", 1e-6 * path.factor_nonzeros}};
}

void add_failure_json(nlohmann::json& summary, const fem::PressurePathResult& path) {
  switch (path.outcome) {
    case fem::PathOutcome::limit_point:
      summary["estimated_limit_pressure_kPa"] = path.estimated_limit_pressure_kPa;
      summary["limit_point_found_by"] = fem::to_string(path.limit_kind);
      break;
    case fem::PathOutcome::material_instability:
      summary["material_instability"] = {{"unstable_gauss_points", path.material.unstable_points},
                                         {"element", path.material.element},
                                         {"largest_isochoric_stretch", path.material.max_stretch},
                                         {"smallest_isochoric_stretch", path.material.min_stretch}};
      break;
    case fem::PathOutcome::element_inversion: summary["inverted_element"] = path.inverted_element; break;
    default: break;
  }
}

}  // namespace softarm::engine

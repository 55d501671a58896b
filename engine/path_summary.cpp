#include "engine/path_summary.hpp"

namespace softarm::engine {

nlohmann::json path_solver_json(const fem::PressurePathResult& path) {
  return {{"load_steps", path.path.stats.steps},
          {"newton_iterations", path.path.stats.newton_iterations},
          {"cutbacks", path.path.stats.cutbacks},
          {"factorizations", path.factorizations},
          {"indefinite_tangents", path.lu_fallbacks},
          {"steps_solved_on_earlier_factor", path.reused_solves},
          {"cg_iterations", path.cg_iterations}};
}

}  // namespace softarm::engine

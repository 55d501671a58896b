#pragma once
// The "solver" block of every FEM scene's summary.json: what the pressure path cost
// (load steps, Newton iterations, cut-backs, factorisations, Newton steps solved by CG
// on an earlier factor), and what one factorisation costs (CHOLMOD's predicted flops and
// nonzeros of L).
#include <nlohmann/json.hpp>

#include "fem/scenes/pressure_path.hpp"

namespace softarm::engine {

nlohmann::json path_solver_json(const fem::PressurePathResult& path);

}  // namespace softarm::engine

#pragma once
// The "solver" block of every FEM scene's summary.json (a cell rod's: fem/scenes/solver_work_json.hpp),
// and what a failure found: what the pressure path cost (load steps, Newton iterations, cut-backs,
// factorisations, Newton steps solved by CG on an earlier factor), and what one factorisation costs
// (CHOLMOD's predicted flops and nonzeros of L).
#include <nlohmann/json.hpp>

#include "fem/scenes/pressure_path.hpp"

namespace softarm::engine {

nlohmann::json path_solver_json(const fem::PressurePathResult& path);

/// What a path that ended in a failure found, added to a summary beside its "outcome": a limit
/// point's pressure and how it was found; where the law lost Drucker stability and at which stretch;
/// which element turned inside out.
void add_failure_json(nlohmann::json& summary, const fem::PressurePathResult& path);

}  // namespace softarm::engine

#pragma once
// The "solver" block of every FEM scene's summary.json, and what a failure found: what the pressure path cost
// (load steps, Newton iterations, cut-backs, factorisations, Newton steps solved by CG
// on an earlier factor), and what one factorisation costs (CHOLMOD's predicted flops and
// nonzeros of L).
#include <nlohmann/json.hpp>
#include <string>

#include "fem/scenes/pressure_path.hpp"
#include "fem/scenes/solver_work_json.hpp"

namespace softarm::engine {

nlohmann::json path_solver_json(const fem::PressurePathResult& path);

/// A cell rod's cells' paths' solves, summed (fem/scenes/solver_work.hpp; as JSON:
/// fem/scenes/solver_work_json.hpp), in words, for a console line or a report: "236 Newton
/// iterations, 105 factorisations (+18 shifted), 0 LUs, 2052 CG iterations".
std::string cells_solver_text(const fem::SolverWork& work);

/// What a path that ended in a failure found, added to a summary beside its "outcome": a limit
/// point's pressure and how it was found; where the law lost Drucker stability and at which stretch;
/// which element turned inside out.
void add_failure_json(nlohmann::json& summary, const fem::PressurePathResult& path);

}  // namespace softarm::engine

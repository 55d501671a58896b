#pragma once
// A SolverWork as JSON: the "solver" block of a cell rod's summary.json (`softarm simulate` on the
// reduced scenes, the design's `verification.cell_solver`), and the same for results that travel as
// text (a cell job between MPI ranks) or are kept to resume from (the design's checkpoint).
#include <nlohmann/json.hpp>

#include "fem/scenes/solver_work.hpp"

namespace softarm::fem {

nlohmann::json solver_work_to_json(const SolverWork& work);
/// Throws nlohmann::json's exceptions where a field is missing or of another type.
SolverWork solver_work_from_json(const nlohmann::json& j);

}  // namespace softarm::fem

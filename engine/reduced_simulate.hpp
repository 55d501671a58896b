#pragma once
// `softarm simulate` on the reduced (rod) model, when a scene's fidelity
// request picks it (fem/scenes/fidelity.hpp): prints the curve, writes
// curve.csv and summary.json (with the model and its measured error).
#include "fem/scenes/scene_config.hpp"

namespace softarm::engine {

/// Returns the exit code (1 when the rod's path stopped short, as for the FEM).
int simulate_reduced(const fem::SceneConfig& config);

}  // namespace softarm::engine

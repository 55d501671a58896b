#pragma once
// Where `softarm simulate` keeps a 3D scene's converged states as it goes
// (fem/scenes/path_log.hpp): path_checkpoint.bin in the output directory, named
// by the scene it belongs to, so that a rerun of a killed 3D run resumes from
// its last converged step and a changed scene starts over.
#include <nlohmann/json.hpp>
#include <string>

#include "fem/scenes/pressure_path.hpp"

namespace softarm::engine {

/// The checkpoint of a scene `document` (the config file's JSON) run with the command
/// line's `overrides` (mesh level, element order, fidelity: anything that changes the model)
/// in `directory`. Its fingerprint is a hash of the document without "output" and
/// "description" and of the overrides; `fresh` removes an earlier run's file. Throws
/// fem::InputError("output.directory", …) where the file cannot be removed or written.
fem::PathCheckpoint scene_checkpoint(nlohmann::json document, const std::string& overrides, const std::string& directory,
                                     bool fresh);

/// "resumed 12 converged states from out/x/path_checkpoint.bin" or why an existing log was
/// not resumed; "" for a run from rest without an earlier file.
std::string checkpoint_note(const fem::PathCheckpoint& checkpoint, const fem::PressurePathResult& path);

}  // namespace softarm::engine

#pragma once
// Lives in fem/ (it depends only on fem) so that the CLI and the parameter
// studies (studies/) read scenes the same way.
// Scene configuration: JSON → validated, defaulted specs. Every key carries
// its unit, unknown keys are rejected with the field named, and the same
// declarations print as documentation (`softarm schema`).
#include <nlohmann/json.hpp>
#include <string>

#include <optional>

#include "fem/scenes/fidelity.hpp"
#include "fem/scenes/rra_scene.hpp"
#include "fem/scenes/spl_scene.hpp"
#include "fem/scenes/tca_scene.hpp"

namespace softarm::fem {

struct OutputSpec {
  std::string directory = "out";
  bool vtu = true;
};

struct SceneConfig {
  std::string scene;   // "rra", "tca" or "spl"
  RraSceneSpec rra;    // scene "rra"
  TcaSceneSpec tca;    // scene "tca"
  SplSceneSpec spl;    // scene "spl"
  OutputSpec output;
  bool verbose = false;
  /// model.fidelity / model.target_error_percent: the level the fidelity ladder chose, and why.
  std::optional<ModelSelection> selection;
  bool reduced = false;  // the chosen level is the reduced (rod) model
  bool cell_rod = false;  // ... the cell rod (with `reduced`; its cells take the mesh settings)
  int& mesh_level() { return scene == "tca" ? tca.mesh_level : scene == "spl" ? spl.mesh_level : rra.mesh_level; }
  int& element_order() { return scene == "tca" ? tca.element_order : scene == "spl" ? spl.element_order : rra.element_order; }
  /// The level whose element layers the 3D mesh gets (mesh.axial_level, else mesh.level); the RRA's mesh.level.
  int layers_level() const;
};

/// Reads a scene file (the whole document); throws InputError naming the field.
SceneConfig read_scene_config(const nlohmann::json& document);
SceneConfig load_scene_config(const std::string& file_name);
/// Lets the fidelity ladder pick the model (mesh level, element, or the rod) for a target
/// error; `asked` says who asked ("fidelity 'fast'", "--fidelity fast"), for the reason printed.
void apply_fidelity(SceneConfig& config, double target_error_percent, const std::string& asked);

}  // namespace softarm::engine

#pragma once
// The arm `softarm workspace` and `softarm reach` pose, from either of two files:
//   - an spl scene config: its design, materials, gravity (the mounting) and tip mass; the chambers'
//     bound the thesis' working pressure unless told;
//   - a design's requirements file (configs/thesis_requirements.json): the arm at its baseline
//     geometry and materials, or at the optimum a `softarm design` run wrote (`--design
//     <its summary.json>`), hanging from the shoulder under gravity as the design judges it
//     (objectives/cell_rod_evaluation.hpp, arm_cell_scene), bounded by the requirements' working
//     pressure and carrying their payload at the tip unless told otherwise.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "fem/scenes/spl_scene.hpp"

namespace softarm::engine {

struct ArmInput {
  fem::SplSceneSpec spl;
  nlohmann::json cells_key;                 // what the arm's cells depend on (cells_cache.hpp)
  std::optional<double> max_pressure_kPa;   // the file's own bound (a requirements file's working pressure)
  std::optional<double> payload_kg;         // the file's own payload (a requirements file's)
  std::string described;                    // the arm in words, for the reports
};

/// Reads `file` as either kind (a document with a "requirements" key is a requirements file);
/// `design_summary`, where not empty, names a design run's summary.json whose optimum replaces a
/// requirements file's baseline. Throws fem::InputError naming the field for a bad file, or for a
/// summary given with a scene or whose optimum does not match the requirements' variables.
ArmInput read_arm_input(const std::string& file, const std::string& design_summary = "");

}  // namespace softarm::engine

#include "engine/workspace/arm_input.hpp"

#include <algorithm>

#include "engine/design/design_config.hpp"
#include "engine/design/design_problem.hpp"
#include "fem/core/input_error.hpp"
#include "fem/core/json_reader.hpp"
#include "fem/scenes/scene_config.hpp"
#include "objectives/cell_rod_evaluation.hpp"

namespace softarm::engine {
namespace {
using nlohmann::json;

/// The variables' values of the optimum in a design run's summary.json (design_report.cpp's
/// "optimum": each variable by name, a material by its name).
std::vector<double> optimum_values(const DesignConfig& config, const std::string& summary_file) {
  const json summary = fem::load_json_file(summary_file);
  if (!summary.contains("optimum") || !summary.at("optimum").is_object())
    throw fem::InputError("--design", "'" + summary_file + "' holds no \"optimum\"; valid: a softarm design run's summary.json");
  const json& optimum = summary.at("optimum");
  std::vector<double> x = baseline_values(config);
  for (std::size_t i = 0; i < config.variables.size(); ++i) {
    const optimise::Variable& v = config.variables[i].variable;
    const std::string field = "--design: optimum." + v.name;
    if (!optimum.contains(v.name))
      throw fem::InputError(field, "missing; valid: the summary of a design run on these requirements");
    const json& value = optimum.at(v.name);
    if (v.kind == optimise::VariableKind::categorical) {
      const auto at = value.is_string() ? std::find(v.choices.begin(), v.choices.end(), value.get<std::string>())
                                        : v.choices.end();
      if (at == v.choices.end()) throw fem::InputError(field, value.dump() + "; valid: one of the requirements' choices");
      x[i] = static_cast<double>(at - v.choices.begin());
    } else {
      if (!value.is_number() || !(value.get<double>() >= v.lower && value.get<double>() <= v.upper))
        throw fem::InputError(field, value.dump() + "; valid: within the requirements' bounds [" +
                                         std::to_string(v.lower) + ", " + std::to_string(v.upper) + "]");
      x[i] = value.get<double>();
    }
  }
  return x;
}

ArmInput from_requirements(const std::string& file, const json& document, const std::string& design_summary) {
  const DesignConfig config = read_design_config(document);
  const std::vector<double> x = design_summary.empty() ? baseline_values(config) : optimum_values(config, design_summary);
  ArmInput out;
  out.spl = objectives::arm_cell_scene(make_candidate(config, x), config.check);
  out.max_pressure_kPa = config.requirements.max_pressure_kPa;
  out.payload_kg = config.requirements.min_payload_kg;
  out.described = "the arm of " + file + (design_summary.empty() ? " at its baseline" : " at the optimum of " + design_summary);
  json arm = document;
  for (const char* key : {"output", "optimiser", "objective", "design_space", "description"}) arm.erase(key);
  out.cells_key = {{"requirements", arm}, {"design", x}};
  return out;
}
}  // namespace

ArmInput read_arm_input(const std::string& file, const std::string& design_summary) {
  const json document = fem::load_json_file(file);  // the readers keep a reference to it
  if (document.is_object() && document.contains("requirements")) return from_requirements(file, document, design_summary);
  if (!design_summary.empty())
    throw fem::InputError("--design", "given with a scene config; valid: only with a requirements file");
  const fem::SceneConfig config = fem::read_scene_config(document);
  if (config.scene != "spl")
    throw fem::InputError("scene", "'" + config.scene + "': an arm's is needed; valid: an spl scene config or a requirements file");
  ArmInput out;
  out.spl = config.spl;
  out.described = file;
  json scene = document;
  for (const char* key : {"load", "output", "description"}) scene.erase(key);  // the cells depend on neither
  out.cells_key = {{"scene", scene}};
  return out;
}

}  // namespace softarm::engine

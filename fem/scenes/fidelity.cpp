#include "fem/scenes/fidelity.hpp"

#include <nlohmann/json.hpp>

#include <sstream>
#include <stdexcept>

namespace softarm::fem {

const char* fidelity_ladder_json();  // configs/measured/fidelity_ladder.json, compiled in (fidelity_ladder_data.cpp.in)

namespace {

std::string percent(double x) {
  std::ostringstream s;
  s.precision(3);
  s << x << " %";
  return s.str();
}

/// One rung from configs/measured/fidelity_ladder.json: its model ("reduced_rod", "cell_rod" or "fem"), mesh and
/// measured error and cost.
ModelLevel read_level(const nlohmann::json& j) {
  ModelLevel m;
  m.name = j.at("name").get<std::string>();
  const std::string model = j.at("model").get<std::string>();
  if (model != "reduced_rod" && model != "cell_rod" && model != "fem")
    throw std::logic_error("configs/measured/fidelity_ladder.json: level '" + m.name + "': unknown model " + model);
  m.reduced = model != "fem";
  m.cell_rod = model == "cell_rod";
  m.mesh_level = j.at("mesh_level").get<int>();
  m.element_order = j.at("element_order").get<int>();
  m.axial_level = j.at("axial_level").get<int>();
  m.serendipity = j.at("serendipity").get<bool>();
  m.reduced_integration = j.at("reduced_integration").get<bool>();
  m.end_rings = j.at("end_rings").get<int>();
  m.error_percent = j.at("error_percent").get<double>();
  m.error_measure = j.at("error_measure").get<std::string>();
  m.seconds = j.at("seconds").get<double>();
  m.dofs = j.at("dofs").get<int>();
  return m;
}

FidelityLadder read_ladder(const std::string& scene) {
  static const nlohmann::json document = nlohmann::json::parse(fidelity_ladder_json());
  const nlohmann::json& j = document.at(scene);
  FidelityLadder ladder{scene, j.at("reference").get<std::string>(), {}};
  for (const nlohmann::json& level : j.at("levels")) ladder.levels.push_back(read_level(level));
  return ladder;
}

}  // namespace

const FidelityLadder& fidelity_ladder(const std::string& scene) {
  static const FidelityLadder rra = read_ladder("rra"), tca = read_ladder("tca"), spl = read_ladder("spl");
  if (scene == "rra") return rra;
  if (scene == "tca") return tca;
  if (scene == "spl") return spl;
  throw std::invalid_argument("fidelity_ladder: unknown scene " + scene);
}

double fidelity_target_percent(const std::string& fidelity) {
  if (fidelity == "fast") return kCheapestModel;
  if (fidelity == "balanced") return 2;
  if (fidelity == "accurate") return 0.5;
  throw std::invalid_argument("fidelity_target_percent: unknown fidelity " + fidelity);
}

ModelSelection select_model(const std::string& scene, double target_percent) {
  const FidelityLadder& ladder = fidelity_ladder(scene);
  if (target_percent == kCheapestModel) {
    const ModelLevel& cheapest = ladder.levels.front();
    return {cheapest, "the cheapest model, whatever its error: measured error " + percent(cheapest.error_percent) +
                          " (" + cheapest.error_measure + ") against " + ladder.reference};
  }
  for (const ModelLevel& m : ladder.levels)
    if (m.error_percent <= target_percent)
      return {m, "the cheapest model within " + percent(target_percent) + ": measured error " +
                     percent(m.error_percent) + " (" + m.error_measure + ") against " + ladder.reference};
  const ModelLevel& best = ladder.levels.back();
  return {best, "no model is measured within " + percent(target_percent) + "; the most accurate one has " +
                    percent(best.error_percent) + " against " + ladder.reference};
}

}  // namespace softarm::fem

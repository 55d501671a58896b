// Setting one scene parameter by name (see scene_parameter.hpp).
#include "studies/scene_parameter.hpp"

#include <array>
#include <iomanip>
#include <sstream>

#include "fem/core/input_error.hpp"

namespace softarm::studies {
using nlohmann::json;

namespace {

// Physical/normalised twins of the RRA geometry (fem/mesh/rra_design.hpp): a scene holds one of each.
constexpr std::array<std::array<const char*, 2>, 4> kTwins{{{"wall_thickness_mm", "wall_thickness_normalised"},
                                                            {"end_cap_thickness_mm", "end_cap_thickness_normalised"},
                                                            {"ring_count", "ring_count_normalised"},
                                                            {"ring_diameter_mm", "ring_thickness_normalised"}}};

void erase_twin(json& object, const std::string& key) {
  for (const auto& pair : kTwins)
    for (int i = 0; i < 2; ++i)
      if (key == pair[i]) object.erase(pair[1 - i]);
}

// Thesis eqs 5–7 for the distal segment (n = 3): its top radius given t_r and (r_b)_3.
void set_taper_ratio(json& scene, double taper_ratio, const std::string& field) {
  if (!(taper_ratio > 0 && taper_ratio <= 1))
    throw fem::InputError(field, "taper ratio " + value_text(taper_ratio) + " is outside (0, 1]");
  json& geometry = scene["geometry"];
  const double rb3 = geometry.value("bottom_radius_mm", 9.0);
  const double rt1 = rb3 / taper_ratio;
  geometry["bottom_radius_mm"] = rb3;
  geometry["top_radius_mm"] = rb3 + (rt1 - rb3) / 3;
}

}  // namespace

std::string value_text(const json& value) {
  if (value.is_string()) return value.get<std::string>();
  if (value.is_number_integer()) return std::to_string(value.get<long long>());
  if (value.is_number()) {
    std::ostringstream s;
    s << std::setprecision(4) << value.get<double>();
    return s.str();
  }
  return value.dump();
}

json with_parameter(json scene, const std::string& parameter, const json& value, const std::string& field) {
  if (parameter == "taper_ratio") {
    if (!value.is_number()) throw fem::InputError(field, "taper_ratio takes numbers, got " + value.dump());
    set_taper_ratio(scene, value.get<double>(), field);
    return scene;
  }
  const auto dot = parameter.find('.');
  if (dot == std::string::npos || dot == 0 || dot + 1 == parameter.size())
    throw fem::InputError(field, "'" + parameter + "' is neither a derived parameter (taper_ratio) nor a path "
                                 "'<section>.<key>' into the scene (e.g. geometry.wall_thickness_normalised)");
  const std::string section = parameter.substr(0, dot), key = parameter.substr(dot + 1);
  static const std::array<const char*, 6> kSections{"geometry", "materials", "load", "mesh", "solver", "model"};
  bool known = false;
  for (const char* s : kSections) known = known || section == s;
  if (!known)
    throw fem::InputError(field, "section '" + section + "' of '" + parameter +
                                     "' is not one of geometry, materials, load, mesh, solver, model");
  json& object = scene[section];
  if (!object.is_object()) object = json::object();
  erase_twin(object, key);
  object[key] = value;
  return scene;
}

}  // namespace softarm::studies

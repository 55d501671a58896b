#include "studies/study_points.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "fem/core/input_error.hpp"
#include "fem/scenes/scene_config.hpp"

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

std::vector<StudyPoint> study_points(const StudySpec& spec) {
  std::size_t total = 1;
  for (const auto& axis : spec.axes) total *= axis.values.size();
  std::vector<StudyPoint> points;
  points.reserve(total);
  for (std::size_t n = 0; n < total; ++n) {
    StudyPoint p;
    p.index = static_cast<int>(n);
    p.scene = spec.scene;
    json key = json::array();
    std::size_t rest = n;
    for (std::size_t a = 0; a < spec.axes.size(); ++a) {
      const SweepAxis& axis = spec.axes[a];
      const json& v = axis.values[rest % axis.values.size()];
      rest /= axis.values.size();
      p.values.push_back(v);
      key.push_back(v);
      p.scene = with_parameter(std::move(p.scene), axis.parameter, v, "sweep[" + std::to_string(a) + "].parameter");
    }
    p.key = key.dump();
    points.push_back(std::move(p));
  }
  return points;
}

int curve_index(const StudySpec& spec, const StudyPoint& point) {
  int index = 0, stride = 1;
  for (std::size_t a = 1; a < spec.axes.size(); ++a) {
    const auto& values = spec.axes[a].values;
    int position = 0;
    for (std::size_t i = 0; i < values.size(); ++i)
      if (values[i] == point.values[a]) position = static_cast<int>(i);
    index += position * stride;
    stride *= static_cast<int>(values.size());
  }
  return index;
}

std::string curve_label(const StudySpec& spec, const StudyPoint& point) {
  std::string label;
  for (std::size_t a = 1; a < spec.axes.size(); ++a)
    label += (label.empty() ? "" : ", ") + spec.axes[a].label + " = " + value_text(point.values[a]);
  return label;
}

void check_points(const StudySpec& spec, const std::vector<StudyPoint>& points) {
  for (const StudyPoint& point : points) {
    try {
      fem::read_scene_config(point.scene);
    } catch (const fem::InputError& e) {
      // Name the axis whose parameter the scene refused (else the first axis' value of this point).
      std::size_t axis = 0;
      for (std::size_t a = 0; a < spec.axes.size(); ++a)
        if (e.field() == spec.axes[a].parameter || e.field().find(spec.axes[a].parameter) == 0) axis = a;
      const auto& values = spec.axes.at(axis).values;
      const auto j = std::find(values.begin(), values.end(), point.values.at(axis)) - values.begin();
      throw fem::InputError("sweep[" + std::to_string(axis) + "].values[" + std::to_string(j) + "]",
                            "value " + point.values.at(axis).dump() + " makes a scene softarm refuses: " + e.what());
    }
  }
}

}  // namespace softarm::studies

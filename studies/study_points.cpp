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

#include "studies/study_spec.hpp"

#include <algorithm>
#include <filesystem>
#include <functional>

#include "fem/core/input_error.hpp"
#include "fem/core/json_reader.hpp"
#include "fem/scenes/scene_config.hpp"
#include "studies/results_store.hpp"
#include "studies/scene_parameter.hpp"

namespace softarm::studies {
using fem::InputError;
using fem::JsonReader;
using fem::Range;
using nlohmann::json;

std::vector<std::string> scalar_outputs(const std::string& scene, const std::string& model) {
  if (scene == "rra")
    return {"extension_mm", "mass_g", "reached_pressure_kPa", "tube_max_stretch", "tube_max_principal_stress_MPa",
            "tube_max_log_strain", "tube_averaged_stretch", "tube_averaged_stress_MPa", "burst_utilisation",
            "limit_pressure_kPa"};
  std::vector<std::string> out{"bending_deg", "normalised_bending", "pressure_for_target_kPa", "mass_g",
                               "reached_pressure_kPa", "tip_x_mm", "tip_z_mm", "burst_utilisation"};
  if (model == "rod") out.insert(out.end(), {"tube_max_stretch", "sheath_max_stretch"});
  return out;
}

namespace {

std::string list_words(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

void require_output(const JsonReader& r, const std::string& key, const std::string& name,
                    const std::vector<std::string>& outputs) {
  if (std::find(outputs.begin(), outputs.end(), name) == outputs.end())
    throw InputError(r.field(key), "'" + name + "' is not an output of this scene and model (outputs: " +
                                       list_words(outputs) + ")");
}

std::vector<json> read_values(JsonReader& axis) {
  const json& list = axis.raw("values", "list", "the swept values, all numbers or all names (or give 'range')");
  const bool has_values = axis.has("values"), has_range = axis.has("range");
  if (has_values == has_range)
    throw InputError(axis.field("values"), "give exactly one of 'values' (a list) or 'range' ({from, to, count})");
  std::vector<json> values;
  if (has_values) {
    if (!list.is_array() || list.empty())
      throw InputError(axis.field("values"), "needs a non-empty list of numbers or names, got " + list.dump());
    for (std::size_t i = 0; i < list.size(); ++i) {
      const json& v = list[i];
      if (!(v.is_number() || v.is_string()) || v.is_number() != list.front().is_number())
        throw InputError(axis.field("values") + "[" + std::to_string(i) + "]",
                         "value " + v.dump() + ": all values must be numbers, or all names");
      if (std::find(values.begin(), values.end(), v) != values.end())
        throw InputError(axis.field("values") + "[" + std::to_string(i) + "]", "value " + v.dump() + " is repeated");
      values.push_back(v);
    }
    return values;
  }
  auto range = axis.object("range", "evenly spaced values: from, to (inclusive) and count");
  const double from = range.number("from", Range{}, "first value");
  const double to = range.number("to", Range{}, "last value");
  const int count = range.integer("count", 5, Range::closed(2, 1000), "number of values");
  range.finish();
  if (!(to != from)) throw InputError(range.field("to"), "value " + std::to_string(to) + " must differ from 'from'");
  for (int i = 0; i < count; ++i) values.emplace_back(from + (to - from) * i / (count - 1));
  return values;
}

std::vector<SweepAxis> read_sweep(JsonReader& root) {
  const std::string field = root.field("sweep");
  const json& list = root.raw("sweep", "list", "1 to 3 swept parameters: {parameter, values | range, label}",
                               "(required)");
  if (!root.has("sweep")) throw InputError(field, "required list of swept parameters is missing");
  if (!list.is_array() || list.empty() || list.size() > 3)
    throw InputError(field, "needs a list of 1 to 3 parameters ({parameter, values | range, label}), got " +
                                std::to_string(list.is_array() ? list.size() : 0));
  std::vector<SweepAxis> axes;
  for (std::size_t i = 0; i < list.size(); ++i) {
    JsonReader axis(list[i], field + "[" + std::to_string(i) + "]");
    SweepAxis a;
    a.parameter = axis.string("parameter", "a scene path (geometry.wall_thickness_normalised, materials.tube, …) or "
                                           "a derived parameter (taper_ratio)");
    a.values = read_values(axis);
    a.label = axis.string("label", a.parameter, "axis label for plots and the rule's words");
    axis.finish();
    for (const auto& b : axes)
      if (b.parameter == a.parameter) throw InputError(axis.field("parameter"), "'" + a.parameter + "' is swept twice");
    axes.push_back(std::move(a));
  }
  return axes;
}

DesignRuleSpec read_rule(JsonReader rule, const std::vector<std::string>& outputs) {
  DesignRuleSpec r;
  r.goal = rule.choice("goal", "max", {"max", "min"}, "whether the best point has the largest or smallest output");
  r.output = rule.string("output", "the performance output the rule ranks by (e.g. extension_mm)");
  require_output(rule, "output", r.output, outputs);
  r.keep_percent = rule.number("keep_percent", 100, Range::closed(50, 100),
                               "points within this percentage of the best output are kept (100: the best only)");
  r.then_minimise = rule.string("then_minimise", "", "among the kept points, take the one with the smallest value "
                                                     "of this output (e.g. mass_g); empty: the best point");
  if (!r.then_minimise.empty()) require_output(rule, "then_minimise", r.then_minimise, outputs);
  const json& list = rule.raw("limits", "list", "eligibility limits on outputs: {output, min | max}");
  if (rule.has("limits")) {
    if (!list.is_array()) throw InputError(rule.field("limits"), "needs a list of {output, min | max}");
    for (std::size_t i = 0; i < list.size(); ++i) {
      JsonReader limit(list[i], rule.field("limits") + "[" + std::to_string(i) + "]");
      OutputLimit l;
      l.output = limit.string("output", "the limited output");
      require_output(limit, "output", l.output, outputs);
      l.min = limit.optional_number("min", Range{}, "points below this are not eligible");
      l.max = limit.optional_number("max", Range{}, "points above this are not eligible");
      if (!l.min && !l.max) throw InputError(limit.field("max"), "give 'min' or 'max' (or both)");
      limit.finish();
      r.limits.push_back(l);
    }
  }
  rule.finish();
  return r;
}

ThesisFinding read_thesis(JsonReader thesis, const std::string& rule_output, const std::vector<std::string>& outputs) {
  ThesisFinding t;
  t.trend_of = thesis.string("trend_of", rule_output, "the output whose trend or order the thesis states");
  require_output(thesis, "trend_of", t.trend_of, outputs);
  t.choice = thesis.raw("choice", "number or name", "the first-axis value the thesis chose");
  t.figure = thesis.string("figure", "", "where the thesis shows it (figure, table)");
  t.finding = thesis.string("finding", "", "what the thesis found, in its words");
  t.trend = thesis.choice("trend", "", {"", "increasing", "decreasing", "peak"},
                          "the trend of trend_of along the first axis in the thesis");
  t.peak_at = thesis.optional_number("peak_at", Range{}, "where the thesis' curve peaks (trend 'peak')");
  const json& order = thesis.raw("order", "list", "first-axis values in the order of trend_of the thesis found");
  if (thesis.has("order")) {
    if (!order.is_array()) throw InputError(thesis.field("order"), "needs a list of first-axis values");
    t.order.assign(order.begin(), order.end());
  }
  t.discussion = thesis.string("discussion", "", "why softarm's result differs from the thesis, if it does");
  thesis.finish();
  return t;
}


}  // namespace

StudySpec read_study(const json& document, const std::filesystem::path& base_directory) {
  JsonReader root(document, "");
  StudySpec s;
  s.name = root.string("study", "short name: the output folder and the index entry");
  if (s.name.empty() || s.name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_-") != std::string::npos)
    throw InputError(root.field("study"), "name '" + s.name + "' must be non-empty lowercase letters, digits, _ or -");
  s.title = root.string("title", s.name, "heading of the study's report");
  s.description = root.string("description", "", "free text shown in the report");

  const json& scene = root.raw("scene", "object or string", "the base scene: a scene document as for softarm "
                               "simulate, or the name of a scene file (relative to the study config)", "(required)");
  if (!(scene.is_object() || scene.is_string()))
    throw InputError(root.field("scene"), "required: a scene document as for softarm simulate, or the name of a "
                                          "scene file (relative to the study config)");
  if (scene.is_string()) {
    const std::filesystem::path file = base_directory / scene.get<std::string>();
    if (!std::filesystem::exists(file))
      throw InputError(root.field("scene"), "scene file '" + file.string() + "' does not exist");
    s.scene = fem::load_json_file(file.string());
    s.scene.erase("output");  // a study writes its own output
    s.scene.erase("description");
  } else {
    s.scene = scene;
    if (s.scene.contains("output"))
      throw InputError("scene.output", "a study writes its own output; remove 'output' from the scene");
  }
  const json& changes = root.raw("scene_changes", "object", "a JSON merge patch applied to the base scene");
  if (root.has("scene_changes")) {
    if (!changes.is_object()) throw InputError(root.field("scene_changes"), "needs an object (a JSON merge patch)");
    s.scene.merge_patch(changes);
  }
  s.scene["output"] = {{"vtu", false}};
  const fem::SceneConfig base = [&] {
    try {
      return fem::read_scene_config(s.scene);
    } catch (const InputError& e) {
      throw InputError("scene." + e.field(), e.message());
    }
  }();
  if (base.scene == "spl")
    throw InputError("scene.scene", "value 'spl': studies run the rra and tca scenes (the arm is `softarm design`'s)");
  s.model = root.choice("model", base.scene == "tca" ? "rod" : "fem", {"fem", "rod"},
                        "fem: the scene's finite-element model; rod: the reduced rod of fem/reduced (seconds per "
                        "3CA instead of minutes; docs/reduced-model.md, Checked against the FEM)");
  s.rod_nodes = root.integer("rod_nodes_per_segment", 17, Range::closed(5, 401), "rod nodes (model rod)");
  s.safety_factor = root.number("safety_factor", 1.5, Range::closed(1, 10), "burst criteria (a), (b) of spec §4");
  s.axes = read_sweep(root);
  const auto outputs = scalar_outputs(base.scene, s.model);

  auto plot = root.object("plot", "the report's plot");
  s.plot_x = plot.choice("x", "parameter", {"parameter", "pressure"},
                         "parameter: the output at the peak pressure vs the first axis; pressure: each point's "
                         "curve vs normalised pressure");
  s.plot_y = plot.string("y", base.scene == "rra" ? "extension_mm" : "bending_deg", "the plotted output");
  if (s.plot_x == "pressure" && s.plot_y != "extension_mm" && s.plot_y != "bending_deg")
    throw InputError(plot.field("y"), "value '" + s.plot_y + "': curves vs pressure exist for extension_mm and "
                                      "bending_deg only");
  require_output(plot, "y", s.plot_y, outputs);
  plot.finish();

  s.rule = read_rule(root.object("rule", "the design rule"), outputs);
  s.thesis = read_thesis(root.object("thesis", "what the thesis found (spec §5)"), s.rule.output, outputs);
  s.point_timeout_s = root.number("point_timeout_s", 900, Range::closed(1, 86400),
                                  "a point running longer is stopped and recorded as failed (s)");
  root.finish();

  // A parameter the scene does not know fails every point alike: report it as a config error.
  for (std::size_t a = 0; a < s.axes.size(); ++a) {
    const std::string field = "sweep[" + std::to_string(a) + "].parameter";
    try {
      fem::read_scene_config(with_parameter(s.scene, s.axes[a].parameter, s.axes[a].values.front(), field));
    } catch (const InputError& e) {
      if (std::string(e.what()).find("unknown key") != std::string::npos)
        throw InputError(field, "'" + s.axes[a].parameter + "' is not a key of the scene: " + e.what());
    }
  }
  json parameters = json::array();
  for (const auto& axis : s.axes) parameters.push_back(axis.parameter);
  s.fingerprint = fingerprint_of({s.scene, s.model, s.rod_nodes, s.safety_factor, parameters});
  return s;
}

StudySpec load_study(const std::string& file_name) {
  return read_study(fem::load_json_file(file_name), std::filesystem::path(file_name).parent_path());
}

}  // namespace softarm::studies

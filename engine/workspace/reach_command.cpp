#include "engine/workspace/reach_command.hpp"

#include <filesystem>
#include <iomanip>
#include <iostream>

#include "engine/optimiser/optimiser.hpp"
#include "engine/options/option_checks.hpp"
#include "engine/report/output_files.hpp"
#include "engine/workspace/cells_cache.hpp"
#include "engine/workspace/reach.hpp"
#include "fem/core/input_error.hpp"
#include "fem/core/json_reader.hpp"
#include "fem/core/thesis_values.hpp"
#include "fem/io/vtu_writer.hpp"
#include "fem/scenes/tube_peaks.hpp"

namespace softarm::engine {
namespace {
using nlohmann::json;

Eigen::Vector3d vector3(const std::vector<double>& v) { return {v[0], v[1], v[2]}; }
json vector_json(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

/// A three-component list, or InputError naming `field`.
std::vector<double> three(const std::vector<double>& v, const std::string& field) {
  if (!v.empty() && v.size() != 3)
    throw fem::InputError(field, std::to_string(v.size()) + " numbers given; valid: three (x, y, z)");
  return v;
}

/// The tasks file: its scene (relative to the file), payload and targets (tasks.json's keys).
std::vector<ReachTarget> read_tasks(ReachOptions& o) {
  const json document = fem::load_json_file(o.tasks);  // the reader keeps a reference to it
  fem::JsonReader root(document, "");
  root.string("description", "", "what the tasks are, and the arm's mounting");
  const std::string scene = root.string("scene", "the arm's spl scene config or requirements file, relative to this file");
  o.scene = (std::filesystem::path(o.tasks).parent_path() / scene).string();
  if (auto payload = root.optional_number("payload_kg", fem::Range::closed(0, 10), "mass at the tip (kg)"))
    if (!o.payload_kg) o.payload_kg = payload;
  const json& list = root.raw("targets", "list", "the targets: name, position_mm [x, y, z], optional axis", "(required)");
  root.finish();  // a misspelt key is named before what it leaves missing
  if (!list.is_array() || list.empty()) throw fem::InputError("targets", "valid: a non-empty list of targets");
  std::vector<ReachTarget> targets;
  for (std::size_t i = 0; i < list.size(); ++i) {
    fem::JsonReader t(list[i], "targets[" + std::to_string(i) + "]");
    ReachTarget target;
    target.name = t.string("name", "the task's name");
    const auto where = t.required_number_list("position_mm", fem::Range::closed(-1e4, 1e4), "the tip's target, scene frame",
                                              "[x, y, z] in mm");
    target.position_mm = vector3(three(where, t.field("position_mm")));
    const auto axis = three(t.number_list("axis", fem::Range::closed(-1, 1), "the tip's axis wanted (optional)"), t.field("axis"));
    if (!axis.empty()) target.axis = vector3(axis);
    t.finish();
    targets.push_back(target);
  }
  return targets;
}

json solution_json(const ReachSolution& s, const fem::TubePeakMaps& maps) {
  const fem::TubePeak peak = maps.at(s.chamber_stretch);
  return {{"pressures_kPa", s.pressure_kPa},      {"tip_mm", vector_json(s.tip_mm)},
          {"tip_axis", vector_json(s.tip_axis)},  {"distance_mm", s.distance_mm},
          {"axis_error_deg", s.axis_error_deg},   {"chamber_stretch", s.chamber_stretch},
          {"peak_stretch", peak.stretch},         {"peak_segment", peak.segment},
          {"peak_extrapolated", peak.extrapolated}};
}

/// Each segment's largest chamber stretch over the solutions found (the peak maps' reach).
std::array<double, 3> largest_chamber_stretch(const std::vector<ReachResult>& results,
                                              const std::vector<PayloadMargin>& margins) {
  std::array<double, 3> largest{1, 1, 1};
  const auto take = [&](const ReachSolution& s) {
    for (int n = 0; n < 3; ++n) largest[n] = std::max(largest[n], s.chamber_stretch[n]);
  };
  for (const ReachResult& r : results) {
    for (const ReachSolution& s : r.solutions) take(s);
    if (r.nearest) take(*r.nearest);
  }
  for (const PayloadMargin& m : margins) take(m.heaviest);
  return largest;
}

void print(const ReachTarget& t, const ReachResult& r, const std::optional<PayloadMargin>& margin) {
  std::cout << std::fixed << std::setprecision(1) << t.name << " (" << t.position_mm.transpose() << " mm): ";
  const auto pressures = [](const ReachSolution& s) {
    std::ostringstream text;
    text << std::fixed << std::setprecision(0);
    for (int k = 0; k < 9; ++k) text << (k ? ", " : "") << s.pressure_kPa[k];
    return text.str() + " kPa";
  };
  if (r.reachable)
    std::cout << "reached, " << r.solutions.size() << " distinct solution(s); first " << pressures(r.solutions.front())
              << ", " << std::setprecision(3) << r.solutions.front().distance_mm << " mm off\n";
  else if (r.nearest)
    std::cout << "NOT reached from " << r.starts << " starts: the nearest point found is " << std::setprecision(1) << r.nearest->distance_mm
              << " mm away, at " << r.nearest->tip_mm.transpose() << " mm (" << pressures(*r.nearest) << ")\n";
  else
    std::cout << "NOT reached: no start posed within the cells' reach\n";
  if (margin && r.reachable)
    std::cout << std::setprecision(2) << "  payload margin: " << (margin->at_least ? "at least " : "") << margin->margin_kg
              << " kg more than " << margin->payload_kg << " kg (" << margin->evaluations << " rod solves, "
              << std::setprecision(1) << margin->seconds << " s)\n";
  std::cout.unsetf(std::ios::floatfield);
}
}  // namespace

CLI::App* add_reach_command(CLI::App& app, ReachOptions& o) {
  CLI::App* r = app.add_subcommand("reach", "the chamber pressures that put the arm's tip on a target (inverse statics on its cells)");
  r->add_option("scene", o.scene,
                "spl scene JSON file (its design, materials, gravity and tip mass), or a requirements file (its arm, "
                "working pressure and payload)");
  r->add_option("--design", o.design, "with a requirements file: a design run's summary.json, whose optimum is posed");
  r->add_option("--target", o.target_mm, "the tip's target x,y,z in mm (scene frame: shoulder up, tip at z = 0 at rest)")
      ->delimiter(',')
      ->expected(3)
      ->check(finite_in(-1e4, 1e4, "mm"));
  r->add_option("--axis", o.axis, "the tip's axis wanted, x,y,z (normalised)")->delimiter(',')->expected(3)->check(finite_in(-1, 1, ""));
  r->add_option("--tasks", o.tasks, "a tasks file (configs/tasks/): its scene and several named targets")
      ->check(CLI::ExistingFile);
  r->add_option("--payload-kg", o.payload_kg, "mass at the tip (default: the tasks' or the requirements' payload, else the scene's load.tip_mass_kg)")->check(finite_in(0, 10, "kg"));
  r->add_option("--cells", o.cells, "the arm's pressure cells file (a workspace run's cells.json); default <output>/cells.json");
  r->add_option("-o,--output", o.output, "output directory")->capture_default_str();
  r->add_option("--max-pressure-kPa", o.max_pressure_kPa,
                "every chamber's bound (default: the requirements' working pressure, else the thesis' 344.7)")
      ->check(finite_in(1, 1000, "kPa"));
  r->add_option("--directions", o.divisions, "divisions of each segment's direction grid (as the workspace's)")
      ->check(CLI::Range(1, 4))
      ->capture_default_str();
  r->add_option("--starts", o.starts, "local searches, from the sampled poses nearest the target")->check(CLI::Range(1, 64))->capture_default_str();
  r->add_option("--tolerance-mm", o.tolerance_mm, "a target is reached within this")->check(finite_in(1e-3, 100, "mm"))->capture_default_str();
  r->add_option("--algorithm", o.algorithm, "the local search (engine/optimiser's names)")
      ->check(CLI::IsMember(optimise::algorithm_names()))
      ->capture_default_str();
  r->add_flag("!--no-payload-margin", o.payload_margin,
              "skip each reached target's payload margin (a search in the pressures and the tip mass from each solution)");
  return r;
}

int run_reach(ReachOptions o) {
  std::vector<ReachTarget> targets;
  if (!o.tasks.empty()) {
    if (!o.target_mm.empty()) throw fem::InputError("--target", "given with --tasks; valid: one of the two");
    targets = read_tasks(o);
  } else {
    if (o.scene.empty()) throw fem::InputError("scene", "missing; valid: an spl scene config or a requirements file (or --tasks FILE)");
    if (o.target_mm.empty()) throw fem::InputError("--target", "missing; valid: x,y,z in mm (or --tasks FILE)");
    ReachTarget t{"target", vector3(o.target_mm), {}};
    if (!o.axis.empty()) {
      if (vector3(o.axis).norm() < 1e-6) throw fem::InputError("--axis", "zero; valid: a direction x,y,z");
      t.axis = vector3(o.axis);
    }
    targets.push_back(t);
  }
  const ArmInput arm = read_arm_input(o.scene, o.design);
  o.max_pressure_kPa = o.max_pressure_kPa.value_or(arm.max_pressure_kPa.value_or(fem::thesis::kWorkingPressure_kPa));
  if (!o.payload_kg) o.payload_kg = arm.payload_kg;
  prepare_output_directory(o.output, "--output");
  const std::string cells_file = o.cells.empty() ? o.output + "/cells.json" : o.cells;
  const fem::SplPressureCells cells = cached_pressure_cells(arm, *o.max_pressure_kPa, o.divisions, cells_file, std::cout);
  if (!cells.failure.empty()) {
    std::cout << "reach: no cells: " << cells.failure << "\n";
    write_json_file(o.output, "reach.json", {{"failure", cells.failure}});
    return 1;
  }
  ReachSettings settings;
  settings.payload_kg = o.payload_kg;
  settings.starts = o.starts;
  settings.tolerance_mm = o.tolerance_mm;
  settings.algorithm = o.algorithm;
  settings.design = arm.spl.design;
  std::vector<ReachResult> results;
  std::vector<PayloadMargin> margins;
  for (const ReachTarget& target : targets) {
    results.push_back(reach(cells, target, settings));
    std::optional<PayloadMargin> margin;
    if (o.payload_margin && results.back().reachable) margins.push_back(*(margin = payload_margin(cells, target, settings, results.back())));
    print(target, results.back(), margin);
  }
  // The tube's peak stretch at every solution: each segment's lone-RRA map over what the solutions reach.
  const fem::TubePeakMaps maps =
      fem::tube_peak_maps(arm.spl, largest_chamber_stretch(results, margins), *o.max_pressure_kPa);
  json report = json::array();
  std::vector<std::vector<Eigen::Vector3d>> lines;
  fem::NamedField which{"target", 1, {}};
  bool all = true;
  for (std::size_t i = 0, m = 0; i < targets.size(); ++i) {
    const ReachResult& r = results[i];
    all = all && r.reachable;
    json j = {{"name", targets[i].name}, {"target_mm", vector_json(targets[i].position_mm)}, {"reachable", r.reachable},
              {"starts", r.starts}, {"evaluations", r.evaluations}, {"seconds", r.seconds}, {"solutions", json::array()}};
    if (targets[i].axis) j["axis"] = vector_json(targets[i].axis->normalized());
    for (const ReachSolution& s : r.solutions) {
      j["solutions"].push_back(solution_json(s, maps));
      lines.push_back(s.centreline_mm);
      which.values.push_back(static_cast<double>(i));
    }
    if (!r.reachable && r.nearest) {
      j["nearest"] = solution_json(*r.nearest, maps);
      lines.push_back(r.nearest->centreline_mm);
      which.values.push_back(static_cast<double>(i));
    }
    if (o.payload_margin && r.reachable) {
      const PayloadMargin& margin = margins[m++];
      j["payload_margin"] = {{"margin_kg", margin.margin_kg},
                             {"at_least", margin.at_least},
                             {"heaviest_kg", margin.payload_kg + margin.margin_kg},
                             {"heaviest_solution", solution_json(margin.heaviest, maps)},
                             {"searches", margin.searches},
                             {"rod_solves", margin.evaluations},
                             {"seconds", margin.seconds}};
    }
    report.push_back(j);
  }
  write_json_file(o.output, "reach.json",
                  {{"scene", o.scene}, {"max_pressure_kPa", *o.max_pressure_kPa}, {"tolerance_mm", o.tolerance_mm},
                   {"payload_kg", o.payload_kg.value_or(arm.spl.tip_mass_kg)}, {"targets", report}});
  fem::write_polyline_vtu(o.output + "/poses.vtu", lines, which);
  std::cout << "written: " << o.output << "/reach.json, poses.vtu\n";
  return all ? 0 : 1;
}

}  // namespace softarm::engine

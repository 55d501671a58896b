#include "engine/cli.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <optional>

#include "engine/options/option_checks.hpp"
#include "engine/design/design_command.hpp"
#include "fem/core/number_text.hpp"
#include "fem/core/thesis_values.hpp"
#include "engine/design/design_config.hpp"
#include "engine/design/design_measures.hpp"
#include "engine/optimiser/optimiser.hpp"
#include "engine/fidelity_report.hpp"
#include "engine/material_command.hpp"
#include "engine/reduced_simulate.hpp"
#include "engine/scene_checkpoint.hpp"
#include "engine/study/study_command.hpp"
#include "studies/study_spec.hpp"
#include "engine/rra_report.hpp"
#include "fem/scenes/scene_config.hpp"
#include "engine/spl_report.hpp"
#include "engine/tca_report.hpp"
#include "engine/workspace/reach_command.hpp"
#include "engine/workspace/workspace_command.hpp"
#include "fem/scenes/tca_export.hpp"
#include "fem/core/input_error.hpp"
#include "fem/core/json_reader.hpp"
#include "fem/core/parallel.hpp"

namespace softarm::engine {
namespace {

void print_checkpoint(const fem::PathCheckpoint& checkpoint) {
  std::cout << "checkpoint: " << checkpoint.file
            << " (every converged step as it comes; a rerun resumes from the last one, --fresh starts over)\n";
}

int simulate_tca(fem::SceneConfig config, const fem::PathCheckpoint& checkpoint) {
  const fem::ModelChoice model = fem::choose_tca_model(config.tca);
  std::cout << "model: " << model.name << " (" << model.reason << ")\n";
  print_checkpoint(checkpoint);
  config.tca.checkpoint = checkpoint;
  TcaCurveWriter writer(config.output.directory, std::cout);
  const auto result = fem::run_tca_scene(config.tca, [&](const fem::TcaState& s) { writer.add(s); });
  if (const std::string note = checkpoint_note(checkpoint, result.path); !note.empty()) std::cout << note << "\n";
  write_tca_summary(config, result, std::cout);
  return fem::is_answer(result.path.outcome) ? 0 : 1;
}

int simulate_spl(fem::SceneConfig config, const fem::PathCheckpoint& checkpoint) {
  const fem::ModelChoice model = fem::choose_spl_model(config.spl);
  std::cout << "model: " << model.name << " (" << model.reason << ")\n";
  print_checkpoint(checkpoint);
  config.spl.checkpoint = checkpoint;
  SplCurveWriter writer(config.output.directory, std::cout);
  const auto result = fem::run_spl_scene(config.spl, [&](const fem::SplState& s) { writer.add(s); });
  if (const std::string note = checkpoint_note(checkpoint, result.path); !note.empty()) std::cout << note << "\n";
  write_spl_summary(config, result, std::cout);
  return fem::is_answer(result.path.outcome) ? 0 : 1;
}

int simulate(const std::string& file, const std::string& output_override, int mesh_level_override,
             int element_order_override, const std::string& fidelity_override, bool fresh) {
  fem::SceneConfig config = fem::load_scene_config(file);
  if (!output_override.empty()) config.output.directory = output_override;
  if (!fidelity_override.empty()) {
    if (mesh_level_override > 0 || element_order_override > 0)
      throw fem::InputError("--fidelity", "the fidelity ladder picks the mesh: give --fidelity or --mesh-level / "
                                          "--element-order, not both");
    fem::apply_fidelity(config, fem::fidelity_target_percent(fidelity_override), "--fidelity " + fidelity_override);
  }
  if ((mesh_level_override > 0 || element_order_override > 0) && config.selection) {
    std::cout << "--mesh-level / --element-order override the fidelity ladder's choice (" << config.selection->level.name
              << ")\n";
    config.selection.reset();
    config.reduced = config.cell_rod = false;
  }
  if (mesh_level_override > 0) config.mesh_level() = mesh_level_override;
  if (element_order_override > 0) config.element_order() = element_order_override;
  if (config.selection)
    std::cout << "model (fidelity ladder): " << config.selection->level.name << ", expected error "
              << config.selection->level.error_percent << " % — " << config.selection->reason << "\n";
  if (config.reduced) return simulate_reduced(config);
  const int axial_level = config.layers_level();
  std::cout << "softarm simulate: " << file << " (scene " << config.scene << ", mesh level " << config.mesh_level()
            << (axial_level != config.mesh_level() ? ", axial level " + std::to_string(axial_level) : "")
            << ", element order " << config.element_order() << ", threads " << fem::thread_count() << ")\n";
  if (config.scene == "tca" || config.scene == "spl") {
    // The 3D models run for minutes to hours: their paths are kept as they go.
    const std::string overrides = "mesh_level " + std::to_string(mesh_level_override) + ", element_order " +
                                  std::to_string(element_order_override) + ", fidelity " + fidelity_override;
    const fem::PathCheckpoint checkpoint =
        scene_checkpoint(fem::load_json_file(file), overrides, config.output.directory, fresh);
    return config.scene == "tca" ? simulate_tca(config, checkpoint) : simulate_spl(config, checkpoint);
  }
  RraCurveWriter writer(config.output.directory, std::cout);
  const auto result = fem::run_rra_scene(config.rra, [&](const fem::RraCurvePoint& p) { writer.add(p); });
  write_rra_summary(config, result, std::cout);
  // A limit point or a named failure is a valid physical answer; a stall is not the requested result.
  return fem::is_answer(result.path.outcome) ? 0 : 1;
}

int export_deck(const std::string& file, const std::string& deck_path, double pressure_kPa, int mesh_level_override) {
  fem::SceneConfig config = fem::load_scene_config(file);
  if (mesh_level_override > 0) config.mesh_level() = mesh_level_override;
  if (config.scene == "spl")
    throw fem::InputError("scene", "export writes rra and tca scenes; an SPL deck is not implemented yet");
  fem::Mesh mesh;
  fem::AbaqusDeck deck;
  double p = pressure_kPa;
  if (config.scene == "tca") {
    // The model the scene is solved on (half or full), at the peak pressures scaled to --pressure-kPa.
    const auto& peaks = config.tca.chamber_pressure_kPa;
    const double p_max = std::max({peaks[0], peaks[1], peaks[2]});
    if (p <= 0) p = p_max;
    const fem::ModelChoice model = fem::choose_tca_model(config.tca);
    mesh = fem::tca_mesh(config.tca, model);
    deck = fem::tca_abaqus_deck(config.tca, mesh, model, p / p_max);
    std::cout << "model: " << model.name << "\n";
  } else {
    if (p <= 0) p = config.rra.path.max_pressure_kPa;
    mesh = fem::rra_mesh(config.rra);
    deck = fem::rra_abaqus_deck(config.rra, mesh, p);
  }
  try {
    fem::write_abaqus_deck(deck_path, deck);
  } catch (const std::invalid_argument& e) {  // unwritable path, or a law with no Abaqus card
    throw fem::InputError("--output", e.what());
  }
  std::cout << "wrote " << deck_path << ": " << mesh.num_elements() << " elements, peak chamber pressure " << p
            << " kPa (run: ccx -i " << deck_path.substr(0, deck_path.rfind(".inp")) << ")\n";
  return 0;
}

/// "sweep[1].range.from" -> "sweep[].range.from": a list's items share their keys.
std::string without_item_indices(const std::string& path) {
  std::string out;
  for (std::size_t i = 0; i < path.size(); ++i) {
    out += path[i];
    if (path[i] != '[') continue;
    while (i + 1 < path.size() && std::isdigit(static_cast<unsigned char>(path[i + 1]))) ++i;
  }
  return out;
}

void print_fields(const std::string& title) {
  std::cout << title << ":\n";
  std::vector<std::string> printed;
  for (const auto& f : fem::JsonReader::documented_fields()) {
    // A list's items print once, as "sweep[].values", whichever item declared them.
    const std::string path = without_item_indices(f.path);
    if (std::find(printed.begin(), printed.end(), path) != printed.end()) continue;
    printed.push_back(path);
    std::cout << path << "  (" << f.type << ", default " << f.default_value
              << (f.range.empty() ? "" : ", valid " + f.range) << ")\n    " << f.doc << "\n";
  }
}

void print_schema(const std::string& scene) {
  if (scene == "design") {
    // Reading the thesis requirements registers every requirements key with its documentation.
    nlohmann::json probe = {{"design_space", nlohmann::json::object()}};
    for (const auto& name : design_variable_names()) {
      if (name.find("_mm") != std::string::npos && name != "actuator_spacing_mm") continue;  // the normalised twin is read
      probe["design_space"][name] = name.find("material") != std::string::npos
                                        ? nlohmann::json{{"choices", {"dragon_skin_30"}}}
                                        : nlohmann::json{{"min", name == "ring_count" ? 20.0 : 0.3},
                                                         {"max", name == "ring_count" ? 40.0 : 0.5}};
    }
    probe["design_space"]["actuator_spacing_mm"] = {{"min", 2.5}, {"max", 6}};
    // The start design must be complete (the geometry takes one of each physical/normalised pair)
    // and inside the probe's bounds.
    probe["baseline_geometry"] = {{"wall_thickness_normalised", 0.466}, {"end_cap_thickness_normalised", 0.4},
                                  {"ring_count_normalised", 0.375}, {"ring_thickness_normalised", 0.4}};
    read_design_config(probe);
    print_fields("requirements config (softarm design) keys; design_space also takes wall_thickness_mm, "
                 "end_cap_thickness_mm, ring_diameter_mm instead of their normalised twins, and baseline_geometry "
                 "any SPL geometry key (softarm schema --scene spl)");
    std::cout << "measures for \"objective\": {\"minimise\"|\"maximise\": name} and \"constraints\": "
                 "[{\"measure\": name, \"min\"|\"max\": value}]:\n";
    for (const auto& m : design_measures()) std::cout << "  " << m.name << "\n    " << m.doc << "\n";
    return;
  }
  if (scene == "study") {
    // Reading a minimal study registers every study key (and the scene keys of its base scene).
    const nlohmann::json probe = {
        {"study", "probe"},
        {"scene", {{"scene", "rra"}, {"geometry", {{"wall_thickness_normalised", 0.466}, {"end_cap_thickness_normalised", 0.25},
                                                   {"ring_count_normalised", 0.375}, {"ring_thickness_normalised", 0.4}}},
                   {"load", {{"max_pressure_kPa", fem::thesis::kRraTestPressure_kPa}}}}},
        {"sweep", {{{"parameter", "geometry.wall_thickness_normalised"}, {"values", {0.4}}},
                   {{"parameter", "geometry.ring_thickness_normalised"}, {"range", {{"from", 0.2}, {"to", 0.3}}}}}},
        {"rule", {{"output", "extension_mm"}, {"limits", {{{"output", "mass_g"}, {"max", 100}}}}}},
        {"thesis", {{"choice", 0.4}, {"order", {0.4}}}}};
    studies::read_study(probe);
    print_fields("study config (softarm study) keys, with those of its base scene (here an rra scene)");
    std::cout << "outputs (rule, plot, limits, thesis.trend_of): rra: ";
    for (const auto& o : studies::scalar_outputs("rra", "fem")) std::cout << o << " ";
    std::cout << "\n  tca (model rod): ";
    for (const auto& o : studies::scalar_outputs("tca", "rod")) std::cout << o << " ";
    std::cout << "\n  sweep parameters: any scene path <section>.<key> (softarm schema --scene rra|tca), or taper_ratio "
                 "(the distal segment's radii by thesis eqs 5-7)\n";
    return;
  }
  // Reading a complete default scene registers every field with its documentation.
  const nlohmann::json rra_sizes = {{"wall_thickness_normalised", 0.466}, {"end_cap_thickness_normalised", 0.25},
                                    {"ring_count_normalised", 0.375}, {"ring_thickness_normalised", 0.4}};
  nlohmann::json probe = {{"scene", scene}, {"geometry", rra_sizes}};
  if (scene == "rra") probe["load"] = {{"max_pressure_kPa", fem::thesis::kRraTestPressure_kPa}};
  if (scene == "tca") probe["load"] = {{"chamber_pressures_kPa", {0.0, fem::thesis::kWorkingPressure_kPa, fem::thesis::kWorkingPressure_kPa}}};
  if (scene == "spl") probe["load"] = {{"chamber_pressures_kPa", {0, 345, 345, 0, 86, 345, 0, 0, 59}}};
  fem::read_scene_config(probe);
  print_fields("scene \"" + scene + "\" config keys");
}

/// The name in `names` nearest to `given` by edit distance (insertions, deletions, substitutions).
std::string nearest_name(const std::string& given, const std::vector<std::string>& names) {
  std::string best;
  std::size_t best_distance = std::string::npos;
  for (const std::string& name : names)
    if (const std::size_t d = fem::edit_distance(given, name); d < best_distance) best_distance = d, best = name;
  return best;
}

struct SimulateOptions {
  std::string scene, output;
  int mesh_level = 0, element_order = 0;
  std::string fidelity;
  bool fresh = false;
};
CLI::App* add_simulate_command(CLI::App& app, SimulateOptions& o) {
  CLI::App* sim = app.add_subcommand("simulate", "run a scene config (e.g. configs/rra_thesis.json)");
  sim->add_option("scene", o.scene, "scene JSON file")->required();
  sim->add_option("-o,--output", o.output, "output directory (overrides output.directory)");
  sim->add_option("--mesh-level", o.mesh_level, "mesh refinement level (overrides mesh.level)")->check(CLI::Range(1, 6));
  sim->add_option("--element-order", o.element_order, "1 (linear) or 2 (quadratic): overrides mesh.element_order")
      ->check(CLI::Range(1, 2));
  sim->add_option("--fidelity", o.fidelity,
                  "fast, balanced or accurate: the fidelity ladder picks the model (overrides the config's mesh and model.fidelity)")
      ->check(CLI::IsMember({"fast", "balanced", "accurate"}));
  sim->add_flag("--fresh", o.fresh,
                "3D scenes: discard the converged steps of an earlier run in the output directory instead of resuming");
  return sim;
}

struct ExportOptions {
  std::string scene, deck = "out/scene.inp";
  double pressure_kPa = 0.0;
  int mesh_level = 0;
};
CLI::App* add_export_command(CLI::App& app, ExportOptions& o) {
  CLI::App* exp = app.add_subcommand("export", "write a scene as an Abaqus/CalculiX input deck (.inp)");
  exp->add_option("scene", o.scene, "scene JSON file")->required();
  exp->add_option("-o,--output", o.deck, "deck file (default out/scene.inp)");
  exp->add_option("--pressure-kPa", o.pressure_kPa, "chamber pressure of the deck (default: load.max_pressure_kPa)")
      ->check(finite_in(1e-6, 1e4, "kPa"));
  exp->add_option("--mesh-level", o.mesh_level, "mesh refinement level (overrides mesh.level)")->check(CLI::Range(1, 6));
  return exp;
}

CLI::App* add_schema_command(CLI::App& app, std::string& scene) {
  CLI::App* schema = app.add_subcommand("schema", "list every scene-config key with its unit, default and valid range");
  schema->add_option("--scene", scene, "which keys: rra, tca, spl (scene configs), design (requirements) or study")
      ->check(CLI::IsMember({"rra", "tca", "spl", "design", "study"}));
  return schema;
}

struct DesignCommandOptions {
  std::string requirements;
  DesignOverrides overrides;
};
CLI::App* add_design_command(CLI::App& app, DesignCommandOptions& o) {
  CLI::App* design = app.add_subcommand(
      "design", "the main job: requirements in, optimal design out (e.g. configs/thesis_requirements.json)");
  design->add_option("requirements", o.requirements, "requirements JSON file")->required();
  design->add_option("-o,--output", o.overrides.output_directory, "output directory (overrides output.directory)");
  design->add_option("--algorithm", o.overrides.algorithm, "optimiser algorithm (overrides optimiser.algorithm)")
      ->check(CLI::IsMember(optimise::algorithm_names()));
  design->add_option("--max-evaluations", o.overrides.max_evaluations,
                     "evaluation budget (overrides optimiser.max_evaluations)")
      ->check(CLI::Range(1, 100000));
  design->add_option("--fidelity", o.overrides.fidelity,
                     "accurate: every optimum verified on the cell rod, which decides feasibility (the config's "
                     "check); fast: the fibre-rod search alone, no verification, no 3D check (a first look in minutes; "
                     "its measured error is printed)")
      ->check(CLI::IsMember({"fast", "accurate"}));
  design->add_flag("--fresh", o.overrides.fresh,
                   "discard the evaluations and 3D checks of an earlier run in the output directory instead of resuming");
  return design;
}

CLI::App* add_study_command(CLI::App& app, StudyOptions& o) {
  CLI::App* study = app.add_subcommand("study", "run parameter studies from JSON study configs and write their design-rule "
                                                "reports (e.g. configs/studies); resumes; mpirun -np N spreads the points");
  study->add_option("configs", o.configs, "study config files or directories of them")->required();
  study->add_option("-o,--output", o.output_root, "output root: <root>/<study>/ and <root>/index.html")
      ->capture_default_str();
  study->add_option("--jobs", o.jobs, "points solved at once on this machine (default: all cores; 1 per "
                                      "rank under mpirun)")
      ->check(CLI::Range(1, 1024));
  study->add_flag("--fresh", o.fresh, "discard earlier results instead of resuming");
  study->add_flag("--retry-failed", o.retry_failed, "recompute points recorded as failed");
  study->add_flag("--report-only", o.report_only, "write the reports from the results on disk");
  return study;
}

CLI::App* add_fidelity_command(CLI::App& app, std::string& report) {
  CLI::App* fidelity = app.add_subcommand("fidelity", "the fidelity ladder: each scene's models with measured error and "
                                                      "cost (what model.fidelity / model.target_error_percent choose from)");
  fidelity->add_option("--report", report, "also write an HTML page with a Pareto plot per scene");
  return fidelity;
}

/// A first argument that names no command: the nearest that does, and exit 2; else nothing.
std::optional<int> refuse_unknown_command(const CLI::App& app, int argc, char** argv) {
  if (argc < 2) return std::nullopt;
  const std::string first = argv[1];
  if (first.empty() || first[0] == '-') return std::nullopt;
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) names.push_back(sub->get_name());
  if (std::find(names.begin(), names.end(), first) != names.end()) return std::nullopt;
  std::cerr << "softarm: unknown command '" << first << "'; did you mean '" << nearest_name(first, names)
            << "'? Commands:";
  for (const auto& n : names) std::cerr << " " << n;
  std::cerr << " (softarm --help)\n";
  return 2;
}

}  // namespace

int run_cli(int argc, char** argv) {
  CLI::App app{"softarm: design optimisation and simulation of soft pneumatic continuum arms", "softarm"};
  app.set_version_flag("--version", std::string("softarm ") + SOFTARM_VERSION);
  app.require_subcommand(1);
  app.fallthrough();  // global options (--threads) may follow the subcommand
  int threads = 0;
  app.add_option("--threads", threads, "worker threads for assembly (default: SOFTARM_THREADS or all cores)")
      ->check(CLI::Range(1, 256));
  SimulateOptions simulate_options;
  CLI::App* sim = add_simulate_command(app, simulate_options);
  ExportOptions export_options;
  CLI::App* exp = add_export_command(app, export_options);
  std::string schema_scene = "rra";
  CLI::App* schema = add_schema_command(app, schema_scene);
  DesignCommandOptions design_options;
  CLI::App* design = add_design_command(app, design_options);
  StudyOptions study_options;
  CLI::App* study = add_study_command(app, study_options);
  std::string fidelity_report;
  CLI::App* fidelity = add_fidelity_command(app, fidelity_report);
  add_material_command(app);
  WorkspaceOptions workspace_options;
  CLI::App* workspace = add_workspace_command(app, workspace_options);
  ReachOptions reach_options;
  CLI::App* reach = add_reach_command(app, reach_options);

  if (argc == 1) {  // bare `softarm`: the help, not an error
    std::cout << app.help();
    return 0;
  }
  if (const std::optional<int> refused = refuse_unknown_command(app, argc, argv)) return *refused;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  } catch (const fem::InputError& e) {
    std::cerr << "softarm: " << e.what() << "\n";
    return 2;
  }
  if (threads > 0) fem::set_thread_count(threads);
  try {
    const SimulateOptions& so = simulate_options;
    if (*sim) return simulate(so.scene, so.output, so.mesh_level, so.element_order, so.fidelity, so.fresh);
    if (*design) return run_design(design_options.requirements, design_options.overrides);
    if (*study) return run_study_command(study_options);
    if (*workspace) return run_workspace(workspace_options);
    if (*reach) return run_reach(reach_options);
    if (*fidelity) {
      print_fidelity_ladders();
      if (!fidelity_report.empty()) write_fidelity_report(fidelity_report);
      return 0;
    }
    if (*exp) return export_deck(export_options.scene, export_options.deck, export_options.pressure_kPa, export_options.mesh_level);
    if (*schema) {
      print_schema(schema_scene);
      return 0;
    }
  } catch (const fem::InputError& e) {
    std::cerr << "softarm: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "softarm: internal error: " << e.what() << "\n";
    return 3;
  }
  return 0;
}

}  // namespace softarm::engine

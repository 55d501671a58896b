#include "engine/design/design_command.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <optional>

#include "engine/design/design_problem.hpp"
#include "engine/design/design_report.hpp"
#include "engine/output_files.hpp"

namespace softarm::engine {
namespace {
using Clock = std::chrono::steady_clock;

std::string fixed(double v, int digits) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}

// The 3D check of one segment of the optimum: the rod's error on it and the 3D model's verdict.
void print_solid_check(const objectives::SolidSegmentCheck& sc, double target_deg) {
  const auto kPa_or = [](const std::optional<double>& p, const char* none) {
    return p ? fixed(*p, 1) + " kPa" : std::string(none);
  };
  std::cout << "3D check of segment " << sc.segment << " (" << sc.element << ", " << sc.dofs << " dofs, "
            << fixed(sc.seconds, 0) << " s): at " << fixed(sc.reached_pressure_kPa, 1) << " kPa it bends "
            << fixed(sc.bending_deg, 2) << " deg, the rod " << fixed(sc.rod_bending_deg, 2) << " deg (rod error "
            << fixed(sc.bending_error_percent(), 1) << " %); " << target_deg << " deg at "
            << kPa_or(sc.pressure_for_target_kPa, "no pressure reached") << " (rod: "
            << kPa_or(sc.rod_pressure_for_target_kPa, "not reached") << "); path: " << sc.outcome << "\n";
  std::cout << "3D verdict on segment " << sc.segment << ": bending " << (sc.meets_bending() ? "met" : "NOT met")
            << ", working pressure " << sc.working_pressure_verdict() << "\n";
}

void print_measures(const std::string& title, const objectives::ArmMeasures& m) {
  std::cout << title << ": mass " << fixed(m.mass_kg, 3) << " kg, payload " << fixed(m.payload_kg, 3)
            << " kg, bending per segment " << fixed(m.segments[0].bending_deg_at_working, 1) << " / "
            << fixed(m.segments[1].bending_deg_at_working, 1) << " / " << fixed(m.segments[2].bending_deg_at_working, 1)
            << " deg, burst utilisation " << fixed(m.burst_utilisation, 3) << " (" << m.burst_governing
            << "), peak log strain " << fixed(m.durability_log_strain, 3) << " (" << fixed(m.seconds, 2) << " s)\n";
}

void print_constraints(const ConstraintValues& c) {
  for (std::size_t i = 0; i < c.names.size(); ++i)
    std::cout << "  " << std::left << std::setw(11) << c.names[i] << std::right << " margin " << std::setw(8)
              << fixed(-100 * c.values[i], 1) << " %" << (c.values[i] > 1e-6 ? "  VIOLATED" : "") << "\n";
}
}  // namespace

int run_design(const std::string& file, const DesignOverrides& overrides) {
  const auto t0 = Clock::now();
  DesignConfig config = load_design_config(file);
  if (!overrides.output_directory.empty()) config.output_directory = overrides.output_directory;
  if (!overrides.algorithm.empty()) config.optimiser.algorithm = overrides.algorithm;
  if (overrides.max_evaluations > 0) config.optimiser.max_evaluations = overrides.max_evaluations;
  std::filesystem::create_directories(config.output_directory);
  std::cout << "softarm design: " << file << "\nobjective: " << config.objective << "; requirements: mass <= "
            << config.requirements.max_mass_kg << " kg, payload >= " << config.requirements.min_payload_kg
            << " kg, bending >= " << config.requirements.bending_per_segment_deg << " deg per segment at "
            << config.requirements.max_pressure_kPa << " kPa, length " << config.requirements.length_m << " m\n"
            << "model: reduced rod + axisymmetric RRA FEM level " << config.model.rra_mesh_level << "; optimiser "
            << config.optimiser.algorithm << ", budget " << config.optimiser.max_evaluations << " evaluations, "
            << config.optimiser.starts << " start(s)\n";

  const double ref_strain =
      objectives::durability_reference_log_strain(config.requirements.durability_reference_pressure_kPa,
                                                  config.model.rra_mesh_level);
  std::cout << "durability reference: thesis RRA at " << config.requirements.durability_reference_pressure_kPa
            << " kPa, peak log strain " << fixed(ref_strain, 4) << " (lasted "
            << config.requirements.durability_reference_cycles << " cycles)\n";

  DesignRun run;
  run.config = &config;
  run.reference_strain = ref_strain;
  run.thesis_x = baseline_values(config);
  run.thesis = objectives::evaluate_arm(make_candidate(config, run.thesis_x), config.model);
  print_measures("thesis design (Tables 7, 11)", run.thesis);
  print_constraints(constraints_of(config, run.thesis, ref_strain));

  // Every evaluation goes to history.csv as it happens: a stopped run keeps what it computed.
  std::ofstream history = open_output_file(config.output_directory, "history.csv");
  history << "evaluation,phase,feasible,objective";
  for (const auto& n : constraints_of(config, {}, ref_strain).names) history << ",g_" << n;
  for (const auto& v : config.variables) history << "," << v.variable.name;
  history << ",failure\n";
  std::map<std::vector<double>, objectives::ArmMeasures> measured;
  optimise::Problem problem = design_problem(config, ref_strain, [&](const std::vector<double>& x, const objectives::ArmMeasures& m) {
    measured[x] = m;
  });
  optimise::Options options = config.optimiser;
  options.x0 = run.thesis_x;
  options.on_evaluation = [&](const optimise::Progress& p) {
    bool feasible = p.value.ok;
    double worst = -1e300;
    std::size_t binding = 0;
    for (std::size_t i = 0; i < p.value.constraints.size(); ++i) {
      feasible = feasible && p.value.constraints[i] <= options.constraint_tolerance;
      if (p.value.constraints[i] > worst) worst = p.value.constraints[i], binding = i;
    }
    run.history.push_back({p.evaluation, p.value.ok ? p.value.objective : std::nan(""), feasible, p.phase});
    std::cout << "eval " << std::setw(3) << p.evaluation << " [" << p.phase << "] ";
    if (!p.value.ok) {
      std::cout << "failed: " << p.value.failure_reason << "\n";
    } else {
      std::cout << "objective " << fixed(p.value.objective, 4) << (feasible ? "  feasible" : "  infeasible")
                << "  (tightest: " << problem.constraint_names[binding] << " " << fixed(-100 * worst, 1)
                << " %)  best feasible " << (std::isfinite(p.best_feasible_objective) ? fixed(p.best_feasible_objective, 4) : "none")
                << "\n";
    }
    history << p.evaluation << "," << p.phase << "," << feasible << "," << (p.value.ok ? p.value.objective : std::nan(""));
    for (std::size_t i = 0; i < problem.constraint_names.size(); ++i)
      history << "," << (i < p.value.constraints.size() ? p.value.constraints[i] : std::nan(""));
    for (double v : p.x) history << "," << v;
    history << ",\"" << p.value.failure_reason << "\"\n";
    history.flush();
  };
  const optimise::Result result = optimise::minimise(problem, options);
  run.result = result;
  run.optimum_x = result.x;
  std::cout << "\noptimiser: " << result.evaluations << " evaluations (" << result.cache_hits << " cache hits), "
            << fixed(result.seconds, 1) << " s; " << result.stop_reason << "\n";
  const auto found = measured.find(result.x);
  run.optimum = found != measured.end() ? found->second
                                        : objectives::evaluate_arm(make_candidate(config, result.x), config.model);
  std::cout << (result.feasible ? "optimal design: " : "no design meets every requirement; the closest: ")
            << describe(config, result.x) << "\n";
  print_measures("optimum (search model)", run.optimum);
  const ConstraintValues margins = constraints_of(config, run.optimum, ref_strain);
  print_constraints(margins);
  if (!result.feasible) {
    std::size_t worst = 0;
    for (std::size_t i = 1; i < margins.values.size(); ++i)
      if (margins.values[i] > margins.values[worst]) worst = i;
    std::cout << "binding constraint: " << margins.names[worst] << ", violated by " << fixed(100 * margins.values[worst], 1)
              << " % of its limit at the best design found within the bounds\n";
  }

  // Re-check at the higher fidelity and report the difference.
  run.check_reference_strain = ref_strain;
  run.check = objectives::evaluate_arm(make_candidate(config, result.x), config.check);
  print_measures("optimum re-checked (" + std::to_string(config.check.rod_nodes_per_segment) + " rod nodes per segment, " +
                     std::to_string(config.check.pressure_steps) + " pressure steps)",
                 run.check);
  const ConstraintValues checked = constraints_of(config, run.check, run.check_reference_strain);
  print_constraints(checked);
  std::cout << "fidelity difference: mass " << fixed(100 * (run.check.mass_kg / run.optimum.mass_kg - 1), 2)
            << " %, payload " << fixed(100 * (run.check.payload_kg / run.optimum.payload_kg - 1), 2) << " %, min bending "
            << fixed(run.check.min_bending_deg - run.optimum.min_bending_deg, 2) << " deg, burst utilisation "
            << fixed(run.check.burst_utilisation - run.optimum.burst_utilisation, 3) << "; search margin "
            << fixed(100 * config.search_margin, 1) << " %\n";
  // The local peaks come from a stress singularity (the groove lip): how they move one RRA mesh level finer.
  objectives::EvaluationSettings finer = config.check;
  finer.rra_mesh_level = config.check.rra_mesh_level + 1;
  run.finer_peaks = objectives::evaluate_arm(make_candidate(config, result.x), finer);
  run.finer_reference_strain = objectives::durability_reference_log_strain(
      config.requirements.durability_reference_pressure_kPa, finer.rra_mesh_level);
  std::cout << "local peaks one RRA mesh level finer (level " << finer.rra_mesh_level << "): burst utilisation "
            << fixed(run.finer_peaks.burst_utilisation, 3) << " (" << run.finer_peaks.burst_governing << ") vs "
            << fixed(run.check.burst_utilisation, 3) << "; durability strain ratio "
            << fixed(run.finer_peaks.durability_log_strain / run.finer_reference_strain, 3) << " vs "
            << fixed(run.check.durability_log_strain / ref_strain, 3)
            << " (the groove lip is a stress singularity: its peaks grow with refinement, so the burst criterion "
               "is defined at RRA level "
            << config.check.rra_mesh_level << "; durability is a ratio to the thesis RRA at the same level)\n";

  if (config.solid_check_segment > 0) {
    // The ladder's accurate rung on the final design: one segment by the 3D FEM against the rod.
    const int n = config.solid_check_segment;
    std::cout << "3D check of segment " << n << " (minutes) ...\n" << std::flush;
    try {
      run.solid_check = objectives::check_segment_in_3d(
          make_candidate(config, result.x), config.check, n, run.check.segments[static_cast<std::size_t>(n - 1)], 1,
          [](double p, double deg) { std::cout << "  3D: " << fixed(p, 1) << " kPa, " << fixed(deg, 2) << " deg\n" << std::flush; });
    } catch (const std::exception& e) {  // the search's results stand; the check reports why it could not run
      std::cout << "3D check of segment " << n << " could not run: " << e.what() << "\n";
    }
  }
  if (run.solid_check) print_solid_check(*run.solid_check, config.requirements.bending_per_segment_deg);

  std::cout << "model errors (fidelity ladder, softarm fidelity):";
  for (const auto& e : model_errors_json(config.check.rra_mesh_level))
    std::cout << " " << e["what"].get<std::string>() << " by the " << e["model"].get<std::string>() << ": "
              << e["error_percent"].get<double>() << " % (" << e["measured_on"].get<std::string>() << ");";
  std::cout << "\n";

  run.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  write_design_outputs(run);
  std::cout << "total " << fixed(run.seconds, 1) << " s; written: " << config.output_directory
            << "/report.html, summary.json, history.csv, optimum_payload_pose.vtu, optimum_mesh.vtu\n";
  return 0;
}

}  // namespace softarm::engine

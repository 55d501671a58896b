// The design search's two models side by side on one design: the search model (fibre rod + lone
// RRA FEM, objectives/arm_evaluation.hpp) and the accurate model that verifies and corrects it
// (the cell rod of the whole arm, objectives/cell_rod_evaluation.hpp). Prints every requirement's
// measure by both, the search model's error, and what the verification costs (cells, dofs, time,
// rod poses, peak memory).
//
//   build/bench_design_verification [requirements.json] [--design '{"wall_thickness_normalised": 0.4, ...}']
//                                   [--cell-levels N]
// Without --design: the config's baseline (the thesis design). The design's values are given in
// the variables' physical units, materials by name.
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>

#include "benchmarks/bench_options.hpp"
#include "benchmarks/bench_stats.hpp"
#include "engine/design/design_config.hpp"
#include "engine/design/design_problem.hpp"
#include "fem/core/input_error.hpp"
#include "fem/core/json_reader.hpp"
#include "objectives/cell_rod_evaluation.hpp"

using namespace softarm;

namespace {
double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;
}

void row(const char* name, double search, double accurate) {
  const double error = std::abs(accurate) > 1e-12 ? 100 * (search - accurate) / std::abs(accurate) : NAN;
  std::printf("  %-34s %12.4f %12.4f %9.1f %%\n", name, search, accurate, error);
}
}  // namespace

int main(int argc, char** argv) try {
  std::string file = std::string(SOFTARM_SOURCE_DIR) + "/configs/thesis_requirements.json";
  std::string design_text = "{}";
  int cell_levels = 16;
  CLI::App app{"one design by the search model and by the cell rod, and what the verification costs"};
  app.add_option("requirements", file, "the design job's requirements config");
  app.add_option("--design", design_text,
                 "the design's values by variable name, in the variables' physical units, materials by name "
                 "(the config's baseline for the rest)")
      ->check(CLI::Validator(
          [](std::string& text) {
            const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
            return j.is_object() ? std::string() : "not a JSON object: " + text;
          },
          "JSON"));
  app.add_option("--cell-levels", cell_levels, "outputs along the cells' pressure ramp")->check(CLI::Range(1, 256));
  if (const auto code = bench::parse_or_exit(app, argc, argv)) return *code;
  const nlohmann::json design = nlohmann::json::parse(design_text);
  const engine::DesignConfig config = engine::read_design_config(fem::load_json_file(file));
  std::vector<double> x = engine::baseline_values(config);
  for (const auto& [name, value] : design.items()) {
    const auto it = std::find_if(config.variables.begin(), config.variables.end(),
                                 [&](const auto& d) { return d.variable.name == name; });
    if (it == config.variables.end()) throw fem::InputError("--design", "'" + name + "' is not a variable of " + file);
    const auto& v = it->variable;
    const std::size_t i = static_cast<std::size_t>(it - config.variables.begin());
    if (v.kind == optimise::VariableKind::categorical) {
      const auto choice = value.is_string() ? std::find(v.choices.begin(), v.choices.end(), value.get<std::string>())
                                            : v.choices.end();
      if (choice == v.choices.end()) throw fem::InputError("--design." + name, value.dump() + " is not one of its choices");
      x[i] = static_cast<double>(choice - v.choices.begin());
    } else {
      if (!value.is_number() || !std::isfinite(value.get<double>()))
        throw fem::InputError("--design." + name, value.dump() + " is not a number");
      x[i] = value.get<double>();
    }
  }
  std::cout << "design: " << engine::describe(config, x) << "\n";
  const objectives::ArmCandidate candidate = engine::make_candidate(config, x);
  const auto t0 = std::chrono::steady_clock::now();
  const objectives::ArmMeasures search = objectives::evaluate_arm(candidate, config.model);
  const double search_s = bench::seconds_since(t0);
  const objectives::CellRodEvaluation cells = objectives::evaluate_arm_on_cells(candidate, config.check, cell_levels);
  if (!cells.ok()) {
    std::cout << "no cells: " << cells.failure << "\n";
    return 1;
  }
  const objectives::ArmMeasures& a = cells.measures;
  std::printf("  %-34s %12s %12s %11s\n", "measure", "search model", "cell rod", "error");
  row("mass (kg)", search.mass_kg, a.mass_kg);
  row("payload (kg)", search.payload_kg, a.payload_kg);
  row("payload lift pressure (kPa)", search.payload_lift_pressure_kPa, a.payload_lift_pressure_kPa);
  for (int n = 0; n < 3; ++n) {
    const std::string name = "segment " + std::to_string(n + 1) + " bending (deg)";
    row(name.c_str(), search.segments[n].bending_deg_at_working, a.segments[n].bending_deg_at_working);
  }
  for (int n = 0; n < 3; ++n) {
    const std::string name = "segment " + std::to_string(n + 1) + " chamber stretch";
    row(name.c_str(), search.segments[n].chamber_stretch, a.segments[n].chamber_stretch);
  }
  row("burst utilisation", search.burst_utilisation, a.burst_utilisation);
  row("durability peak log strain", search.durability_log_strain, a.durability_log_strain);
  std::cout << "search model: " << search.burst_governing << "; payload: " << search.payload_note << "\n";
  std::cout << "cell rod: " << a.burst_governing << "; payload: " << a.payload_note << "\n";
  for (int n = 0; n < 3; ++n)
    std::cout << "  segment " << n + 1 << " cells: " << fem::to_string(cells.segment_outcome[n]) << " at "
              << cells.segment_reached_kPa[n] << " kPa" << (a.segments[n].governing.empty() ? "" : "; burst: " + a.segments[n].governing)
              << "\n";
  std::printf("cost: search model %.2f s; cell rod %.1f s (%d cells, largest %d dofs; %d end cells, largest %d dofs: "
              "%.1f s; %d rod poses: %.2f s); peak RSS %.0f MB\n",
              search_s, a.seconds, cells.cells, cells.largest_cell_dofs, cells.end_cells, cells.largest_end_cell_dofs,
              cells.cell_seconds, cells.poses, cells.pose_seconds, peak_rss_mb());
  if (!cells.notes.empty()) std::cout << "notes:" << cells.notes << "\n";
  return 0;
} catch (const fem::InputError& e) {
  std::fprintf(stderr, "%s\n", e.what());
  return 2;
}

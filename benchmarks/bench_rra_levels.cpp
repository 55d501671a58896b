// Benchmark (not a test): the thesis RRA at every mesh level.
//
// For each level: DOFs, load steps, Newton iterations, time in assembly /
// factorisation / solve and in total (median of --repeat runs), peak memory,
// and the extension at the final pressure with its change from the next finer
// level. With --variants all, the same table for the Q1/P0 (mean dilatation)
// element and for Q1 with pointwise volumetric integration (which locks), to
// justify the element choice.
//
// Usage: bench_rra_levels [config] [--max-level L] [--repeat N] [--threads T] [--variants all]
#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "benchmarks/bench_options.hpp"
#include "benchmarks/bench_stats.hpp"
#include "fem/core/input_error.hpp"
#include "fem/scenes/scene_config.hpp"
#include "fem/core/parallel.hpp"

using namespace softarm;

namespace {
double peak_memory_MiB() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;
}

struct Row {
  int level, elements, dofs, steps, iterations;
  double assembly, factorize, solve, total, extension, reached;
  std::string outcome;
};

Row run_level(fem::RraSceneSpec spec, int level, int repeat) {
  spec.mesh_level = level;
  std::vector<double> assembly, factorize, solve, total;
  fem::RraResult r;
  for (int k = 0; k < repeat; ++k) {
    r = fem::run_rra_scene(spec);
    assembly.push_back(r.timings.assembly_s);
    factorize.push_back(r.path.factorize_s + r.path.analyse_s);
    solve.push_back(r.path.solve_s);
    total.push_back(r.timings.total_s);
  }
  return {level, r.mesh.num_elements(), r.dofs, r.path.path.stats.steps, r.path.path.stats.newton_iterations,
          bench::median(assembly), bench::median(factorize), bench::median(solve), bench::median(total),
          r.curve.empty() ? 0.0 : r.curve.back().extension_mm, r.path.reached_pressure_kPa,
          fem::to_string(r.path.outcome)};
}
}  // namespace

int main(int argc, char** argv) try {
  std::string config = "configs/rra_thesis.json", which = "default";
  int max_level = 5, repeat = 5, threads = 1;
  CLI::App app{"an rra scene (the thesis RRA) at every mesh level"};
  app.add_option("config", config, "an rra scene config");
  app.add_option("--max-level", max_level, "mesh levels 1 to this")->check(CLI::Range(1, 8));
  app.add_option("--repeat", repeat, "runs per level below 5 (the median is printed)")->check(CLI::Range(1, 1000));
  app.add_option("--threads", threads, "threads")->check(CLI::Range(1, 256));
  app.add_option("--variants", which, "all: also Q1/P0 and Q1 with pointwise volumetric integration")
      ->check(CLI::IsMember({"default", "all"}));
  if (const auto code = bench::parse_or_exit(app, argc, argv)) return *code;
  const bool all_variants = which == "all";
  fem::set_thread_count(threads);
  const auto scene = fem::load_scene_config(config);
  std::printf("thesis RRA benchmark: %s, %d thread(s), median of %d runs per level\n", config.c_str(), threads, repeat);
  struct Variant {
    const char* name;
    int order;
    fem::VolumetricTreatment treatment;
  };
  const std::vector<Variant> variants = {
      {"Q2/P1, projected dilatation (default)", 2, fem::VolumetricTreatment::projected_dilatation},
      {"Q1/P0, mean dilatation", 1, fem::VolumetricTreatment::projected_dilatation},
      {"Q1, pointwise volumetric integration (locks)", 1, fem::VolumetricTreatment::pointwise}};
  for (const auto& variant : variants) {
    if (&variant != &variants.front() && !all_variants) break;
    auto spec = scene.rra;
    spec.element_order = variant.order;
    spec.treatment = variant.treatment;
    std::printf("\nelement: %s\n", variant.name);
    std::printf("level elements   dofs steps newton  assembly_s factor_s solve_s  total_s  peak_MiB  ext_mm@%.1fkPa  outcome\n",
                spec.path.max_pressure_kPa);
    std::vector<Row> rows;
    for (int level = 1; level <= max_level; ++level) {
      rows.push_back(run_level(spec, level, level >= 5 ? 1 : repeat));
      const Row& r = rows.back();
      std::printf("%5d %8d %6d %5d %6d  %10.4f %8.4f %7.4f %8.4f %9.1f  %12.5f  %s\n", r.level, r.elements, r.dofs, r.steps,
                  r.iterations, r.assembly, r.factorize, r.solve, r.total, peak_memory_MiB(), r.extension, r.outcome.c_str());
      std::fflush(stdout);
    }
    std::printf("change of the extension from the next finer level:\n");
    for (std::size_t k = 0; k + 1 < rows.size(); ++k)
      std::printf("  level %d -> %d: %+.4f %%\n", rows[k].level, rows[k + 1].level,
                  100.0 * (rows[k].extension - rows[k + 1].extension) / rows[k + 1].extension);
    std::printf("  level %d vs finest (%d): %+.4f %%\n", spec.mesh_level, rows.back().level,
                100.0 * (rows[std::min<std::size_t>(spec.mesh_level, rows.size()) - 1].extension - rows.back().extension) /
                    rows.back().extension);
  }
  return 0;
} catch (const fem::InputError& e) {
  std::fprintf(stderr, "%s\n", e.what());
  return 2;
}

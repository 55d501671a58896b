// Benchmark (not a test): do the burst and durability peaks converge under mesh refinement?
//
// The thesis RRA (or any rra scene) at mesh levels 1..L, at its final pressure: the pointwise
// peaks of the tube (largest principal stretch, Cauchy stress and log strain over every Gauss
// point, which sit at the groove lip's bi-material corner) beside their averages over balls of
// fixed radius (fem/post/region_average.hpp), with each one's change from the next finer level.
//
// Usage: bench_peak_convergence [config] [--max-level L] [--pressure-kPa P] [--radii r1,r2,...]
#include <cstdio>
#include <string>
#include <vector>

#include "benchmarks/bench_options.hpp"
#include "fem/core/input_error.hpp"
#include "fem/post/region_average.hpp"
#include "fem/scenes/scene_config.hpp"

using namespace softarm;

namespace {
struct Peaks {
  double stretch = 0, stress = 0, log_strain = 0;
};

Peaks pointwise(const fem::RraResult& r, int tube) {
  Peaks p;
  for (int e = 0; e < r.mesh.num_elements(); ++e)
    if (r.mesh.part[e] == tube) {
      const auto& q = r.final_element_results[e];
      p.stretch = std::max(p.stretch, q.max_principal_stretch);
      p.stress = std::max(p.stress, q.max_principal_cauchy_MPa);
      p.log_strain = std::max(p.log_strain, q.max_principal_log_strain);
    }
  return p;
}

Peaks averaged(const fem::RraResult& r, int tube, double radius) {
  std::vector<double> s, t, l;
  for (const auto& q : r.final_element_results) {
    s.push_back(q.mean_principal_stretch);
    t.push_back(q.mean_principal_cauchy_MPa);
    l.push_back(q.mean_principal_log_strain);
  }
  return {fem::max_region_average(r.mesh, s, tube, radius).value, fem::max_region_average(r.mesh, t, tube, radius).value,
          fem::max_region_average(r.mesh, l, tube, radius).value};
}

double change(double coarse, double fine) { return 100.0 * (coarse - fine) / fine; }
}  // namespace

int main(int argc, char** argv) try {
  std::string config = "configs/rra_thesis.json";
  int max_level = 3;
  double pressure = -1;
  std::vector<double> radii = {0.25, 0.5, 1.0};
  CLI::App app{"do the burst and durability peaks of an rra scene converge under mesh refinement?"};
  app.add_option("config", config, "an rra scene config");
  app.add_option("--max-level", max_level, "mesh levels 1 to this")->check(CLI::Range(1, 8));
  app.add_option("--pressure-kPa", pressure, "the final pressure")->check(bench::Positive)->default_str("the config's");
  app.add_option("--radii", radii, "radii of the balls the peaks are averaged over (mm)")
      ->delimiter(',')
      ->check(bench::Positive);
  if (const auto code = bench::parse_or_exit(app, argc, argv)) return *code;
  auto spec = fem::load_scene_config(config).rra;
  if (pressure > 0) {
    spec.path.max_pressure_kPa = pressure;
    spec.path.output_pressures_kPa = {pressure};
  }
  std::printf("peak convergence: %s at %.1f kPa, mesh levels 1..%d\n", config.c_str(), spec.path.max_pressure_kPa,
              max_level);
  std::printf("%-22s", "measure");
  for (int level = 1; level <= max_level; ++level) std::printf("   level %d", level);
  for (int level = 1; level < max_level; ++level) std::printf("  %d->%d %%", level, level + 1);
  std::printf("\n");
  std::vector<std::vector<Peaks>> rows(1 + radii.size());
  std::vector<double> reached;
  for (int level = 1; level <= max_level; ++level) {
    spec.mesh_level = level;
    const auto r = fem::run_rra_scene(spec);
    const int tube = r.mesh.part_index("tube");
    reached.push_back(r.path.reached_pressure_kPa);
    rows[0].push_back(pointwise(r, tube));
    for (std::size_t k = 0; k < radii.size(); ++k) rows[k + 1].push_back(averaged(r, tube, radii[k]));
  }
  auto print = [&](const std::string& name, auto get) {
    for (std::size_t k = 0; k < rows.size(); ++k) {
      char label[64];
      if (k == 0) std::snprintf(label, sizeof label, "%s, pointwise", name.c_str());
      else std::snprintf(label, sizeof label, "%s, ball %.2f mm", name.c_str(), radii[k - 1]);
      std::printf("%-22s", label);
      for (const auto& p : rows[k]) std::printf("  %8.4f", get(p));
      for (std::size_t l = 0; l + 1 < rows[k].size(); ++l) std::printf("  %+7.2f", change(get(rows[k][l]), get(rows[k][l + 1])));
      std::printf("\n");
    }
  };
  print("stretch", [](const Peaks& p) { return p.stretch; });
  print("stress MPa", [](const Peaks& p) { return p.stress; });
  print("log strain", [](const Peaks& p) { return p.log_strain; });
  std::printf("pressure reached (kPa):");
  for (double p : reached) std::printf(" %.1f", p);
  std::printf("\n");
  return 0;
} catch (const fem::InputError& e) {
  std::fprintf(stderr, "%s\n", e.what());
  return 2;
}

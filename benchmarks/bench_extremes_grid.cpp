// Benchmark (not a test): the lone RRA over the corners and edges of the design bounds, every
// built-in silicone, two pressures, at RRA mesh levels 1 and 2 (issue 38).
//
// Grid: wall t_w/r_b ∈ {0.1, 0.5, 0.9}, end cap t_c/r_b ∈ {0.05, 0.525, 1.0} (and 0.1 at the
// corners), ring thickness ∈ {0.15, 0.55, 0.95}: the 8 corners and 12 edge midpoints of that box
// plus the 4 corners with caps of 0.1, on the thesis RRA (configs/rra_thesis.json) in Dragon
// Skin 10, 20 and 30, to 206.8 and 400 kPa. Prints one row per run that does not complete, the
// count of each outcome per level (completed, limit point by how it was found, stalled, refused as
// invalid input), the time, and each limit pressure's change from level 1 to level 2.
//
// Usage: bench_extremes_grid [--max-level L]
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "fem/core/input_error.hpp"
#include "fem/core/json_reader.hpp"
#include "fem/scenes/scene_config.hpp"

using namespace softarm;

namespace {
struct Case {
  double wall, cap, ring;
  std::string material;
  double pressure_kPa;
  std::string name() const {
    char b[128];
    std::snprintf(b, sizeof b, "wall %.2f cap %.3f ring %.2f %s %.1f kPa", wall, cap, ring, material.c_str(),
                  pressure_kPa);
    return b;
  }
};

std::vector<Case> grid() {
  const double w[3] = {0.1, 0.5, 0.9}, c[3] = {0.05, 0.525, 1.0}, d[3] = {0.15, 0.55, 0.95};
  std::vector<std::array<double, 3>> shapes;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        if ((i != 1) + (j != 1) + (k != 1) >= 2) shapes.push_back({w[i], c[j], d[k]});  // corners and edge midpoints
  for (int i : {0, 2})
    for (int k : {0, 2}) shapes.push_back({w[i], 0.1, d[k]});
  std::vector<Case> out;
  for (const char* m : {"dragon_skin_10", "dragon_skin_20", "dragon_skin_30"})
    for (double p : {206.8, 400.0})
      for (const auto& s : shapes) out.push_back({s[0], s[1], s[2], m, p});
  return out;
}

struct Outcome {
  std::string kind;  // completed, limit_point, stalled, refused
  std::string found_by;  // a limit point's fem::LimitKind (traced, pressure_volume, lowest_mode, fold)
  double limit_kPa = NAN, reached_kPa = NAN, seconds = 0;
  std::string words;
};

Outcome run(const Case& c, int level) {
  nlohmann::json s = fem::load_json_file("configs/rra_thesis.json");
  s["geometry"]["wall_thickness_normalised"] = c.wall;
  s["geometry"]["end_cap_thickness_normalised"] = c.cap;
  s["geometry"]["ring_thickness_normalised"] = c.ring;
  s["materials"]["tube"] = c.material;
  s["mesh"] = {{"level", level}, {"element_order", 2}};
  s["load"] = {{"max_pressure_kPa", c.pressure_kPa}, {"output_count", 4}};
  Outcome o;
  const auto t0 = std::chrono::steady_clock::now();
  try {
    const auto r = fem::run_rra_scene(fem::read_scene_config(s).rra);
    o.kind = fem::to_string(r.path.outcome);
    o.reached_kPa = r.path.reached_pressure_kPa;
    if (r.path.outcome == fem::PathOutcome::limit_point) {
      o.limit_kPa = r.path.estimated_limit_pressure_kPa;
      o.found_by = fem::to_string(r.path.limit_kind);
    }
    o.words = r.path.diagnosis;
  } catch (const fem::InputError& e) {
    o.kind = "refused";
    o.words = e.what();
  }
  o.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return o;
}
}  // namespace

int main(int argc, char** argv) {
  int max_level = 2;
  for (int i = 1; i + 1 < argc; ++i)
    if (!std::strcmp(argv[i], "--max-level")) max_level = std::atoi(argv[++i]);
  const auto cases = grid();
  std::vector<std::vector<Outcome>> results(max_level);
  for (int level = 1; level <= max_level; ++level) {
    std::map<std::string, int> count;
    double total = 0;
    std::printf("\nRRA mesh level %d: %zu runs\n", level, cases.size());
    for (const Case& c : cases) {
      const Outcome o = run(c, level);
      results[level - 1].push_back(o);
      ++count[o.found_by.empty() ? o.kind : o.kind + " (" + o.found_by + ")"];
      total += o.seconds;
      if (o.kind != "completed")
        std::printf("  %-52s %-11s reached %6.1f kPa  limit %6.1f kPa  %5.1f s  %.160s\n", c.name().c_str(),
                    o.kind.c_str(), o.reached_kPa, o.limit_kPa, o.seconds, o.words.c_str());
      std::fflush(stdout);
    }
    std::printf("level %d outcomes:", level);
    for (const auto& [kind, n] : count) std::printf("  %s %d", kind.c_str(), n);
    std::printf("  (%.1f s in all)\n", total);
  }
  if (max_level >= 2) {
    std::printf("\nlimit pressures, level 1 -> 2:\n");
    double worst = 0;
    for (std::size_t k = 0; k < cases.size(); ++k) {
      const Outcome &a = results[0][k], &b = results[1][k];
      if (a.kind != "limit_point" && b.kind != "limit_point") continue;
      const double change = 100 * (a.limit_kPa - b.limit_kPa) / b.limit_kPa;
      if (std::isfinite(change)) worst = std::max(worst, std::abs(change));
      std::printf("  %-52s %-11s %7.1f  %-11s %7.1f kPa  %+6.2f %%\n", cases[k].name().c_str(), a.kind.c_str(),
                  a.limit_kPa, b.kind.c_str(), b.limit_kPa, change);
    }
    std::printf("largest change of a limit pressure found at both levels: %.2f %%\n", worst);
  }
  return 0;
}

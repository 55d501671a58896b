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
// Every run is appended to a results file as it ends (one CSV row: level, case, outcome, how a
// limit point was found, pressures, seconds); a rerun with the same file skips the runs it holds
// and prints the tables from all of them, so an interrupted grid resumes where it stopped.
// Runs go side by side, one thread each (--threads, SOFTARM_THREADS; the rows' order is the
// grid's whatever the threads).
//
// Usage: bench_extremes_grid [--levels 1,2] [--match TEXT ...] [--results FILE] [--threads N]
//   --levels: the RRA mesh levels to run (1 to 3); each level's limit pressures are compared with the
//   next one's. --match: only the cases whose name holds one of these texts ("wall 0.90 cap 1.000"),
//   e.g. to run level 3 where levels 1 and 2 differ. --held-only: run nothing, print the tables of
//   the runs held (a case not held counts as "not run").
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

#include "benchmarks/bench_options.hpp"
#include "benchmarks/bench_stats.hpp"
#include "fem/core/input_error.hpp"
#include "fem/core/json_reader.hpp"
#include "fem/core/parallel.hpp"
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
  std::string kind = "not run";  // completed, limit_point, stalled, refused
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
  o.seconds = bench::seconds_since(t0);
  return o;
}

/// The results file: one row per run, "level,case,kind,found_by,reached_kPa,limit_kPa,seconds"
/// (the case's name has no comma; the diagnosis is not kept).
std::string row(int level, const Case& c, const Outcome& o) {
  std::ostringstream r;
  r.precision(10);
  r << level << ',' << c.name() << ',' << o.kind << ',' << o.found_by << ',' << o.reached_kPa << ',' << o.limit_kPa
    << ',' << o.seconds;
  return r.str();
}

std::map<std::pair<int, std::string>, Outcome> read_results(const std::string& file) {
  std::map<std::pair<int, std::string>, Outcome> done;
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
    if (f.size() != 7) continue;  // a torn last line: that run is done again
    Outcome o;
    o.kind = f[2];
    o.found_by = f[3];
    o.reached_kPa = std::stod(f[4]);
    o.limit_kPa = std::stod(f[5]);
    o.seconds = std::stod(f[6]);
    done[{std::stoi(f[0]), f[1]}] = o;
  }
  return done;
}
}  // namespace

int main(int argc, char** argv) try {
  CLI::App app{"the lone RRA over the corners and edges of the design bounds (issue 38)"};
  std::vector<int> levels{1, 2};
  std::vector<std::string> matches;
  std::string results_file = "bench_extremes_grid.csv";
  int threads = fem::thread_count();
  bool held_only = false;
  app.add_option("--levels", levels, "RRA mesh levels to run, compared pairwise")->delimiter(',')->check(CLI::Range(1, 3));
  app.add_option("--match", matches, "only the cases whose name holds one of these texts");
  app.add_option("--results", results_file, "results file: appended to as runs end, read to resume");
  app.add_option("--threads", threads, "runs side by side")->check(CLI::Range(1, 256));
  app.add_flag("--held-only", held_only, "run nothing: the tables of the runs the results file holds");
  if (const auto code = bench::parse_or_exit(app, argc, argv)) return *code;
  fem::set_thread_count(threads);
  std::sort(levels.begin(), levels.end());
  levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
  const auto chosen = [&](const Case& c) {
    return matches.empty() || std::any_of(matches.begin(), matches.end(), [&](const std::string& m) {
             return c.name().find(m) != std::string::npos;
           });
  };
  const auto cases = grid();
  auto done = read_results(results_file);
  std::ofstream results(results_file, std::ios::app);
  std::mutex results_mutex;
  std::printf("results: %s (%zu runs held; %d threads)\n", results_file.c_str(), done.size(), fem::thread_count());
  std::map<int, std::vector<Outcome>> outcomes;
  for (const int level : levels) {
    outcomes[level].resize(cases.size());
    std::vector<int> todo;
    for (std::size_t k = 0; k < cases.size(); ++k) {
      if (!chosen(cases[k])) continue;
      const auto held = done.find({level, cases[k].name()});
      if (held != done.end()) outcomes[level][k] = held->second;
      else if (!held_only) todo.push_back(static_cast<int>(k));
    }
    const auto n_chosen = std::count_if(cases.begin(), cases.end(), chosen);
    std::printf("\nRRA mesh level %d: %ld runs, %zu of them to do\n", level, static_cast<long>(n_chosen), todo.size());
    std::fflush(stdout);
    fem::parallel_tasks(static_cast<int>(todo.size()), [&](int i) {
      const int k = todo[static_cast<std::size_t>(i)];
      const Outcome o = run(cases[k], level);
      const std::lock_guard<std::mutex> lock(results_mutex);
      outcomes[level][k] = o;
      results << row(level, cases[k], o) << std::endl;  // flushed: a stop loses at most the runs under way
      if (o.kind != "completed")
        std::printf("  %-52s %-11s reached %6.1f kPa  limit %6.1f kPa  %5.1f s  %.160s\n", cases[k].name().c_str(),
                    o.kind.c_str(), o.reached_kPa, o.limit_kPa, o.seconds, o.words.c_str());
      std::fflush(stdout);
    });
    std::map<std::string, int> count;
    double total = 0;
    for (std::size_t k = 0; k < cases.size(); ++k) {
      if (!chosen(cases[k])) continue;
      const Outcome& o = outcomes[level][k];
      ++count[o.found_by.empty() ? o.kind : o.kind + " (" + o.found_by + ")"];
      total += o.seconds;
    }
    std::printf("level %d outcomes:", level);
    for (const auto& [kind, n] : count) std::printf("  %s %d", kind.c_str(), n);
    std::printf("  (%.1f s of runs in all)\n", total);
  }
  for (std::size_t l = 0; l + 1 < levels.size(); ++l) {
    const int coarse = levels[l], fine = levels[l + 1];
    std::printf("\nlimit pressures, level %d -> %d:\n", coarse, fine);
    double worst = 0;
    for (std::size_t k = 0; k < cases.size(); ++k) {
      const Outcome &a = outcomes[coarse][k], &b = outcomes[fine][k];
      if (!chosen(cases[k]) || (a.kind != "limit_point" && b.kind != "limit_point")) continue;
      const double change = 100 * (a.limit_kPa - b.limit_kPa) / b.limit_kPa;
      if (std::isfinite(change)) worst = std::max(worst, std::abs(change));
      std::printf("  %-52s %-11s %7.1f  %-11s %7.1f kPa  %+6.2f %%\n", cases[k].name().c_str(), a.kind.c_str(),
                  a.limit_kPa, b.kind.c_str(), b.limit_kPa, change);
    }
    std::printf("largest change of a limit pressure found at both levels: %.2f %%\n", worst);
  }
  return 0;
} catch (const fem::InputError& e) {  // configs/rra_thesis.json cannot be read (run from the repository root)
  std::fprintf(stderr, "%s\n", e.what());
  return 2;
}

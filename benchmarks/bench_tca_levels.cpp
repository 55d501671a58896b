// Benchmark (not a test): the thesis 3CA bending scene at chosen mesh levels
// and element orders. Each run is a separate process (fork) so that its peak
// memory is its own. For each: model (half/full), DOFs, load steps, Newton
// iterations, factorisations, time in assembly / factorisation and in total,
// peak memory, the pressure reaching the target bending angle and the bending
// angle and tip position at the peak pressure. Where three or more runs differ only
// in their element layers (mesh.axial_level), the three finest are extrapolated to
// infinitely many layers (fem/post/richardson.hpp) with their observed order.
//
// Usage: bench_tca_levels [config] [--runs 1:2,2:1,20:1,20r:1/2 (element:level[/axial level];
//        element 1 = Hex8, 2 = Hex27, 20 = Hex20, 20r = Hex20 at 2×2×2 points; the axial level,
//        mesh.axial_level, refines along the axis alone)] [--repeat N] [--threads T]
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <regex>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "benchmarks/bench_options.hpp"
#include "fem/core/input_error.hpp"
#include "fem/scenes/scene_config.hpp"
#include "fem/core/parallel.hpp"
#include "fem/mesh/tca_mesher.hpp"
#include "fem/post/richardson.hpp"

using namespace softarm;

namespace {
double peak_memory_MiB() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;
}

// What a run hands back to the parent (through a pipe: each run is its own process).
struct RunResult {
  int element = 0, reduced = 0, level = 0, layers = 0;
  double target_kPa = -1;             // −1: the target bending was not reached
  double angle_deg = 0, at_kPa = 0;   // at the peak pressure
};

void run_one(fem::TcaSceneSpec spec, int element, bool reduced, int level, int axial_level, int repeat, int fd) {
  spec.element_order = element == 1 ? 1 : 2;
  spec.serendipity = element == 20;
  spec.integration = reduced ? fem::ElementIntegration::reduced : fem::ElementIntegration::full;
  spec.mesh_level = level;
  spec.axial_level = axial_level;
  std::vector<double> totals;
  fem::TcaResult r;
  for (int k = 0; k < repeat; ++k) {
    r = fem::run_tca_scene(spec);
    totals.push_back(r.timings.total_s);
  }
  std::sort(totals.begin(), totals.end());
  const auto& last = r.curve.back();
  std::printf("%6s %5d %5d %-5s %8d %5d %6d %6d %9.2f %9.2f %9.2f %8.0f %10s %9.3f %9.2f %8.2f %8.2f  %s\n",
              element == 1 ? "Hex8" : element == 2 ? "Hex27" : reduced ? "Hex20R" : "Hex20", level,
              fem::layers_level(level, axial_level), r.model.half ? "half" : "full", r.dofs, r.path.path.stats.steps,
              r.path.path.stats.newton_iterations, r.path.factorizations, r.timings.assembly_s, r.timings.factorize_s,
              totals[totals.size() / 2], peak_memory_MiB(),
              r.target_pressure_kPa ? std::to_string(*r.target_pressure_kPa).substr(0, 7).c_str() : "-",
              last.bending_angle_deg, last.pressure_kPa, last.tip_position_mm.x(), last.tip_position_mm.z(),
              fem::to_string(r.path.outcome));
  std::fflush(stdout);
  const RunResult out{element, reduced, level, fem::layers_level(level, axial_level),
                      r.target_pressure_kPa.value_or(-1.0), last.bending_angle_deg, last.pressure_kPa};
  if (write(fd, &out, sizeof out) != static_cast<ssize_t>(sizeof out)) std::perror("bench_tca_levels: pipe");
}

// Richardson extrapolation over the element layers: runs with the same element and
// cross-section, the layers' level standing for 1/h (layers per band ∝ level).
void print_layer_extrapolations(std::vector<RunResult> runs) {
  std::sort(runs.begin(), runs.end(), [](const RunResult& a, const RunResult& b) {
    return std::tie(a.element, a.reduced, a.level, a.layers) < std::tie(b.element, b.reduced, b.level, b.layers);
  });
  for (std::size_t end = runs.size(); end >= 3;) {
    const RunResult& f = runs[end - 1];
    std::size_t begin = end;
    while (begin > 0 && runs[begin - 1].element == f.element && runs[begin - 1].reduced == f.reduced &&
           runs[begin - 1].level == f.level)
      --begin;
    const RunResult &a = runs[end - 3], &b = runs[end - 2], &c = runs[end - 1];
    if (end - begin >= 3 && a.layers < b.layers && b.layers < c.layers) {  // a repeated run is no refinement
      std::printf("layers %d, %d, %d extrapolated (element %d%s, level %d):", a.layers, b.layers, c.layers, f.element,
                  f.reduced ? "r" : "", f.level);
      const auto print = [&](const char* what, double fa, double fb, double fc) {
        const auto e = fem::richardson_extrapolate(1.0 / a.layers, fa, 1.0 / b.layers, fb, 1.0 / c.layers, fc);
        if (e) std::printf(" %s %.3f (order %.2f, finest %.2f %% off)", what, e->limit, e->order,
                           100 * e->finest_error / std::abs(e->limit));
        else std::printf(" %s: not monotone, no extrapolation", what);
      };
      if (a.target_kPa > 0 && b.target_kPa > 0 && c.target_kPa > 0)
        print("p_target_kPa", a.target_kPa, b.target_kPa, c.target_kPa);
      if (a.at_kPa == b.at_kPa && b.at_kPa == c.at_kPa) print("angle_deg", a.angle_deg, b.angle_deg, c.angle_deg);
      std::printf("\n");
    }
    end = begin;
  }
}
}  // namespace

int main(int argc, char** argv) try {
  std::string config = "configs/tca_thesis.json";
  std::vector<std::string> runs{"2:1"};
  int repeat = 1, threads = fem::thread_count();
  CLI::App app{"a tca scene (the thesis 3CA bending) at chosen mesh levels and element orders, each run in its own process"};
  app.add_option("config", config, "a tca scene config");
  app.add_option("--runs", runs,
                 "element:level[/axial level]; element 1 = Hex8, 2 = Hex27, 20 = Hex20, 20r = Hex20 at 2x2x2 points; "
                 "the axial level (mesh.axial_level) refines along the axis alone")
      ->delimiter(',')
      ->check(CLI::Validator(
          [](std::string& run) {
            static const std::regex form("(1|2|20|20r):[1-8](/[1-8])?");
            return std::regex_match(run, form) ? std::string() : "run '" + run + "' is not element:level[/axial level] "
                                                                 "(element 1, 2, 20 or 20r; levels 1 to 8)";
          },
          "RUN"));
  app.add_option("--repeat", repeat, "runs of each (the median time is printed)")->check(CLI::Range(1, 1000));
  app.add_option("--threads", threads, "threads")->check(CLI::Range(1, 256));
  if (const auto code = bench::parse_or_exit(app, argc, argv)) return *code;
  fem::set_thread_count(threads);
  const auto scene = fem::load_scene_config(config);
  if (scene.scene != "tca") {
    std::fprintf(stderr, "bench_tca_levels: %s is not a tca scene\n", config.c_str());
    return 2;
  }
  std::printf("%s, threads %d, time = median of %d\n", config.c_str(), fem::thread_count(), repeat);
  std::printf("%6s %5s %5s %-5s %8s %5s %6s %6s %9s %9s %9s %8s %10s %9s %9s %8s %8s  %s\n", "elem", "level", "axial", "model",
              "dofs", "steps", "newton", "factor", "assemb_s", "factor_s", "total_s", "peak_MiB", "p_target",
              "angle_deg", "at_kPa", "tip_x", "tip_z", "outcome");
  std::vector<RunResult> results;
  for (const std::string& item : runs) {
    const int element = std::atoi(item.c_str()), level = std::atoi(item.c_str() + item.find(':') + 1);
    const bool reduced = item.find('r') != std::string::npos && item.find('r') < item.find(':');
    const auto slash = item.find('/');
    const int axial_level = slash == std::string::npos ? 0 : std::atoi(item.c_str() + slash + 1);
    if ((element != 1 && element != 2 && element != 20) || (reduced && element != 20)) {
      std::fprintf(stderr, "bench_tca_levels: run '%s': element must be 1, 2, 20 or 20r\n", item.c_str());
      return 2;
    }
    std::fflush(stdout);  // else the child inherits, and prints again, what the parent has buffered
    int fds[2];
    if (pipe(fds) != 0) {
      std::perror("bench_tca_levels: pipe");
      return 1;
    }
    const pid_t child = fork();
    if (child == 0) {
      close(fds[0]);
      run_one(scene.tca, element, reduced, level, axial_level, repeat, fds[1]);
      std::_Exit(0);
    }
    close(fds[1]);
    RunResult r;
    if (read(fds[0], &r, sizeof r) == static_cast<ssize_t>(sizeof r)) results.push_back(r);
    close(fds[0]);
    int status = 0;
    waitpid(child, &status, 0);
  }
  print_layer_extrapolations(results);
  return 0;
} catch (const fem::InputError& e) {
  std::fprintf(stderr, "%s\n", e.what());
  return 2;
}

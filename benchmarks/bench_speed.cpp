// The main scenes' speed in one run (docs/performance.md, "The main scenes in one run"): the
// thesis RRA's curve on one thread, the 3CA default, one SPL segment's cells as the design's check
// of a segment runs them (its 3CA cell rod), and the SPL default, each with its wall time (the
// median of --repeat runs), unknowns, Newton iterations, factorisations (with the shifted Cholesky
// attempts and the LUs), CG iterations and peak memory; then the 3D solves at three sizes against
// CalculiX at equal tolerance (bench_ccx_3d, beside this binary, which prints the ratio).
//
// Each run is a process of its own (this binary again, with --item), so that its peak memory is its
// own and no run warms the next one's caches or allocator. A cell rod's unknowns and counts are its
// cells' and end cells' summed (fem/scenes/solver_work.hpp): they are the same on every run of a
// config; the times are not (a shared machine), hence the median. For a cell rod also its cells'
// own seconds summed (work_s), the slowest cell's (longest_s) and the least time its cells can take
// on the threads given, max(longest_s, work_s / threads) (bound_s): each cell is one path on one
// thread, so no balance of the cells over the threads ends a run sooner.
//
//   bench_speed [--items rra,tca,segment,spl,3d] [--repeat 3] [--threads N]
//               [--rra configs/rra_thesis.json] [--tca configs/tca_thesis.json]
//               [--spl configs/spl_thesis_pose.json] [--segment 1] [--lengths 32,64,128]
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "benchmarks/bench_options.hpp"
#include "benchmarks/bench_stats.hpp"
#include "fem/core/input_error.hpp"
#include "fem/core/parallel.hpp"
#include "fem/scenes/rra_scene.hpp"
#include "fem/scenes/scene_config.hpp"
#include "fem/scenes/solver_work.hpp"
#include "fem/scenes/spl_cell_rod.hpp"
#include "fem/scenes/spl_scene.hpp"
#include "fem/scenes/tca_cell_rod.hpp"
#include "fem/scenes/tca_scene.hpp"

using namespace softarm;

namespace {

struct Options {
  std::vector<std::string> items = {"rra", "tca", "segment", "spl", "3d"};
  int repeat = 3, threads = fem::thread_count(), segment = 1;
  std::string rra = "configs/rra_thesis.json", tca = "configs/tca_thesis.json", spl = "configs/spl_thesis_pose.json";
  std::vector<double> lengths = {32, 64, 128};
  std::string item;  // a child's one run
};

/// One run's figures, as a child prints them on its last line and the parent reads them back.
struct Figures {
  std::string model;
  fem::SolverWork work;
  double seconds = 0;
  std::string outcome;
};

fem::SceneConfig scene(const std::string& file, const std::string& kind) {
  fem::SceneConfig s = fem::load_scene_config(file);
  if (s.scene != kind) throw fem::InputError(file, "a \"" + s.scene + "\" scene, not \"" + kind + "\"");
  return s;
}

Figures run_item(const Options& o) {
  Figures f;
  std::chrono::steady_clock::time_point t0;
  if (o.item == "rra") {
    const fem::RraSceneSpec spec = scene(o.rra, "rra").rra;
    fem::set_thread_count(1);  // the thesis RRA's curve on one core
    t0 = std::chrono::steady_clock::now();
    const fem::RraResult r = fem::run_rra_scene(spec);
    f.work.add(r.path, r.dofs, 0);
    f.model = "axisymmetric FEM, 1 thread";
    f.outcome = fem::to_string(r.path.outcome);
  } else if (o.item == "tca" || o.item == "segment") {
    fem::TcaSceneSpec spec;
    bool cell_rod = true;
    if (o.item == "tca") {
      const fem::SceneConfig c = scene(o.tca, "tca");
      spec = c.tca;
      cell_rod = c.cell_rod;
    } else {
      spec = fem::spl_segment_cell_scene(scene(o.spl, "spl").spl, o.segment - 1, fem::kDefaultCellLevels);
    }
    t0 = std::chrono::steady_clock::now();
    if (cell_rod) {
      const fem::CellRodTcaResult r = fem::run_cell_rod_tca(spec);
      f.work = r.work;
      f.model = "cell rod, " + std::to_string(r.work.paths) + " cells";
      f.outcome = fem::to_string(r.outcome);
    } else {
      const fem::TcaResult r = fem::run_tca_scene(spec);
      f.work.add(r.path, r.dofs, 0);
      f.model = "3D FEM";
      f.outcome = fem::to_string(r.path.outcome);
    }
  } else if (o.item == "spl") {
    const fem::SceneConfig c = scene(o.spl, "spl");
    t0 = std::chrono::steady_clock::now();
    if (c.cell_rod) {
      const fem::SplCells cells = fem::spl_cells(c.spl);
      const fem::SplCellRodResult r = fem::pose_spl_cell_rod(cells, c.spl.output_levels);
      f.work = cells.work;
      f.model = "cell rod, " + std::to_string(cells.work.paths) + " cells";
      f.outcome = fem::to_string(r.outcome);
    } else {
      const fem::SplResult r = fem::run_spl_scene(c.spl);
      f.work.add(r.path, r.dofs, 0);
      f.model = "3D FEM";
      f.outcome = fem::to_string(r.path.outcome);
    }
  }
  f.seconds = bench::seconds_since(t0);
  return f;
}

/// A table cell of seconds, 9 wide: "-" for none (negative).
std::string format_seconds(double s) {
  char text[32];
  if (s < 0)
    std::snprintf(text, sizeof text, "%9s", "-");
  else
    std::snprintf(text, sizeof text, "%9.3f", s);
  return text;
}

/// The child's last line: the figures, tab-separated.
void print_figures(const Figures& f) {
  const fem::SolverWork& w = f.work;
  std::printf("FIGURES\t%s\t%lld\t%.6f\t%d\t%d\t%d\t%d\t%d\t%.6f\t%.6f\t%s\n", f.model.c_str(), w.dofs, f.seconds,
              w.newton_iterations, w.factorizations, w.shifted_factorizations, w.lu_fallbacks, w.cg_iterations, w.seconds,
              w.longest_seconds, f.outcome.c_str());
}

bool parse_figures(const std::string& output, Figures& f) {
  const auto at = output.rfind("FIGURES\t");
  if (at == std::string::npos) return false;
  std::stringstream line(output.substr(at + 8));
  std::vector<std::string> field;
  for (std::string s; std::getline(line, s, '\t');) field.push_back(s);
  if (field.size() < 11) return false;
  f.model = field[0];
  f.work.dofs = std::stoll(field[1]);
  f.seconds = std::stod(field[2]);
  f.work.newton_iterations = std::stoi(field[3]);
  f.work.factorizations = std::stoi(field[4]);
  f.work.shifted_factorizations = std::stoi(field[5]);
  f.work.lu_fallbacks = std::stoi(field[6]);
  f.work.cg_iterations = std::stoi(field[7]);
  f.work.seconds = std::stod(field[8]);
  f.work.longest_seconds = std::stod(field[9]);
  f.outcome = field[10].substr(0, field[10].find('\n'));
  return true;
}

/// `argv` run as a child process: its standard output, and its peak resident memory in MB.
std::string run_child(const std::vector<std::string>& argv, double& peak_mb, int& status) {
  int pipe_fds[2];
  if (pipe(pipe_fds) != 0) throw std::runtime_error("bench_speed: no pipe");
  const pid_t pid = fork();
  if (pid == 0) {
    dup2(pipe_fds[1], STDOUT_FILENO);
    close(pipe_fds[0]);
    close(pipe_fds[1]);
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execv(args[0], args.data());
    _exit(127);
  }
  close(pipe_fds[1]);
  std::string output;
  char buffer[4096];
  for (ssize_t n; (n = read(pipe_fds[0], buffer, sizeof buffer)) > 0;) output.append(buffer, static_cast<std::size_t>(n));
  close(pipe_fds[0]);
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  peak_mb = usage.ru_maxrss / 1024.0;  // kB on Linux
  return output;
}

std::string joined(const std::vector<double>& v) {
  std::string s;
  for (double x : v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", x);
    s += (s.empty() ? "" : ",") + std::string(text);
  }
  return s;
}

}  // namespace

int main(int argc, char** argv) try {
  Options o;
  CLI::App app{"the main scenes' time, unknowns, Newton iterations, factorisations and peak memory in one run, "
               "and the 3D solves against CalculiX"};
  app.add_option("--items", o.items, "what to run, in this order")
      ->delimiter(',')
      ->check(CLI::IsMember({"rra", "tca", "segment", "spl", "3d"}));
  app.add_option("--repeat", o.repeat, "runs of each item (the median time is printed)")->check(CLI::Range(1, 100));
  app.add_option("--threads", o.threads, "threads of the 3CA, segment and SPL runs (the RRA runs on one)")
      ->check(CLI::Range(1, 256));
  app.add_option("--rra", o.rra, "the RRA config")->check(CLI::ExistingFile);
  app.add_option("--tca", o.tca, "the 3CA config")->check(CLI::ExistingFile);
  app.add_option("--spl", o.spl, "the SPL config (also the segment's)")->check(CLI::ExistingFile);
  app.add_option("--segment", o.segment, "the SPL's segment whose cells are run (1: proximal)")->check(CLI::Range(1, 3));
  app.add_option("--lengths", o.lengths, "the 3D solves' actuator lengths (bench_ccx_3d --lengths)")
      ->delimiter(',')
      ->check(bench::Positive);
  app.add_option("--item", o.item, "(internal) run one item once and print its figures")
      ->check(CLI::IsMember({"rra", "tca", "segment", "spl"}));
  if (const auto code = bench::parse_or_exit(app, argc, argv)) return *code;
  fem::set_thread_count(o.threads);
  if (!o.item.empty()) {
    print_figures(run_item(o));
    return 0;
  }
  const std::string self = std::filesystem::read_symlink("/proc/self/exe").string();
  std::printf("bench_speed: %d threads (the RRA one), %d run(s) of each item, medians\n", o.threads, o.repeat);
  std::printf("%-8s %-28s %10s %10s %9s %9s %8s %9s %9s %8s %6s %8s %9s  %s\n", "item", "model", "unknowns", "time_s",
              "work_s", "longest_s", "bound_s", "Newton", "factorise", "shifted", "LU", "CG", "peak_MB", "outcome");
  for (const std::string& item : o.items) {
    if (item == "3d") continue;
    std::vector<double> seconds, work, longest, peaks;
    Figures first;
    bool same_counts = true;
    for (int run = 0; run < o.repeat; ++run) {
      double peak = 0;
      int status = 0;
      const std::string out = run_child({self, "--item", item, "--threads", std::to_string(o.threads), "--rra", o.rra, "--tca",
                                         o.tca, "--spl", o.spl, "--segment", std::to_string(o.segment)},
                                        peak, status);
      Figures f;
      if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !parse_figures(out, f)) {
        std::fprintf(stderr, "bench_speed: %s failed (status %d):\n%s\n", item.c_str(), status, out.c_str());
        return 1;
      }
      if (run == 0) first = f;
      same_counts = same_counts && f.work.newton_iterations == first.work.newton_iterations &&
                    f.work.factorizations == first.work.factorizations && f.work.cg_iterations == first.work.cg_iterations;
      seconds.push_back(f.seconds);
      work.push_back(f.work.seconds);
      longest.push_back(f.work.longest_seconds);
      peaks.push_back(peak);
    }
    const fem::SolverWork& w = first.work;
    // A cell rod's paths each run on one thread: no run ends before the slowest of them, nor before
    // their summed seconds spread evenly over the threads (the RRA and the 3D FEM are one path each,
    // timed as the run: "-").
    const bool cell_rod = first.work.seconds > 0;
    const double work_s = cell_rod ? bench::median(work) : -1, longest_s = cell_rod ? bench::median(longest) : -1;
    const std::string cells = format_seconds(work_s) + " " + format_seconds(longest_s) + " " +
                              format_seconds(cell_rod ? std::max(longest_s, work_s / o.threads) : -1);
    std::printf("%-8s %-28s %10lld %10.3f %s %9d %9d %8d %6d %8d %9.0f  %s%s\n", item.c_str(), first.model.c_str(), w.dofs,
                bench::median(seconds), cells.c_str(), w.newton_iterations, w.factorizations, w.shifted_factorizations,
                w.lu_fallbacks, w.cg_iterations, *std::max_element(peaks.begin(), peaks.end()), first.outcome.c_str(),
                same_counts ? "" : " (counts differed between runs)");
    std::fflush(stdout);
  }
  if (std::find(o.items.begin(), o.items.end(), "3d") != o.items.end()) {
    // bench_ccx_3d's own table: softarm (Hex20 at 2×2×2, its default tolerance) against ccx with
    // *CONTROLS tightened to it, on the same meshes, with the ratio.
    const std::string ccx = (std::filesystem::path(self).parent_path() / "bench_ccx_3d").string();
    std::printf("\n3D solves against CalculiX at equal tolerance (%s):\n", ccx.c_str());
    std::fflush(stdout);
    const std::string command = ccx + " --scene tca --elements 20r --levels 1 --lengths " + joined(o.lengths) +
                                " --variants strict,ccx-tight --threads 1 --repeat " + std::to_string(o.repeat);
    const int status = std::system(command.c_str());
    if (status != 0) return 1;
  }
  return 0;
} catch (const fem::InputError& e) {
  std::fprintf(stderr, "%s\n", e.what());
  return 2;
}

// Benchmark (not a test): the sparse direct solve of 3D Hex27 tangents.
//
// Builds box meshes of a slender body (60 × 30 × 160 mm by default, Hex27 / P1,
// Dragon Skin 30 Ogden, the z = 0 face clamped), assembles the tangent at rest
// and, for each solver configuration (each in its own forked process, so that its memory peak is
// its own), prints dofs, nnz(K), nnz(L), the predicted factor flops, the analysis time, the median
// factorisation time over --repeat factorisations (wall and CPU time: CPU time is the robust figure
// on a shared machine for a serial BLAS), the median solve time, the achieved GFlop/s, CHOLMOD's
// peak memory, the peak RSS of the process, and the median time and iterations of CG to 1e-10
// preconditioned with the factor: what a Newton step on an earlier factor costs per iteration, on
// the factor's single-precision copy (super-double-cg: on the factor itself). Also prints the
// median assembly time (EnergyProblem::evaluate with gradient + Hessian).
//
// The BLAS is whichever libblas.so.3 / liblapack.so.3 the loader finds: compare
// BLAS builds with LD_LIBRARY_PATH (e.g. /usr/lib/x86_64-linux-gnu/blas:
// /usr/lib/x86_64-linux-gnu/lapack for reference BLAS) without touching the system.
//
// Usage: bench_linear_solver [--sizes 4x4x40,6x6x60] [--box 60x30x160] [--repeat N]
//                            [--threads T] [--configs auto,super,...|all] [--no-assembly]
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "benchmarks/bench_options.hpp"
#include "benchmarks/bench_stats.hpp"
#include "fem/assembly/energy_problem.hpp"
#include "fem/core/input_error.hpp"
#include "fem/core/parallel.hpp"
#include "fem/forms/make_elastic_form.hpp"
#include "fem/materials/material.hpp"
#include "fem/mesh/quadratic_mesh.hpp"
#include "fem/mesh/structured_mesh.hpp"
#include "fem/solver/linear_solver.hpp"

using namespace softarm;
using namespace softarm::fem;
using Options = LinearSolver::Options;

namespace {
double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
double cpu_seconds() {  // user + system time of every thread of this process
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}
double peak_rss_MiB() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;
}

struct Config {
  std::string name;
  Options options;
};

std::vector<Config> all_configs() {
  using M = Options::Mode;
  using O = Options::Ordering;
  auto make = [](M mode, O ordering, bool postorder = true) {
    Options o;
    o.mode = mode;
    o.ordering = ordering;
    o.postorder = postorder;
    return o;
  };
  return {
      {"default", Options{}},
      {"auto", make(M::automatic, O::cholmod_default)},
      {"simplicial", make(M::simplicial, O::cholmod_default)},
      {"super", make(M::supernodal, O::cholmod_default)},
      {"super-amd", make(M::supernodal, O::amd)},
      {"super-metis", make(M::supernodal, O::metis)},
      {"super-nesdis", make(M::supernodal, O::nesdis)},
      {"super-all", make(M::supernodal, O::best_of_all)},
      {"super-nopost", make(M::supernodal, O::cholmod_default, false)},
      {"auto-metis", make(M::automatic, O::metis)},
      {"auto-amd", make(M::automatic, O::amd)},
      {"super-double-cg", [&] {
         auto o = make(M::supernodal, O::cholmod_default);
         o.single_precision_preconditioner = false;
         return o;
       }()},
      {"super-metis-relax", [&] {
         auto o = make(M::supernodal, O::metis);
         o.large_supernodes = true;
         return o;
       }()},
  };
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, sep);)
    if (!item.empty()) out.push_back(item);
  return out;
}

/// Runs one configuration in the current (forked) process and prints its row.
void run_config(const Config& c, const SparseMatrix& K, int repeat) {
  LinearSolver solver(c.options);
  std::vector<double> factor, factor_cpu, solve, cg;
  double residual = 0.0, cg_residual = 0.0;
  int cg_iterations = 0;
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(K.rows());
  for (int k = 0; k < repeat; ++k) {
    const double f0 = solver.factorize_seconds, c0 = cpu_seconds();
    if (solver.factorize(K) != LinearSolver::Status::positive_definite) {
      std::printf("  %-17s not positive definite\n", c.name.c_str());
      return;
    }
    factor.push_back(solver.factorize_seconds - f0);
    factor_cpu.push_back(cpu_seconds() - c0);
    const double t0 = now();
    const Eigen::VectorXd x = solver.solve(b);
    solve.push_back(now() - t0);
    residual = (K * x - b).norm() / b.norm();
    // CG on the factor of K itself: what a Newton step solved on an earlier factor costs per
    // iteration (a product with K and the preconditioner's two sweeps), here in 1-3 iterations.
    Eigen::VectorXd d;
    solver.solve_reusing_factor(K, b, 1e-10, d);  // once untimed: the preconditioner's copy is made at the first
    const int before = solver.cg_iterations;
    const double t1 = now();
    solver.solve_reusing_factor(K, b, 1e-10, d);
    cg.push_back(now() - t1);
    cg_iterations = solver.cg_iterations - before;
    cg_residual = (K * d - b).norm() / b.norm();
  }
  const double tf = bench::median(factor);
  std::printf("  %-17s %-5s %8.2f %8.3f %8.3f %7.3f %7.3f %7.2f %7.3f %9.0f %9.0f  %.1e  %7.4f %2d %.1e\n", c.name.c_str(),
              solver.supernodal ? "super" : "simpl", solver.factor_nonzeros / 1e6, solver.factor_flops / 1e9,
              solver.analyse_seconds, tf, bench::median(factor_cpu), solver.factor_flops / tf / 1e9, bench::median(solve),
              solver.cholmod_peak_bytes / 1048576.0, peak_rss_MiB(), residual, bench::median(cg), cg_iterations,
              cg_residual);
  std::fflush(stdout);
}

/// "AxBxC": three numbers above 0 (integers when `integers`).
CLI::Validator three_by(bool integers) {
  return CLI::Validator(
      [integers](std::string& text) {
        const auto n = split(text, 'x');
        bool ok = n.size() == 3;
        for (const auto& v : n) {
          int i = 0;
          ok = ok && (integers ? CLI::detail::lexical_cast(v, i) && i >= 1 && i <= 1000 : bench::Positive(v).empty());
        }
        return ok ? std::string() : text + " is not " + (integers ? "NxNxN (elements, 1 to 1000 each)" : "AxBxC (mm above 0)");
      },
      integers ? "NxNxN" : "AxBxC");
}
}  // namespace

int main(int argc, char** argv) try {
  std::vector<std::string> sizes{"4x4x40", "6x6x60"}, configs{"all"};
  std::string box = "60x30x160";
  int repeat = 5, threads = 1;
  bool no_assembly = false;
  std::vector<std::string> config_names{"all"};
  for (const auto& c : all_configs()) config_names.push_back(c.name);
  CLI::App app{"the sparse direct solve of 3D Hex27 tangents: CHOLMOD configurations and BLAS builds"};
  app.add_option("--sizes", sizes, "box meshes, elements along x, y and z")->delimiter(',')->check(three_by(true));
  app.add_option("--box", box, "the box's extent (mm)")->check(three_by(false));
  app.add_option("--repeat", repeat, "factorisations per configuration (the median is printed)")->check(CLI::Range(1, 1000));
  app.add_option("--threads", threads, "threads for assembly")->check(CLI::Range(1, 256));
  app.add_option("--configs", configs, "solver configurations")->delimiter(',')->check(CLI::IsMember(config_names));
  app.add_flag("--no-assembly", no_assembly, "skip timing the assembly");
  if (const auto code = bench::parse_or_exit(app, argc, argv)) return *code;
  const bool assembly = !no_assembly;
  set_thread_count(threads);
  std::vector<Config> chosen;
  const bool all = std::find(configs.begin(), configs.end(), "all") != configs.end();
  for (const auto& c : all_configs())
    if (all || std::find(configs.begin(), configs.end(), c.name) != configs.end()) chosen.push_back(c);
  const auto extent = split(box, 'x');
  const Eigen::Vector3d hi(std::stod(extent.at(0)), std::stod(extent.at(1)), std::stod(extent.at(2)));
  const char* blas = std::getenv("LD_LIBRARY_PATH");
  std::printf("bench_linear_solver: Hex27/P1 box %s mm, Dragon Skin 30, z = 0 clamped, tangent at rest; "
              "%d thread(s) for assembly, median of %d; LD_LIBRARY_PATH=%s\n",
              box.c_str(), threads, repeat, blas ? blas : "(unset)");

  for (const auto& size : sizes) {
    const auto n = split(size, 'x');
    const Mesh mesh = to_quadratic_3d(
        box_mesh(Eigen::Vector3d::Zero(), hi, std::stoi(n.at(0)), std::stoi(n.at(1)), std::stoi(n.at(2))));
    DirichletConstraints clamp;
    for (int node = 0; node < mesh.num_nodes(); ++node)
      if (mesh.X(node, 2) == 0.0)
        for (int i = 0; i < 3; ++i) clamp.fix(3 * node + i);
    EnergyProblem problem(flattened_positions(mesh), clamp);
    problem.add_form(make_elastic_form(mesh, {builtin_material("dragon_skin_30", "material")}));
    problem.finalize();
    const Vector x = problem.reference_positions();
    Evaluation ev = problem.evaluate(x, true, true);
    std::printf("\nmesh %s elements (%d nodes): %d dofs, nnz(K) %.2f M (full symmetric storage)\n", size.c_str(),
                mesh.num_nodes(), problem.num_dofs(), ev.hessian.nonZeros() / 1e6);
    if (assembly) {
      std::vector<double> gh, g;
      for (int k = 0; k < repeat; ++k) {
        double t0 = now();
        ev = problem.evaluate(x, true, true);
        gh.push_back(now() - t0);
        t0 = now();
        problem.evaluate(x, true, false);
        g.push_back(now() - t0);
      }
      std::printf("  assembly (median): gradient + Hessian %.3f s, gradient only %.3f s\n", bench::median(gh), bench::median(g));
    }
    std::printf("  %-17s %-5s %8s %8s %8s %7s %7s %7s %7s %9s %9s  %-7s  %7s %2s %s\n", "config", "L", "nnzL[M]",
                "GFlop", "analyse", "factor", "cpu", "GFlop/s", "solve", "chol[MiB]", "RSS[MiB]", "residual", "cg", "it",
                "cg_resid");
    std::fflush(stdout);
    for (const auto& c : chosen) {
      const pid_t pid = fork();
      if (pid == 0) {
        run_config(c, ev.hessian, repeat);
        std::fflush(stdout);
        _exit(0);
      }
      int status = 0;
      waitpid(pid, &status, 0);
    }
  }
  return 0;
} catch (const InputError& e) {
  std::fprintf(stderr, "%s\n", e.what());
  return 2;
}

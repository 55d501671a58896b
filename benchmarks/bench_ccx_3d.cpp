// softarm vs CalculiX (ccx 2.20, SPOOLES) wall time on the same 3D actuator
// meshes: a short three-chambered actuator (3CA, half model, chambers 2 and 3
// pressurised) and a lone RRA (half model), Hex27/H2P1 or Hex20/H2sP1
// (--elements) in softarm, C3D20R in ccx (the export of
// fem/scenes/tca_export.hpp; for Hex20 it is the very same mesh, node for node,
// so the unknowns are equal), neo-Hookean silicone with
// Dragon Skin 30's initial moduli and digital-ABS rings, one pressure.
//
// Matched work: both engines take the same fixed load increments (--increments,
// default 4: ccx's *STATIC initial = maximum increment = 1/n; softarm's
// StepSettings initial = maximum = 1/n) and the same number of threads
// (--threads, default 1: softarm's thread count, ccx's CCX_NPROC_* and
// OMP_NUM_THREADS). Tolerances: ccx's default residual control (largest
// residual force ≤ R_n = 0.005 of the time-averaged mean force, and correction
// ≤ C_n = 0.01 of the increment's displacement) is far looser than softarm's
// default (2-norm residual ≤ 1e-8 of the load's force scale, and update ≤ 1e-6).
// Each size is therefore timed three ways: softarm at its default, softarm at
// --loose-tol (default 5e-3, update 1e-2: the order of ccx's defaults), and ccx
// at its defaults; with the variant ccx-tight also ccx with *CONTROLS, PARAMETERS=FIELD
// R_n = 1e-6, C_n = 1e-5 (softarm-like). The answers (mean free-face
// displacement over the nodes both engines have) are printed next to the times.
//
// Usage: bench_ccx_3d [--scene tca|rra|both] [--levels 1,2] [--lengths 32,64]
//                     [--pressure-kPa 15] [--repeat 3] [--threads 1]
//                     [--increments 4] [--loose-tol 5e-3]
//                     [--variants strict,loose,ccx,ccx-tight,strict-refactor,loose-refactor]
//                                 (ratio: time / the first variant's)
//                     [--elements 27,20,20r]   (softarm's Hex27, Hex20 and/or Hex20 at 2×2×2 Gauss points,
//                                           the C3D20R rule; ccx runs once per mesh)
//                     (strict-refactor, loose-refactor: softarm factorising every Newton iteration,
//                      without its default factor reuse, NewtonSettings::reuse_factor)
// Medians over --repeat runs are printed (this machine is shared and noisy).
// "dofs": 3 × nodes, constrained ones included (softarm: Hex27 nodes; ccx: the
// C3D20 nodes). softarm's time is setup + solve (not meshing; the 3CA's includes
// the dp/dV solve per step); ccx's is the whole process (reading the deck,
// writing .dat/.frd).
//
// Measured 2026-11-22 (15 kPa, 4 increments, 1 thread, medians of 3 on the
// shared 2-core machine under a load of ~5; seconds, Newton iterations):
//   RRA 32 mm L1 (5,049 / 2,985 dofs): softarm 1.44 (19), loose 1.00 (12), ccx 0.86 (12)
//   RRA 32 mm L2 (33,327 / 18,351):    softarm 19.8 (18), loose 11.2 (9),  ccx 15.8 (12)
//   3CA 32 mm L1 (18,990 / 10,296):    softarm 22.1 (19), loose 14.0 (11), ccx 19.5 (12)
//   3CA 64 mm L1 (34,830 / 18,720):    softarm 24.7 (18), loose 12.5 (8),  ccx 20.1 (13)
//   3CA 32 mm L2 (139,206 / 72,750), one run: softarm 247 (18), ccx 277 (13)
// Measured 2026-11-23, Hex20 at 3×3×3 and at 2×2×2 points (--elements 20,20r --lengths 32,64
// --levels 1 --variants strict,loose,ccx, medians of 3, one thread, a level-2 3CA solve on the
// other core); ccx / softarm loose with the C3D20R rule: RRA 32 mm 3.4×, RRA 64 mm 3.2×,
// 3CA 32 mm 3.0×, 3CA 64 mm 3.4× (docs/performance.md, With ccx's own integration rule).
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "benchmarks/bench_options.hpp"
#include "benchmarks/bench_stats.hpp"
#include "fem/core/input_error.hpp"
#include "fem/core/parallel.hpp"
#include "fem/forms/chamber_pressure_form.hpp"
#include "fem/forms/make_elastic_form.hpp"
#include "fem/materials/neo_hookean.hpp"
#include "fem/mesh/tca_mesher.hpp"
#include "fem/scenes/tca_export.hpp"
#include "fem/scenes/tca_scene.hpp"
#include "fem/solver/load_stepper.hpp"

using namespace softarm::fem;
namespace bench = softarm::bench;

namespace {

using Clock = std::chrono::steady_clock;

Material silicone() {  // Dragon Skin 30's initial moduli: μ0 = 0.1153 MPa, D1 = 0.7029/MPa
  Material m;
  m.name = "neo_hookean_ds30";
  m.law = std::make_shared<NeoHookean>(0.1153 / 2, VolumetricPolynomial({0.7029}));
  m.density_g_cm3 = 1.08;
  return m;
}

/// A short RRA with the thesis cross-section and ring pitch (l/n_r = 16/3 mm).
RraDesign short_rra(double length_mm) {
  RraDesign d;
  d.length_mm = length_mm;
  d.top_radius_mm = 9 + 3 * length_mm / 160;  // the thesis taper
  d.ring_count = std::max(1, static_cast<int>(std::lround(length_mm * 30 / 160)));
  d.ring_diameter_mm = 0.4 * length_mm / d.ring_count;
  d.ring_section = RraDesign::RingSection::square;
  return d;
}

struct Answer {
  int dofs = 0, iterations = 0, increments = 0;
  double seconds = 0;
  Eigen::Vector3d u = Eigen::Vector3d::Constant(std::nan(""));
  bool ok = false;
};

struct Problem {
  std::string scene;
  double length_mm = 32;
  int level = 1;
  double pressure_kPa = 15;
  bool serendipity = false;  // softarm's Hex20 instead of Hex27 (ccx's deck is the same)
  ElementIntegration integration = ElementIntegration::full;  // reduced: Hex20 as C3D20R
};

TcaSceneSpec tca_spec(const Problem& p, int increments, const NewtonSettings& newton) {
  TcaSceneSpec spec;
  spec.design.actuator = short_rra(p.length_mm);
  spec.tube_material = spec.sheath_material = silicone();
  spec.ring_material = builtin_material("digital_abs", "bench");
  spec.mesh_level = p.level;
  spec.serendipity = p.serendipity;
  spec.integration = p.integration;
  spec.chamber_pressure_kPa = {0, p.pressure_kPa, p.pressure_kPa};
  spec.output_pressures_kPa = {p.pressure_kPa};
  spec.steps.initial_increment = spec.steps.max_increment = 1.0 / increments;
  spec.newton = newton;
  return spec;
}

Mesh rra_mesh_of(const Problem& p) {
  SolidMeshOptions options;
  options.level = p.level;
  options.half = true;
  options.serendipity = p.serendipity;
  return mesh_rra_3d(short_rra(p.length_mm), options);
}

Answer softarm_run(const Problem& p, int increments, const NewtonSettings& newton) {
  Answer a;
  if (p.scene == "tca") {
    const TcaSceneSpec spec = tca_spec(p, increments, newton);
    const TcaResult r = run_tca_scene(spec);
    a.seconds = r.timings.setup_s + r.timings.solve_s;  // not the meshing (ccx reads a finished mesh)
    a.dofs = r.dofs;
    a.iterations = r.path.path.stats.newton_iterations;
    a.increments = r.path.path.stats.steps;
    a.ok = r.path.outcome == PathOutcome::completed;
    // Back to the solver frame (the same as the user frame here: mirror plane through chamber 1).
    const Mesh solver_mesh = tca_mesh(spec, r.model);
    const Eigen::Matrix3d R = rotation_about_z(-r.model.frame_angle_rad);
    Eigen::VectorXd u = r.final_positions - flattened_positions(r.mesh);
    for (Eigen::Index n = 0; n < u.size() / 3; ++n) u.segment<3>(3 * n) = R * u.segment<3>(3 * n);
    a.u = mean_displacement(exported_nodes(solver_mesh, solver_mesh.node_sets.at("bottom")), u);
    return a;
  }
  const Mesh mesh = rra_mesh_of(p);
  const auto t0 = Clock::now();
  LoadState load;
  load.chamber_pressure_MPa = {0.0};
  EnergyProblem problem(flattened_positions(mesh), actuator_3d_constraints(mesh));
  problem.add_form(make_elastic_form(mesh, {silicone(), builtin_material("digital_abs", "bench")},
                                     VolumetricTreatment::projected_dilatation, p.integration));
  problem.add_form(std::make_shared<ChamberPressureForm>(mesh, 0, load));
  problem.finalize();
  Eigen::VectorXd x = problem.reference_positions();
  LinearSolver solver;
  StepSettings steps;
  steps.initial_increment = steps.max_increment = 1.0 / increments;
  const PathCallbacks cb{[&](double level) { load.chamber_pressure_MPa[0] = level * p.pressure_kPa * 1e-3; }, {}};
  const PathResult r = follow_load_path(problem, x, solver, {1.0}, cb, newton, steps);
  a.seconds = bench::seconds_since(t0);
  a.dofs = problem.num_dofs();
  a.iterations = r.stats.newton_iterations;
  a.increments = r.stats.steps;
  a.ok = r.completed;
  a.u = mean_displacement(exported_nodes(mesh, mesh.node_sets.at("bottom")), x - problem.reference_positions());
  return a;
}

Answer ccx_run(const Problem& p, int increments, int threads, bool tight) {
  Answer a;
  Mesh mesh;
  AbaqusDeck deck;
  TcaSceneSpec spec;
  if (p.scene == "tca") {
    spec = tca_spec(p, increments, {});
    const ModelChoice model = choose_tca_model(spec);
    mesh = tca_mesh(spec, model);
    deck = tca_abaqus_deck(spec, mesh, model, 1.0);
  } else {
    mesh = rra_mesh_of(p);
    deck = rra_3d_abaqus_deck(mesh, silicone(), builtin_material("digital_abs", "bench"), p.pressure_kPa);
  }
  deck.initial_increment = deck.max_increment = 1.0 / increments;
  const auto dir = std::filesystem::temp_directory_path() / ("softarm_bench_ccx_3d_" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string inp = (dir / "job.inp").string();
  write_abaqus_deck(inp, deck);
  if (tight) {  // *CONTROLS after the *STATIC data line
    std::ifstream in(inp);
    std::stringstream text;
    text << in.rdbuf();
    std::string s = text.str();
    const auto at = s.find('\n', s.find("*STATIC\n") + 8);
    // The full line: a partial one zeroes q_0 and q_u (defaults 0.01, 1e-5); the rest are the defaults.
    s.insert(at + 1, "*CONTROLS, PARAMETERS=FIELD\n1e-6, 1e-5, 0.01, 1e-5, 0.02, 1e-5, 1e-3, 1e-8\n");
    std::ofstream(inp) << s;
  }
  const std::string t = std::to_string(threads);
  const std::string cmd = "cd " + dir.string() + " && OMP_NUM_THREADS=" + t + " CCX_NPROC_EQUATION_SOLVER=" + t +
                          " CCX_NPROC_STIFFNESS=" + t + " CCX_NPROC_RESULTS=" + t + " ccx -i job > ccx.log 2>&1";
  const auto t0 = Clock::now();
  const int status = std::system(cmd.c_str());
  a.seconds = bench::seconds_since(t0);
  const auto stats = read_ccx_statistics((dir / "job.sta").string());
  a.iterations = stats.iterations;
  a.increments = stats.increments;
  a.ok = status == 0 && std::abs(stats.reached_time - 1.0) < 1e-9;
  const auto u = read_ccx_displacements((dir / "job.dat").string());
  const auto nodes = exported_nodes(mesh, mesh.node_sets.at("bottom"));
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  std::size_t found = 0;
  for (int n : nodes)
    if (const auto it = u.find(n); it != u.end()) sum += it->second, ++found;
  if (found == nodes.size() && found > 0) a.u = sum / static_cast<double>(found);
  else a.ok = false;
  // ccx's unknowns before constraints: 3 per node of its elements (no Hex27 face or body centres).
  std::vector<int> all(static_cast<std::size_t>(mesh.num_nodes()));
  for (int i = 0; i < mesh.num_nodes(); ++i) all[static_cast<std::size_t>(i)] = i;
  a.dofs = 3 * static_cast<int>(exported_nodes(mesh, all).size());
  if (a.ok) std::filesystem::remove_all(dir);
  else std::fprintf(stderr, "ccx run kept in %s\n", dir.string().c_str());
  return a;
}


}  // namespace

int main(int argc, char** argv) try {
  std::string scene = "both";
  std::vector<int> levels{1, 2};
  std::vector<double> lengths{32};
  std::vector<std::string> elements{"27"};
  double pressure = 15, loose = 5e-3;
  int repeat = 3, threads = 1, increments = 4;
  std::vector<std::string> which{"strict", "loose", "ccx"};
  CLI::App app{"softarm vs CalculiX (ccx) wall time on the same 3D actuator meshes"};
  app.add_option("--scene", scene, "the short 3CA, the lone RRA or both")->check(CLI::IsMember({"tca", "rra", "both"}));
  app.add_option("--levels", levels, "mesh levels")->delimiter(',')->check(CLI::Range(1, 4));
  app.add_option("--lengths", lengths, "actuator lengths (mm)")->delimiter(',')->check(bench::Positive);
  app.add_option("--elements", elements, "softarm's Hex27, Hex20 and/or Hex20 at 2x2x2 Gauss points (C3D20R's rule)")
      ->delimiter(',')
      ->check(CLI::IsMember({"27", "20", "20r"}));
  app.add_option("--pressure-kPa", pressure, "the pressure")->check(bench::Positive);
  app.add_option("--repeat", repeat, "runs per variant (the median is printed)")->check(CLI::Range(1, 1000));
  app.add_option("--threads", threads, "softarm's threads and ccx's CCX_NPROC_* / OMP_NUM_THREADS")
      ->check(CLI::Range(1, 256));
  app.add_option("--increments", increments, "fixed load increments of both engines")->check(CLI::Range(1, 1000));
  app.add_option("--loose-tol", loose, "softarm's residual tolerance in the loose variants")->check(bench::Positive);
  app.add_option("--variants", which, "what is timed (ratio: time / the first variant's)")
      ->delimiter(',')
      ->check(CLI::IsMember({"strict", "loose", "ccx", "ccx-tight", "strict-refactor", "loose-refactor"}));
  if (const auto code = bench::parse_or_exit(app, argc, argv)) return *code;
  set_thread_count(threads);
  // softarm's 3D default (tca_scene.hpp): factor reuse, a shifted Cholesky where the tangent is
  // indefinite (no LU), stiff parts rotated exactly.
  NewtonSettings strict = TcaSceneSpec{}.newton, relaxed = strict;
  relaxed.residual_tolerance = loose;
  relaxed.update_tolerance = 1e-2;
  NewtonSettings strict_refactor = strict, relaxed_refactor = relaxed;  // after the tolerances
  strict_refactor.reuse_factor = relaxed_refactor.reuse_factor = false;
  std::printf("softarm (Hex27 H2/P1 or Hex20 H2s/P1) vs ccx (C3D20R), %g kPa, %d fixed increments, %d thread(s), median of %d\n",
              pressure, increments, threads, repeat);
  std::printf("%-5s %6s %5s %8s | %-26s %5s %5s %8s | %-10s %12s %12s %12s\n", "scene", "l_mm", "level", "dofs",
              "engine", "incr", "iters", "time_s", "ratio", "u_x_mm", "u_y_mm", "u_z_mm");
  const std::vector<std::string> scenes = scene == "both" ? std::vector<std::string>{"rra", "tca"} : std::vector<std::string>{scene};
  for (const auto& s : scenes)
    for (double l : lengths)
      for (int lv : levels) {
        const Problem p{s, l, lv, pressure};
        struct Variant {
          std::string name, kind;
          bool serendipity = false;
          ElementIntegration integration = ElementIntegration::full;
          std::vector<Answer> runs;
        };
        std::vector<Variant> variants;
        for (const auto& v : which)
          for (const std::string& e : elements) {
            const bool h20 = e == "20" || e == "20r", first = e == elements.front();
            const auto rule = e == "20r" ? ElementIntegration::reduced : ElementIntegration::full;
            if (!h20 && e != "27") {
              std::fprintf(stderr, "--elements takes 27, 20 and/or 20r\n");
              return 2;
            }
            const std::string tag = e == "20r" ? " H20R" : h20 ? " H20" : " H27";
            char loose_text[32];  // "%g": 1e-06 stays readable where a fixed width would print 0.0000
            std::snprintf(loose_text, sizeof loose_text, "%g", loose);
            if (v == "strict") variants.push_back({"softarm tol 1e-8" + tag, v, h20, rule, {}});
            else if (v == "loose") variants.push_back({"softarm tol " + std::string(loose_text) + tag, v, h20, rule, {}});
            else if (v == "strict-refactor") variants.push_back({"refactor tol 1e-8" + tag, v, h20, rule, {}});
            else if (v == "loose-refactor")
              variants.push_back({"refactor tol " + std::string(loose_text) + tag, v, h20, rule, {}});
            else if (v == "ccx" && first) variants.push_back({"ccx default", v, false, ElementIntegration::full, {}});
            else if (v == "ccx-tight" && first) variants.push_back({"ccx R_n 1e-6", v, false, ElementIntegration::full, {}});
            else if (v != "ccx" && v != "ccx-tight") {
              std::fprintf(stderr, "unknown variant %s\n", v.c_str());
              return 2;
            }
          }
        for (int r = 0; r < repeat; ++r)
          for (std::size_t k = 0; k < variants.size(); ++k) {
            const std::string& v = variants[k].kind;
            Problem pk = p;
            pk.serendipity = variants[k].serendipity;
            pk.integration = variants[k].integration;
            const auto newton = [&]() -> const NewtonSettings& {
              if (v == "strict") return strict;
              if (v == "loose") return relaxed;
              return v == "strict-refactor" ? strict_refactor : relaxed_refactor;
            };
            variants[k].runs.push_back(v.starts_with("ccx") ? ccx_run(p, increments, threads, v == "ccx-tight")
                                                            : softarm_run(pk, increments, newton()));
            const Answer& a = variants[k].runs.back();  // each run as it ends (long runs)
            std::printf("  run %d %-26s %5d iterations %8.2f s  u = (%.5f, %.5f, %.5f) mm%s\n", r + 1,
                        variants[k].name.c_str(), a.iterations, a.seconds, a.u.x(), a.u.y(), a.u.z(),
                        a.ok ? "" : "  (FAILED)");
            std::fflush(stdout);
          }
        std::vector<double> medians;
        for (const auto& v : variants) {
          std::vector<double> t;
          for (const auto& a : v.runs) t.push_back(a.seconds);
          medians.push_back(softarm::bench::median(t));
        }
        for (std::size_t k = 0; k < variants.size(); ++k) {
          const Answer& a = variants[k].runs.back();
          std::printf("%-5s %6.0f %5d %8d | %-26s %5d %5d %8.2f | %-10.2f %12.5f %12.5f %12.5f%s\n", s.c_str(), l,
                      p.level, a.dofs, variants[k].name.c_str(), a.increments, a.iterations, medians[k],
                      medians[k] / medians[0], a.u.x(), a.u.y(), a.u.z(), a.ok ? "" : "  (FAILED)");
        }
        std::fflush(stdout);
      }
  return 0;
} catch (const InputError& e) {
  std::fprintf(stderr, "%s\n", e.what());
  return 2;
}

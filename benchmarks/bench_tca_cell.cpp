// The ring-pitch cell of a 3CA config (fem/scenes/tca_cell.hpp): its free stretch and
// curvature along the pressure ramp at chosen rings, and the bending angle they add up to
// over the ringed length, for comparison with the whole 3CA's curve (gravity off).
//
//   bench_tca_cell [config] [--rings 1,15,30] [--axial-level N] [--threads N]
//                  [--compare curve.csv]   (a `softarm simulate` curve of the same 3CA)
//                  [--moment-Nmm Mx,My]    (a dead end moment on every cell besides the pressures:
//                                           how far the cells' linear compliance carries)
//                  [--end-rings N]         (also both ends through their first N rings,
//                                           fem/scenes/tca_end_cell.hpp: their own turn against
//                                           the cells' κ₀ over the same length, and the rod with them)
//                  [--torsion]             (also each cell's GJ along the pressure ramp: the periodic
//                                           cell under its pressures, cell_torsion_along_ramp)
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "benchmarks/bench_options.hpp"
#include "benchmarks/bench_stats.hpp"
#include "benchmarks/bench_scene.hpp"
#include "fem/core/input_error.hpp"
#include "fem/core/parallel.hpp"
#include "fem/scenes/scene_config.hpp"
#include "fem/scenes/tca_cell.hpp"
#include "fem/core/angles.hpp"

using namespace softarm;

int main(int argc, char** argv) try {
  std::string config = "configs/tca_thesis.json", compare;
  std::vector<int> rings;
  int axial_level = -1, end_rings = 0, threads = fem::thread_count();
  bool torsion = false;
  std::pair<double, double> moment{0, 0};
  CLI::App app{"the ring-pitch cells of a 3CA config along its pressure ramp, and the cell rod's curve from them"};
  app.add_option("config", config, "a tca scene config");
  app.add_option("--rings", rings, "the cells' rings")
      ->delimiter(',')
      ->check(CLI::Range(1, 1000))
      ->default_str("the first, middle and last");
  app.add_option("--axial-level", axial_level, "element layers along the axis as at this mesh level (0: the mesh level's)")
      ->check(CLI::Range(0, 8))
      ->default_str("the config's");
  app.add_option("--compare", compare, "a `softarm simulate` curve.csv of the same 3CA")->check(CLI::ExistingFile);
  app.add_option("--end-rings", end_rings, "also both ends through their first N rings (0: none)")->check(CLI::Range(0, 100));
  app.add_flag("--torsion", torsion, "also each cell's GJ along the pressure ramp");
  app.add_option("--moment-Nmm", moment, "a dead end moment Mx,My on every cell besides the pressures")
      ->delimiter(',')
      ->check(bench::Finite)
      ->default_str("0,0");
  app.add_option("--threads", threads, "threads")->check(CLI::Range(1, 256));
  if (const auto code = bench::parse_or_exit(app, argc, argv)) return *code;
  fem::set_thread_count(threads);
  fem::CellEndLoad end_load;
  end_load.moment_Nmm = Eigen::Vector2d(moment.first, moment.second);
  const auto scene = bench::scene_of_kind(config, "tca", "bench_tca_cell");
  if (!scene) return 2;
  fem::TcaSceneSpec spec = scene->tca;
  if (axial_level >= 0) spec.axial_level = axial_level;
  const int n = spec.design.actuator.ring_count;
  if (rings.empty()) rings = {1, (n + 1) / 2, n};
  for (int ring : rings)
    if (ring > n) {
      std::fprintf(stderr, "bench_tca_cell: --rings: %s has %d rings, not %d\n", config.c_str(), n, ring);
      return 2;
    }
  std::printf("%s: %d rings, pitch %.4f mm, threads %d\n", config.c_str(), n, spec.design.actuator.pitch(),
              fem::thread_count());
  if (torsion)
    for (int ring : rings) {
      const auto t0 = std::chrono::steady_clock::now();
      const auto gj = fem::cell_torsion_along_ramp(spec, ring);
      std::printf("ring %d: GJ along the ramp (%.1f s)\n%12s %14s %10s\n", ring,
                  bench::seconds_since(t0), "pressure_kPa",
                  "GJ_Nmm2", "vs_rest");
      for (const auto& g : gj)
        std::printf("%12.2f %14.1f %10.3f\n", g.pressure_kPa, g.stiffness_Nmm2, g.stiffness_Nmm2 / gj.front().stiffness_Nmm2);
    }
  std::vector<fem::TcaCellResult> cells;
  double cell_seconds = 0;
  for (int ring : rings) {
    const auto r = fem::run_tca_cell(spec, ring, end_load);
    cells.push_back(r);
    cell_seconds += r.seconds;
    std::printf("\nring %d at z = %.3f mm: %s, %s, %d dofs, %d steps, %d Newton, %.1f s; %s%s\n", ring,
                r.ring_centre_z_mm, r.model.name.c_str(), r.element_name.c_str(), r.dofs, r.path.path.stats.steps,
                r.path.path.stats.newton_iterations, r.seconds, fem::to_string(r.path.outcome),
                r.path.diagnosis.empty() ? "" : (": " + r.path.diagnosis).c_str());
    std::printf("  costs: %d evaluations %.2f s, %d factorisations (%d shifted, %.1f GFlop each, nnz(L) %.2f M) %.2f s, "
                "solves %.2f s (%d by CG on an earlier factor, %d CG iterations), analysis %.2f s, "
                "end-face compliances %.2f s\n",
                r.evaluations, r.assembly_s, r.path.factorizations, r.path.shifted_factorizations,
                r.path.factor_flops / 1e9, r.path.factor_nonzeros / 1e6, r.path.factorize_s, r.path.solve_s, r.path.reused_solves,
                r.path.cg_iterations, r.path.analyse_s, r.compliance_s);
    std::printf("%12s %10s %14s %14s %12s %10s %14s %12s %12s %12s %12s %12s\n", "pressure_kPa", "stretch", "curv_deg_mm", "deg_per_pitch",
                "volume_mm3", "gap_mm", "EI_Nmm2", "EA_N", "kx_per_mm", "ky_per_mm", "Cxx", "Cyy");
    for (const auto& s : r.states) {
      std::printf("%12.2f %10.5f %14.6f %14.4f %12.1f %10.2e", s.pressure_kPa, s.stretch,
                  s.curvature_per_mm * softarm::fem::kDeg, s.curvature_per_mm * r.pitch_mm * softarm::fem::kDeg,
                  s.chamber_volume_mm3, s.plane_gap_mm);
      if (s.bending_compliance_per_Nmm2 > 0)
        std::printf(" %14.1f %12.2f", 1 / s.bending_compliance_per_Nmm2, 1 / s.axial_compliance_per_N);
      else
        std::printf(" %14s %12s", s.is_output ? "-" : "", s.is_output ? "-" : "");
      const auto& c = s.bending_compliance_matrix_per_Nmm2;
      std::printf(" %12.4e %12.4e %12.4e %12.4e\n", s.curvature_vector_per_mm.x(), s.curvature_vector_per_mm.y(), c(0, 0),
                  c(1, 1));
    }
  }
  // The cell rod along the config's outputs, with the config's gravity and without.
  std::map<double, double> reference;  // pressure → bending of the compared curve
  if (!compare.empty()) {
    std::ifstream in(compare);
    std::string line;
    std::getline(in, line);
    for (double p, angle; std::getline(in, line);)
      if (std::sscanf(line.c_str(), "%lf,%lf", &p, &angle) == 2) reference[p] = angle;
  }
  std::vector<fem::TcaEndCellResult> ends;
  if (end_rings > 0)
    for (const fem::TcaEnd end : {fem::TcaEnd::bottom, fem::TcaEnd::top}) {
      const auto e = fem::run_tca_end_cell(spec, end, end_rings, fem::tca_scene_end_support(end));
      ends.push_back(e);
      cell_seconds += e.seconds;
      std::printf("\n%s end through %d rings (%.3f mm): %s, %d dofs, %d Newton, %.1f s; %s%s\n",
                  end == fem::TcaEnd::top ? "clamped" : "free", end_rings, e.length_mm, e.element_name.c_str(), e.dofs,
                  e.path.path.stats.newton_iterations, e.seconds, fem::to_string(e.path.outcome),
                  e.path.diagnosis.empty() ? "" : (": " + e.path.diagnosis).c_str());
      std::printf("  costs: %d factorisations (%d shifted, %d LU) %.2f s, solves %.2f s (%d by CG on an earlier factor, "
                  "%d CG iterations), analysis %.2f s; %d states by pressure control, %d beyond by volume control\n",
                  e.path.factorizations, e.path.shifted_factorizations, e.path.lu_fallbacks, e.path.factorize_s,
                  e.path.solve_s, e.path.reused_solves, e.path.cg_iterations, e.path.analyse_s,
                  static_cast<int>(e.path.history.size()), static_cast<int>(e.path.beyond_limit.size()));
      std::printf("%12s %12s %14s %12s %14s\n", "pressure_kPa", "turn_deg", "cells_turn_deg", "extra_deg",
                  "elongation_mm");
      // The cells' turn over the same length, as the weightless rod without ends integrates it
      // (caps rigid): the rod's bending without the end table, less with it, plus the end's turn.
      fem::CellRodSpec part = fem::tca_cell_rod(spec, cells);
      part.gravity_along_bend_m_s2 = part.gravity_along_axis_m_s2 = 0;
      for (const auto& s : e.states) {
        if (!s.is_output) continue;
        double cells_turn = NAN;
        part.ends.clear();
        if (const auto without = fem::solve_cell_rod(part, s.pressure_kPa); without.ok) {
          part.ends = {fem::end_table(e)};
          if (const auto with = fem::solve_cell_rod(part, s.pressure_kPa); with.ok)
            cells_turn = without.bending_angle_deg - with.bending_angle_deg + s.rotation_rad * softarm::fem::kDeg;
        }
        std::printf("%12.2f %12.4f %14.4f %12.4f %14.4f\n", s.pressure_kPa, s.rotation_rad * softarm::fem::kDeg, cells_turn,
                    s.rotation_rad * softarm::fem::kDeg - cells_turn, s.elongation_mm);
      }
    }
  fem::CellRodSpec rod = fem::tca_cell_rod(spec, cells, ends);
  fem::CellRodSpec weightless = rod;
  weightless.gravity_along_bend_m_s2 = weightless.gravity_along_axis_m_s2 = 0;
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<std::array<fem::CellRodState, 2>> curve;
  std::vector<double> pressures = {0.0};
  pressures.insert(pressures.end(), spec.output_pressures_kPa.begin(), spec.output_pressures_kPa.end());
  for (double p : pressures) curve.push_back({fem::solve_cell_rod(rod, p), fem::solve_cell_rod(weightless, p)});
  const double rod_seconds = bench::seconds_since(t0);
  std::printf("\ncell rod from %zu cells (%.1f s of cells, %.3f s for the curve; gravity %.3f along the bend, %.3f along z m/s^2)\n",
              cells.size(), cell_seconds, rod_seconds, rod.gravity_along_bend_m_s2, rod.gravity_along_axis_m_s2);
  std::printf("%12s %12s %10s %10s %14s %12s %10s\n", "pressure_kPa", "bending_deg", "tip_bend", "tip_z",
              "weightless_deg", "compared_deg", "error_%");
  for (const auto& [with, without] : curve) {
    if (!with.ok) {
      std::printf("%12.2f  %s\n", with.pressure_kPa, with.diagnosis.c_str());
      continue;
    }
    std::printf("%12.2f %12.3f %10.2f %10.2f %14.3f", with.pressure_kPa, with.bending_angle_deg, with.tip_along_bend_mm,
                with.tip_z_mm, without.bending_angle_deg);
    const auto it = reference.find(with.pressure_kPa);
    if (it != reference.end() && std::abs(it->second) > 1e-9)
      std::printf(" %12.3f %10.2f\n", it->second, 100 * (with.bending_angle_deg - it->second) / std::abs(it->second));
    else
      std::printf("\n");
  }
  return 0;
} catch (const fem::InputError& e) {
  std::fprintf(stderr, "%s\n", e.what());
  return 2;
}

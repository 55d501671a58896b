// The rod's bending error on optimised designs, and what mends it (docs/reduced-model.md, Where
// the rod's error comes from; docs/design-job.md, Check and correct on the 3D segment): the distal
// segment of each design bent by
//   - the search's rod (objectives::segment_rod's section, 17 nodes),
//   - the same rod with RodPiece::force_factor set to the lone RRA's
//     axisymmetric FEM calibration up to the 3D pressure (fem::calibrate_rra),
//   - the rod with ring-confined tube walls (ArmRodSpec::ring_confinement,
//     fem/reduced/confined_wall.hpp),
//   - with --with-3d, the 3D FEM (objectives::check_segment_in_3d: Hex20 at
//     2x2x2 points, level 1; minutes per design),
// all at the pressure where the main job's 3D checks stopped (the working
// pressure, or their limit point). The designs are the thesis', the thesis
// geometry with a Dragon Skin 20 sheath, and the optimised designs of the main
// job (rounds 0 and 1, and the other machine's optimum). Without --with-3d the
// 3D column is the one these runs recorded (the table in docs/reduced-model.md, Where the rod's
// error comes from), and the last lines give the ratio 3D/rod per design: check and correct's
// zeroth-order factor carries from one design to the next only as far as that ratio is constant.
//
//   build/benchmarks/bench_rod_error [--with-3d] [--design N] [--stiffness] [--cell-rod]
//
// --design N (1-5) runs only the N-th design; with --with-3d it also prints the
// 3D path's bending at every output beside the rod's at the same pressure, so
// the error can be followed along the curve, not only at its end.
//
// --cell-rod bends each distal segment by the cell rod (fem/reduced/cell_rod.hpp; cells and end
// cells as the fidelity ladder's rung: Hex20/P1 at 27 points with level 4's layers; its path at every
// output with --design N) along 8 steps to the recorded 3D pressure (about a minute per design).
//
// --cell-rod --reference also runs the whole segment on the fidelity ladder's reference mesh
// (Hex20/P1 at 27 points, level 1 with level 4's layers; ~10 minutes per design) to the same
// pressure, for the cell rod and the 3D check's 8-point mesh to be measured against.
//
// --stiffness measures what the confined rod still misses (docs/reduced-model.md, What the
// confined rod still misses): each design's distal segment under ten times its weight along its
// axis, by the 3D model (about a minute each) and by both rods; k = rod/3D stretch; then the
// confined rod with every fibre stiffened by its k, at the recorded 3D pressure.
#include <algorithm>
#include <cmath>
#include <array>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "benchmarks/bench_options.hpp"
#include "engine/design/design_config.hpp"
#include "engine/design/design_problem.hpp"
#include "fem/core/input_error.hpp"
#include "fem/core/json_reader.hpp"
#include "fem/reduced/arm_rod.hpp"
#include "fem/scenes/rra_calibration.hpp"
#include "fem/scenes/tca_cell_rod.hpp"
#include "objectives/solid_segment_check.hpp"
#include "fem/core/angles.hpp"

using namespace softarm;

namespace {
constexpr double kG = 9.80665;

struct Design {
  const char* name;
  std::vector<double> x;  // the design variables in design_variable_names() order; materials: 0 DS30, 1 DS20
  double pressure_kPa;    // where the 3D check stopped
  double recorded_3d_deg; // the 3D bending there (bench_rod_error --with-3d, Hex20 2x2x2 level 1)
};

// The distal segment's rod, free or with ring-confined walls.
fem::ArmRod distal_rod(const objectives::ArmCandidate& c, const fem::ForceFactor* factor, bool confined) {
  fem::ArmRodSpec spec;
  spec.ring_confinement = confined;
  spec.tube = c.tube, spec.sheath = c.sheath, spec.rings = c.rings;
  spec.nodes_per_segment = 17;
  fem::RodPiece piece;
  piece.kind = fem::RodPiece::Kind::tca;
  piece.design = c.design.segments[2];
  if (factor) piece.force_factor = *factor;
  spec.pieces = {piece};
  return fem::ArmRod(spec);
}

// The distal segment's rod bending at p (gravity against the bend, as the design's bending scene), deg.
// `stiffening` k > 1 scales every fibre's stress by k: the same as loads divided by k.
double rod_bending_deg(const objectives::ArmCandidate& c, double p_kPa, const fem::ForceFactor* factor,
                       bool confined = false, double stiffening = 1) {
  const fem::ArmRod rod = distal_rod(c, factor, confined);
  fem::RodLoad load;
  load.chamber_pressure_kPa = {{0.0, p_kPa / stiffening, p_kPa / stiffening}};
  load.gravity_m_s2 = {-kG / stiffening, 0.0};
  const fem::RodState st = rod.follow(load, 12);
  return rod.tip_rotation(st, load) * softarm::fem::kDeg;
}

// --stiffness: the distal segment hanging under ten times its weight along its axis, unpressurised:
// the tip's axial displacement (mm) by the rod and by the 3D model (as check_segment_in_3d's mesh).
double rod_axial_stretch_mm(const objectives::ArmCandidate& c, bool confined) {
  const fem::ArmRod rod = distal_rod(c, nullptr, confined);
  fem::RodLoad load;
  load.chamber_pressure_kPa = {{0.0, 0.0, 0.0}};
  load.gravity_m_s2 = {0.0, -10 * kG};
  return -(rod.solve(load, nullptr).z.back() + rod.length_mm());
}

double solid_axial_stretch_mm(const objectives::ArmCandidate& c) {
  fem::TcaSceneSpec spec = objectives::solid_segment_scene(c, 3);
  spec.chamber_pressure_kPa = {0.0, 1e-3, 1e-3};  // a path needs a pressure to ramp: 1 Pa is nothing here
  spec.gravity_m_s2 = Eigen::Vector3d(0.0, 0.0, -10 * kG);
  spec.output_pressures_kPa = {1e-3};
  return -fem::run_tca_scene(spec).states.back().tip_displacement_mm.z();
}

// The lone RRA of the distal segment in the axisymmetric FEM up to p: its force factor c(p).
fem::RraCalibration lone_rra(const objectives::ArmCandidate& c, double p_kPa) {
  fem::RraSceneSpec spec;
  spec.design = c.design.segments[2].actuator;
  spec.tube_material = c.tube;
  spec.ring_material = c.rings;
  spec.mesh_level = 1;
  spec.path.max_pressure_kPa = p_kPa;
  for (int k = 1; k <= 8; ++k) spec.path.output_pressures_kPa.push_back(p_kPa * k / 8);
  return fem::calibrate_rra(spec);
}

// --cell-rod: the distal segment's bending scene (as the 3D check's) on the fidelity ladder's
// reference mesh settings (Hex20/P1 at 27 points, level 1, level 4's layers), 8 steps to p_kPa.
fem::TcaSceneSpec reference_mesh_scene(const objectives::ArmCandidate& c, double p_kPa) {
  fem::TcaSceneSpec spec = objectives::solid_segment_scene(c, 3);
  spec.serendipity = true;
  spec.integration = fem::ElementIntegration::full;
  spec.mesh_level = 1;
  spec.axial_level = 4;
  fem::use_cell_rod_rung(spec);  // the same mesh, and the rung's end cells for the cell rod
  spec.chamber_pressure_kPa = {0.0, p_kPa, p_kPa};
  spec.output_pressures_kPa.clear();
  for (int k = 1; k <= 8; ++k) spec.output_pressures_kPa.push_back(p_kPa * k / 8);
  return spec;
}
}  // namespace

int main(int argc, char** argv) try {
  bool with_3d = false, stiffness = false, cell_rod = false, reference = false;
  std::size_t only = 0;  // 1-based; 0: every design
  CLI::App app{"the rod's bending error on optimised designs, and what mends it"};
  app.add_flag("--with-3d", with_3d, "also the 3D FEM (minutes per design)");
  app.add_option("--design", only, "only the N-th design (1-5); with --with-3d its 3D path at every output")
      ->check(CLI::Range(1, 5))
      ->default_str("every design");
  app.add_flag("--stiffness", stiffness, "each distal segment's stretch under ten times its weight, 3D and both rods");
  CLI::Option* cells = app.add_flag("--cell-rod", cell_rod, "bend each distal segment by the cell rod");
  app.add_flag("--reference", reference, "with --cell-rod: also the fidelity ladder's reference mesh (~10 minutes per design)")
      ->needs(cells);
  if (const auto code = bench::parse_or_exit(app, argc, argv)) return *code;
  const engine::DesignConfig config = engine::read_design_config(
      fem::load_json_file(std::string(SOFTARM_SOURCE_DIR) + "/configs/thesis_requirements.json"));
  std::vector<double> thesis_ds20 = engine::baseline_values(config);
  thesis_ds20.back() = 1;
  const std::vector<Design> designs = {
      {"thesis (DS30/DS30)", engine::baseline_values(config), 309.1, 99.1},
      {"thesis geometry, DS30/DS20", thesis_ds20, 309.1, 80.4},
      {"round 0, 1.364 kg (DS30/DS20)", {0.350108, 0.180914, 35, 0.343385, 4.37683, 0.523542, 0, 1}, 254.5, 75.8},
      {"round 1, 0.971 kg (DS20/DS20)", {0.336163, 0.167693, 21, 0.263945, 3.92867, 0.695315, 1, 1}, 344.7, 78.4},
      {"1.458 kg, other machine (DS30/DS20)", {0.341, 0.246, 34, 0.363, 3.71, 0.485, 0, 1}, 305.8, 84.4}};
  if (cell_rod) {
    std::printf("%-38s %8s %10s %12s %10s %8s %10s\n", "design (distal segment)", "p (kPa)", "rod (deg)",
                "cell rod", "3D (deg)", "error", "cells (s)");
    for (std::size_t n = 0; n < designs.size(); ++n) {
      if (only != 0 && n + 1 != only) continue;
      const Design& d = designs[n];
      const objectives::ArmCandidate c = engine::make_candidate(config, d.x);
      const fem::TcaSceneSpec spec = reference_mesh_scene(c, d.pressure_kPa);
      const fem::CellRodTcaResult r = fem::run_cell_rod_tca(spec);
      const double rod = rod_bending_deg(c, d.pressure_kPa, nullptr);
      if (!r.converged) {
        std::printf("%-38s %8.1f %10.2f  stopped: %s\n", d.name, d.pressure_kPa, rod, r.diagnosis.c_str());
        continue;
      }
      const double bend = r.curve.back().bending_angle_deg;
      std::printf("%-38s %8.1f %10.2f %12.2f %10.1f %+7.1f%% %10.1f\n", d.name, d.pressure_kPa, rod, bend,
                  d.recorded_3d_deg, 100 * (bend / d.recorded_3d_deg - 1), r.cell_seconds);
      std::fflush(stdout);
      if (only != 0)  // one design: its whole path, to set beside a --reference run's
        for (const auto& state : r.curve)
          std::printf("  cell rod %7.1f kPa %8.2f deg\n", state.pressure_kPa, state.bending_angle_deg);
      if (!reference) continue;
      const fem::TcaResult full = fem::run_tca_scene(spec);
      for (std::size_t k = 0; k < full.curve.size(); ++k) {
        const auto& s3 = full.curve[k];
        const fem::CellRodState* cr = nullptr;
        for (const auto& s : r.curve)
          if (std::abs(s.pressure_kPa - s3.pressure_kPa) < 1e-6) cr = &s;
        std::printf("  reference %7.1f kPa %8.2f deg  cell rod %8.2f deg (%+5.1f %%)\n", s3.pressure_kPa,
                    s3.bending_angle_deg, cr ? cr->bending_angle_deg : NAN,
                    cr ? 100 * (cr->bending_angle_deg / s3.bending_angle_deg - 1) : NAN);
      }
      std::printf("  reference: %s, %d dofs, %.0f s%s%s\n", to_string(full.path.outcome), full.dofs,
                  full.timings.total_s, full.path.diagnosis.empty() ? "" : ": ", full.path.diagnosis.c_str());
      std::fflush(stdout);
    }
    return 0;
  }
  if (stiffness) {
    std::printf("%-38s %11s %11s %11s %8s %8s %18s %10s\n", "design (distal segment), 10 g axial", "3D (mm)",
                "rod (mm)", "confined", "k rod", "k conf", "stiffened confined", "3D (deg)");
    for (std::size_t n = 0; n < designs.size(); ++n) {
      if (only != 0 && n + 1 != only) continue;
      const Design& d = designs[n];
      const objectives::ArmCandidate c = engine::make_candidate(config, d.x);
      const double solid = solid_axial_stretch_mm(c), free = rod_axial_stretch_mm(c, false),
                   held = rod_axial_stretch_mm(c, true);
      const double bend = rod_bending_deg(c, d.pressure_kPa, nullptr, true, held / solid);
      std::printf("%-38s %11.3f %11.3f %11.3f %8.3f %8.3f %9.2f (%+5.1f %%) %10.1f\n", d.name, solid, free, held,
                  free / solid, held / solid, bend, 100 * (bend / d.recorded_3d_deg - 1), d.recorded_3d_deg);
      // One design: the stiffened confined rod at the 3D check's outputs (24 steps to the working
      // pressure), to set beside `--design N --with-3d`'s 3D curve.
      if (only != 0)
        for (int i = 1; i <= config.check.pressure_steps; ++i) {
          const double p = config.check.working_pressure_kPa * i / config.check.pressure_steps;
          if (p > d.pressure_kPa + 1e-9) break;
          std::printf("  %7.1f kPa  stiffened confined rod %7.2f deg\n", p,
                      rod_bending_deg(c, p, nullptr, true, held / solid));
        }
      std::fflush(stdout);
    }
    return 0;
  }
  std::printf("%-38s %8s %10s %10s %10s %10s  lone RRA c(p) at p\n", "design (distal segment)", "p (kPa)",
              "rod (deg)", "rod c(p)", "confined", "3D (deg)");
  std::vector<std::array<double, 2>> ratios;  // 3D/rod, 3D/confined rod
  for (std::size_t n = 0; n < designs.size(); ++n) {
    if (only != 0 && n + 1 != only) continue;
    const Design& d = designs[n];
    const objectives::ArmCandidate c = engine::make_candidate(config, d.x);
    const fem::RraCalibration cal = lone_rra(c, d.pressure_kPa);
    const double rod = rod_bending_deg(c, d.pressure_kPa, nullptr);
    const double calibrated = rod_bending_deg(c, d.pressure_kPa, &cal.force_factor);
    const double confined = rod_bending_deg(c, d.pressure_kPa, nullptr, true);
    ratios.push_back({d.recorded_3d_deg / rod, d.recorded_3d_deg / confined});
    char recorded[32];
    std::snprintf(recorded, sizeof recorded, "%.1f (recorded)", d.recorded_3d_deg);
    std::string solid = recorded;
    if (with_3d) {
      const objectives::ArmMeasures m = objectives::evaluate_arm(c, config.check);
      const auto curve = [&](double p, double deg) {
        if (only == 0) return;
        const double r = objectives::bending_at_pressure(m.segments[2], p);
        std::printf("  3D path: %7.1f kPa  3D %7.2f deg  rod %7.2f deg  rod error %+6.1f %%\n", p, deg, r,
                    deg > 0 ? 100 * (r - deg) / deg : 0.0);
        std::fflush(stdout);
      };
      const auto sc = objectives::check_segment_in_3d(c, config.check, 3, m.segments[2], 1, curve);
      const double at = objectives::bending_at_pressure(m.segments[2], sc.reached_pressure_kPa);
      char buffer[96];
      std::snprintf(buffer, sizeof buffer, "%.2f at %.1f kPa (rod there %.2f), %.0f s", sc.bending_deg,
                    sc.reached_pressure_kPa, at, sc.seconds);
      solid = buffer;
    }
    std::printf("%-38s %8.1f %10.2f %10.2f %10.2f %10s  %.3f (%s)\n", d.name, d.pressure_kPa, rod, calibrated, confined,
                solid.c_str(), cal.force_factor.at(d.pressure_kPa), cal.outcome.c_str());
    std::fflush(stdout);
  }
  if (ratios.size() < 2) return 0;
  std::printf("\nrecorded 3D / rod, per design:\n");
  for (int k = 0; k < 2; ++k) {
    double lo = 1e300, hi = 0;
    std::printf("  %-14s", k == 0 ? "rod" : "confined rod");
    for (const auto& r : ratios) {
      std::printf(" %6.3f", r[k]);
      lo = std::min(lo, r[k]);
      hi = std::max(hi, r[k]);
    }
    std::printf("   max/min %.3f\n", hi / lo);
  }
  return 0;
} catch (const fem::InputError& e) {
  std::fprintf(stderr, "%s\n", e.what());
  return 2;
}

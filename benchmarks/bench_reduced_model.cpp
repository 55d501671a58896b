// Benchmark (not a test): the reduced rod model against the FEM on the thesis
// designs. Prints, with wall times: the lone thesis RRA's extension (rod
// uncalibrated vs the axisymmetric FEM), the thesis 3CA's bending curve by the
// rod (and, with --with-3d, by the 3D Hex27 FEM of configs/tca_thesis.json on
// the same pressures: minutes to tens of minutes), and the whole arm's mass and
// payload capacity; the thesis SPL pose (configs/spl_thesis_pose.json) by the
// spatial rod at several node counts and section grids (its discretisation
// error: the tip against the finest); with --out-of-plane also an out-of-plane bend,
// the 32 mm 3CA of configs/convergence with chambers 1 and 2 at 200 and
// 100 kPa, by the spatial rod and by the 3D Hex27 full model (bending angle
// and the azimuth of the tip's displacement).
//
// Usage (from the repository root): bench_reduced_model [--with-3d] [--out-of-plane] [--repeat N]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "benchmarks/bench_options.hpp"
#include "benchmarks/bench_stats.hpp"
#include "fem/core/input_error.hpp"
#include "fem/scenes/scene_config.hpp"
#include "fem/scenes/reduced_scenes.hpp"
#include "fem/reduced/spatial_rod.hpp"
#include "fem/scenes/tca_scene.hpp"
#include "fem/scenes/rra_calibration.hpp"
#include "objectives/arm_evaluation.hpp"
#include "objectives/payload_capacity.hpp"
#include "fem/core/angles.hpp"

using namespace softarm;
using Clock = std::chrono::steady_clock;

namespace {
}  // namespace

int main(int argc, char** argv) try {
  bool with_3d = false, out_of_plane = false;
  int repeat = 5;
  CLI::App app{"the reduced rod model against the FEM on the thesis designs (run from the repository root)"};
  app.add_flag("--with-3d", with_3d, "also the thesis 3CA's bending by the 3D Hex27 FEM (minutes to tens of minutes)");
  app.add_flag("--out-of-plane", out_of_plane, "also an out-of-plane bend of the 32 mm 3CA, spatial rod against 3D");
  app.add_option("--repeat", repeat, "timed runs of each rod (the median is printed)")->check(CLI::Range(1, 1000));
  if (const auto code = bench::parse_or_exit(app, argc, argv)) return *code;
  const fem::Material ds30 = fem::builtin_material("dragon_skin_30", "bench"), abs = fem::builtin_material("digital_abs", "bench");

  // 1. Lone RRA: rod vs axisymmetric FEM (level 1).
  fem::RraSceneSpec rra;
  rra.tube_material = ds30;
  rra.ring_material = abs;
  rra.path.max_pressure_kPa = 206.8;
  rra.path.output_pressures_kPa = {68.9, 137.9, 206.8};
  const fem::RraCalibration cal = fem::calibrate_rra(rra);
  const fem::FibreLaw law(*ds30.law);
  std::vector<double> rod_times;
  double rod_ext = 0;
  for (int k = 0; k < repeat; ++k) {
    const auto t = Clock::now();
    rod_ext = fem::rod_rra_extension_mm(rra.design, law, 206.8, 1.0);
    rod_times.push_back(bench::seconds_since(t));
  }
  std::printf("thesis RRA at 206.8 kPa: FEM (axisymmetric Q2/P1 level 1, %d dofs) %.2f mm in %.3f s; rod %.2f mm "
              "(%+.1f %%) in %.4f s (median of %d)\n",
              cal.dofs, cal.fem_extension_mm.back(), cal.fem_seconds, rod_ext,
              100 * (rod_ext / cal.fem_extension_mm.back() - 1), bench::median(rod_times), repeat);

  // 2. Thesis 3CA: top clamped, chambers 2 and 3, gravity against the bend.
  fem::ArmRodSpec spec;
  spec.pieces = {fem::RodPiece{}};
  spec.tube = spec.sheath = ds30;
  spec.rings = abs;
  spec.nodes_per_segment = 17;
  const fem::ArmRod rod(spec);
  fem::RodLoad load;
  load.chamber_pressure_kPa = {{0, 344.7, 344.7}};
  load.gravity_m_s2 = {-9.80665, 0};
  std::vector<double> p, angle, times;
  for (int k = 0; k < repeat; ++k) {
    p.clear();
    angle.clear();
    const auto t = Clock::now();
    rod.follow(load, 10, [&](double f, const fem::RodState& st) {
      p.push_back(f * 344.7);
      angle.push_back(rod.tip_rotation(st, load) * softarm::fem::kDeg);
    });
    times.push_back(bench::seconds_since(t));
  }
  double p90 = -1;
  for (std::size_t i = 1; i < p.size(); ++i)
    if (p90 < 0 && angle[i] >= 90) p90 = p[i - 1] + (90 - angle[i - 1]) * (p[i] - p[i - 1]) / (angle[i] - angle[i - 1]);
  std::printf("thesis 3CA by the rod: %.3f s (median of %d), mass %.1f g, 90 deg at %.1f kPa\n", bench::median(times), repeat,
              rod.mass_kg() * 1e3, p90);
  std::printf("  pressure_kPa  rod_deg%s\n", with_3d ? "  fem3d_deg" : "");
  std::vector<double> fem_angle(p.size(), std::nan(""));
  double fem_seconds = 0, fem_p90 = -1;
  int fem_dofs = 0;
  if (with_3d) {
    fem::SceneConfig config = fem::load_scene_config("configs/tca_thesis.json");
    config.tca.output_pressures_kPa = p;
    const auto t = Clock::now();
    const fem::TcaResult r = fem::run_tca_scene(config.tca);
    fem_seconds = bench::seconds_since(t);
    fem_dofs = r.dofs;
    for (const auto& s : r.curve)
      for (std::size_t i = 0; i < p.size(); ++i)
        if (std::abs(s.pressure_kPa - p[i]) < 1e-6) fem_angle[i] = s.bending_angle_deg;
    if (const auto q = fem::pressure_at_bending(r.states, 90)) fem_p90 = *q;
  }
  for (std::size_t i = 0; i < p.size(); ++i) {
    std::printf("  %12.2f  %7.2f", p[i], angle[i]);
    if (with_3d) std::printf("  %9.2f", fem_angle[i]);
    std::printf("\n");
  }
  if (with_3d)
    std::printf("3D FEM (%d dofs): %.1f s, 90 deg at %.1f kPa; rod/3D cost ratio 1/%.0f, 90-deg pressure %+.1f %%\n",
                fem_dofs, fem_seconds, fem_p90, fem_seconds / bench::median(times), 100 * (p90 / fem_p90 - 1));

  // 3. The thesis arm: mass and payload capacity.
  objectives::ArmCandidate arm;
  nlohmann::json g = {{"wall_thickness_normalised", 0.466}, {"end_cap_thickness_normalised", 0.25},
                      {"ring_count_normalised", 0.375}, {"ring_thickness_normalised", 0.4}};
  fem::JsonReader reader(g, "geometry");
  arm.design = fem::read_spl_design(reader);
  arm.tube = arm.sheath = ds30;
  arm.rings = arm.connector = abs;
  objectives::EvaluationSettings settings;
  const fem::ArmRod whole = objectives::arm_rod(arm, settings);
  objectives::PayloadSettings ps;
  ps.sheath_allowable_stretch = (1 + ds30.elongation_at_break) / settings.safety_factor;
  std::vector<double> payload_times;
  objectives::PayloadResult payload;
  for (int k = 0; k < repeat; ++k) {
    const auto t = Clock::now();
    payload = objectives::payload_capacity(whole, ps);
    payload_times.push_back(bench::seconds_since(t));
  }
  std::printf("thesis arm: mass %.3f kg, payload capacity %.3f kg at %.1f kPa (%s), %d rod solves, %.3f s (median of %d)\n",
              whole.mass_kg(), payload.capacity_kg, payload.lift_pressure_kPa, payload.limited_by.c_str(),
              payload.rod_solves, bench::median(payload_times), repeat);

  // 4. The thesis SPL pose by the spatial rod: discretisation convergence of the tip.
  const fem::SceneConfig pose = fem::load_scene_config("configs/spl_thesis_pose.json");
  struct Run { int nodes, cells; };
  const std::vector<Run> runs{{9, 24}, {17, 16}, {17, 24}, {17, 48}, {33, 24}, {65, 48}};
  std::vector<fem::ReducedSplResult> results;
  std::vector<double> seconds;
  for (const Run& run : runs) {
    std::vector<double> t;
    for (int k = 0; k < repeat; ++k) {
      results.push_back(fem::run_reduced_spl(pose.spl, run.nodes, run.cells));
      t.push_back(results.back().seconds);
    }
    seconds.push_back(bench::median(t));
  }
  const Eigen::Vector3d finest = results.back().joints.back().pose.position_mm;
  const double reach = (finest - results.back().joints.front().pose.position_mm).norm();
  std::printf("thesis SPL pose by the spatial rod (tip; error against %d nodes x %d cells, relative to the shoulder-tip "
              "distance %.1f mm):\n  nodes/segment  cells  tip_x_mm  tip_y_mm  tip_z_mm  tilt_deg  error_%%  time_s (median of %d)\n",
              runs.back().nodes, runs.back().cells, reach, repeat);
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const auto& r = results[(i + 1) * repeat - 1];
    const auto& tip = r.joints.back().pose;
    std::printf("  %13d  %5d  %8.2f  %8.2f  %8.2f  %8.2f  %7.3f  %6.3f%s\n", runs[i].nodes, runs[i].cells,
                tip.position_mm.x(), tip.position_mm.y(), tip.position_mm.z(), tip.tilt_deg,
                100 * (tip.position_mm - finest).norm() / reach, seconds[i], r.final_state.converged ? "" : "  (stopped)");
  }
  if (!out_of_plane) return 0;

  // 5. Out of plane: the 32 mm 3CA, chambers 1 and 2 at 200 and 100 kPa (the bend's azimuth is set
  // by the two chambers' moments, between the planes of symmetry).
  fem::SceneConfig cut = fem::load_scene_config("configs/convergence/tca_32mm.json");
  cut.tca.chamber_pressure_kPa = {200, 100, 0};
  cut.tca.output_pressures_kPa = {50, 100, 150, 200};
  const auto t3 = Clock::now();
  const fem::TcaResult fem3d = fem::run_tca_scene(cut.tca);
  const double fem3d_s = bench::seconds_since(t3);
  fem::ArmRodSpec one;
  one.pieces = {fem::RodPiece{}};
  one.pieces[0].design = cut.tca.design;
  one.tube = one.sheath = ds30;
  one.rings = abs;
  one.nodes_per_segment = 17;
  const fem::SpatialRod spatial(one);
  fem::SpatialRodLoad sl;
  sl.chamber_pressure_kPa = {{200, 100, 0}};
  sl.clamp_position_mm = {0, 0, cut.tca.design.actuator.length_mm};
  std::vector<fem::SpatialRodState> rod_states;
  std::vector<double> rod_pressure;
  const auto t4 = Clock::now();
  spatial.follow(sl, 4, [&](double f, const fem::SpatialRodState& st) {
    rod_states.push_back(st);
    rod_pressure.push_back(200 * f);
  });
  const double rod_s = bench::seconds_since(t4);
  std::printf("32 mm 3CA, chambers 1, 2 at 200, 100 kPa: 3D %s (%d dofs, %s) %.1f s; spatial rod %.3f s\n",
              fem3d.element_name.c_str(), fem3d.dofs, fem3d.model.name.c_str(), fem3d_s, rod_s);
  std::printf("  chamber1_kPa  fem_deg  rod_deg  fem_azimuth_deg  rod_azimuth_deg  fem_tip_u_mm  rod_tip_u_mm\n");
  const int tip = spatial.node_count() - 1;
  for (const fem::TcaState& f : fem3d.curve) {
    std::size_t i = 0;
    while (i < rod_states.size() && std::abs(rod_pressure[i] - f.pressure_kPa) > 1e-6) ++i;
    if (i == rod_states.size()) continue;  // the rest state, or a pressure the rod did not stop at
    const Eigen::Vector3d uf = f.tip_displacement_mm, ur = rod_states[i].position.back();
    std::printf("  %12.1f  %7.3f  %7.3f  %15.2f  %15.2f  %12.3f  %12.3f\n", f.pressure_kPa,
                f.bending_angle_deg, spatial.tilt_deg(rod_states[i], sl, tip),
                std::atan2(uf.y(), uf.x()) * softarm::fem::kDeg, std::atan2(ur.y(), ur.x()) * softarm::fem::kDeg, uf.norm(), ur.norm());
  }
  return 0;
} catch (const fem::InputError& e) {
  std::fprintf(stderr, "%s\n", e.what());
  return 2;
}

// The SPL pose on the spatial cell rod (fem/scenes/spl_cell_rod.hpp): its cells' cost and
// the tip's path, and with --compare the joints against a 3D run's summary.json (the
// fidelity ladder's reference, configs/convergence/spl_thesis_pose_axial3.json, whose joints
// benchmarks/data/spl_thesis_pose_axial3_joints.json keeps).
//
//   bench_spl_cell_rod [config] [--full] [--cell-levels N] [--threads N] [--compare summary.json]
//                      [--torsion-scales 1,0.5,2] [--tables] [--save-cells F | --load-cells F] [--rigid-caps]
//                      [--axial-level N] [--end-rings N] [--moments] [--cells-torsion]
//   --full: full-model cells even where a segment's pressures allow a half model
//   --save-cells F / --load-cells F: keep the cells' tables in a JSON file / pose from one (no cells run)
//   --tables: print every cell's table (stretch, curvature vector, compliances) at its outputs
//   --axial-level N / --end-rings N: the cells' layers as the 3D mesh's at level N / ends through N rings
//     (0: none), instead of the 3CA ladder's cell-rod rung's
//   --moments: the moment (section frame) and tension the rod puts on each cell at full pressure,
//     for bench_tca_cell --moment-Nmm (how far each cell's tangent compliance carries)
//   --rigid-caps: pose without the end cells' tables (the cells' response up to rigid caps)
//   --cells-torsion: pose with the cells' GJ over the bonded ends too (their end cells' twist compliance
//     left out, as before that was measured: fem/scenes/twist_compliance.hpp)
//   --torsion-scales: pose again with each segment's GJ times each factor (the cells once)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "benchmarks/bench_options.hpp"
#include "benchmarks/bench_scene.hpp"
#include "fem/core/input_error.hpp"
#include "fem/core/json_reader.hpp"
#include "fem/core/parallel.hpp"
#include "fem/reduced/cell_tables_json.hpp"
#include "fem/scenes/scene_config.hpp"
#include "fem/scenes/spl_cell_rod.hpp"
#include "fem/scenes/tca_cell.hpp"
#include "fem/core/angles.hpp"

using namespace softarm;

int main(int argc, char** argv) try {
  std::string config = "configs/spl_thesis_pose.json", compare, save_cells, load_cells;
  bool full = false, tables = false, rigid_caps = false, moments = false, cells_torsion = false;
  int cell_levels = 16, axial_level = 0, end_rings = -1, threads = fem::thread_count();
  std::vector<double> torsion_scales;
  CLI::App app{"the SPL pose on the spatial cell rod: its cells' cost and the tip's path"};
  app.add_option("config", config, "an spl scene config");
  app.add_option("--compare", compare, "a 3D run's summary.json (or the ladder's joints file) to set the joints against")
      ->check(CLI::ExistingFile);
  app.add_flag("--full", full, "full-model cells even where a segment's pressures allow a half model");
  app.add_flag("--tables", tables, "print every cell's table at its outputs");
  app.add_flag("--rigid-caps", rigid_caps, "pose without the end cells' tables");
  app.add_flag("--moments", moments, "the moment and tension the rod puts on each cell at full pressure");
  app.add_flag("--cells-torsion", cells_torsion, "pose with the cells' GJ over the bonded ends too");
  app.add_option("--axial-level", axial_level, "the cells' layers as the 3D mesh's at level N")
      ->check(CLI::Range(1, 8))
      ->default_str("the cell-rod rung's");
  app.add_option("--end-rings", end_rings, "ends through N rings (0: none)")
      ->check(CLI::Range(0, 100))
      ->default_str("the cell-rod rung's");
  CLI::Option* save = app.add_option("--save-cells", save_cells, "keep the cells' tables in this JSON file");
  app.add_option("--load-cells", load_cells, "pose from the cells' tables in this JSON file (no cells run)")
      ->check(CLI::ExistingFile)
      ->excludes(save);
  app.add_option("--torsion-scales", torsion_scales, "pose again with each segment's GJ times each factor")
      ->delimiter(',')
      ->check(bench::Positive)
      ->default_str("1");
  app.add_option("--cell-levels", cell_levels, "outputs along the cells' pressure ramp")->check(CLI::Range(1, 256));
  app.add_option("--threads", threads, "threads")->check(CLI::Range(1, 256));
  if (const auto code = bench::parse_or_exit(app, argc, argv)) return *code;
  fem::set_thread_count(threads);
  const auto scene = bench::scene_of_kind(config, "spl", "bench_spl_cell_rod");
  if (!scene) return 2;
  fem::SplSceneSpec spec = scene->spl;
  if (full) spec.allow_symmetry = false;
  fem::SplCells cells;
  if (load_cells.empty()) {
    cells = fem::spl_cells(spec, cell_levels, [&](fem::TcaSceneSpec& s) {
      if (axial_level > 0) s.axial_level = axial_level;
      if (end_rings >= 0) s.cell_rod_end_rings = end_rings;
    });
  } else {
    cells.rod.gravity_m_s2 = spec.gravity_m_s2;
    cells.rod.tip_mass_kg = spec.tip_mass_kg;
    fem::read_cell_tables(fem::load_json_file(load_cells), cells.rod);
    // Tables saved before the cells had their torsion: the cells' GJ now.
    for (std::size_t p = 1; p < cells.rod.pieces.size(); p += 2)
      for (auto& c : cells.rod.pieces[p].cells)
        if (c.torsion_compliance_per_Nmm2 == 0) {
          const fem::TcaSceneSpec scene = fem::spl_segment_cell_scene(spec, static_cast<int>(p / 2), cell_levels);
          const int ring = static_cast<int>(std::lround(c.z_mm / scene.design.actuator.pitch() + 0.5));
          c.torsion_compliance_per_Nmm2 = 1 / fem::cell_torsion_stiffness(scene, ring);
        }
  }
  if (!save_cells.empty()) std::ofstream(save_cells) << fem::cell_tables_json(cells.rod).dump(1);
  std::printf("%s: %d cells (largest %d dofs), %d end cells (largest %d dofs), %.1f s, threads %d\n", config.c_str(),
              cells.cells, cells.largest_cell_dofs, cells.end_cells, cells.largest_end_cell_dofs, cells.seconds,
              fem::thread_count());
  if (!cells.end_cells_note.empty()) std::printf("(%s)\n", cells.end_cells_note.c_str());
  for (std::size_t p = 0; p < cells.rod.pieces.size(); ++p)
    for (const auto& e : cells.rod.pieces[p].ends)
      if (!e.level.empty())
        std::printf("segment %zu %s end, %.2f mm: at level %.3f turns (%.5f, %.5f) rad, elongates %.4f mm\n", p / 2 + 1,
                    e.at_top ? "top" : "bottom", e.length_mm, e.level.back(), e.rotation_rad.back().x(),
                    e.rotation_rad.back().y(), e.elongation_mm.back());
  for (std::size_t p = 0; p < cells.rod.pieces.size(); ++p)
    for (const auto& e : cells.rod.pieces[p].ends)
      if (e.twist_compliance_per_Nmm > 0)
        std::printf("segment %zu %s end: twists %.4e rad/(N·mm) at rest, its cells over the same length %.4e\n", p / 2 + 1,
                    e.at_top ? "top" : "bottom", e.twist_compliance_per_Nmm,
                    e.length_mm * cells.rod.pieces[p].cells[e.at_top ? cells.rod.pieces[p].cells.size() - 1 : 0]
                                      .torsion_compliance_per_Nmm2);
  if (rigid_caps)
    for (auto& p : cells.rod.pieces) p.ends.clear();
  if (cells_torsion)
    for (auto& p : cells.rod.pieces)
      for (auto& e : p.ends) e.twist_compliance_per_Nmm = 0;
  for (int n = 0; n < 3; ++n) {
    std::printf("segment %d: %s model, rings", n + 1, cells.half_model[n] ? "half" : "full");
    for (int ring : cells.rings[n]) std::printf(" %d", ring);
    std::printf("\n");
  }
  if (tables)
    for (const auto& piece : cells.rod.pieces)
      for (const auto& c : piece.cells) {
        std::printf("\ncell at z = %.3f mm (GJ %.4g N·mm²)\n%8s %10s %12s %12s %12s %12s %12s %12s %12s\n", c.z_mm,
                    1 / c.torsion_compliance_per_Nmm2, "level", "stretch", "kx_per_mm", "ky_per_mm", "Cxx", "Cxy", "Cyx",
                    "Cyy", "C_axial");
        for (std::size_t i = 0; i < c.level.size(); ++i) {
          const auto& k = c.curvature_per_mm[i];
          const auto& m = c.bending_compliance_per_Nmm2[i];
          std::printf("%8.4f %10.6f %12.4e %12.4e %12.4e %12.4e %12.4e %12.4e %12.4e\n", c.level[i], c.stretch[i], k.x(),
                      k.y(), m(0, 0), m(0, 1), m(1, 0), m(1, 1), c.axial_compliance_per_N[i]);
        }
      }
  if (moments) {  // the rod up its ramp to full pressure, then each cell's load in its section's frame
    fem::SpatialCellRodState s;
    for (double level : spec.output_levels) s = fem::solve_spatial_cell_rod(cells.rod, level, s.ok ? &s : nullptr);
    if (s.ok) {
      std::printf("\nloads on the cells at full pressure (section frame):\n%8s %8s %12s %12s %12s\n", "segment",
                  "z_mm", "Mx_Nmm", "My_Nmm", "Mz_Nmm");
      for (std::size_t p = 1; p < cells.rod.pieces.size(); p += 2) {
        const auto& piece = cells.rod.pieces[p];
        const int first = s.piece_first_node[p], count = s.piece_last_node[p] - first;
        for (const auto& c : piece.cells) {
          const int i = first + std::clamp(static_cast<int>((piece.length_mm - c.z_mm) / piece.length_mm * count), 0, count - 1);
          const Eigen::Vector3d m = s.frame[i].transpose() * s.moment_Nmm[i];
          std::printf("%8zu %8.2f %12.1f %12.1f %12.1f\n", p / 2 + 1, c.z_mm, m.x(), m.y(), m.z());
        }
      }
    }
  }
  nlohmann::json reference;
  if (!compare.empty()) reference = fem::load_json_file(compare);
  if (torsion_scales.empty()) torsion_scales = {1.0};
  int rc = 0;
  for (double scale : torsion_scales) {
    fem::SplCells scaled = cells;
    for (auto& piece : scaled.rod.pieces)
      for (auto& c : piece.cells) c.torsion_compliance_per_Nmm2 /= scale;
    const fem::SplCellRodResult r = fem::pose_spl_cell_rod(scaled, spec.output_levels);
    std::printf("\nGJ x %.3g: rod %.3f s; mass %.1f g\n", scale, r.rod_seconds, 1e3 * r.mass_kg);
    std::printf("%10s %10s %10s %10s %10s %6s\n", "level", "tip_x_mm", "tip_y_mm", "tip_z_mm", "tilt_deg", "iter");
    for (const auto& s : r.curve)
      std::printf("%10.4f %10.2f %10.2f %10.2f %10.2f %6d\n", s.load_fraction, s.tip_position_mm.x(),
                  s.tip_position_mm.y(), s.tip_position_mm.z(), s.tip_tilt_deg, s.newton_iterations);
    std::printf("outcome: %s%s%s\n", fem::to_string(r.outcome), r.diagnosis.empty() ? "" : " — ", r.diagnosis.c_str());
    rc = std::max(rc, r.converged ? 0 : 1);
    double sum = 0;
    int count = 0;
    for (std::size_t j = 0; j < r.joints.size(); ++j) {
      const auto& p = r.joints[j].pose.position_mm;
      std::printf("%-36s (%8.2f, %8.2f, %8.2f) mm, tilt %7.2f°", r.joints[j].name.c_str(), p.x(), p.y(), p.z(),
                  r.joints[j].pose.tilt_deg);
      if (!reference.is_null() && j < reference["joints"].size()) {
        const auto& q = reference["joints"][j]["position_mm"];
        const double d = std::hypot(p.x() - q[0].get<double>(), p.y() - q[1].get<double>(), p.z() - q[2].get<double>());
        std::printf("   reference (%8.2f, %8.2f, %8.2f), %6.1f mm off", q[0].get<double>(), q[1].get<double>(),
                    q[2].get<double>(), d);
        if (j > 0) sum += d, ++count;  // the shoulder is clamped in both
      }
      std::printf("\n");
    }
    // Each segment's own bend: the rotation from its top joint's frame to its bottom joint's.
    for (std::size_t j = 0; j + 1 < r.joints.size(); j += 2) {
      const Eigen::Matrix3d rel = r.joints[j].pose.rotation.transpose() * r.joints[j + 1].pose.rotation;
      const Eigen::AngleAxisd a(rel);
      std::printf("segment %zu bends %7.2f° about (%6.3f, %6.3f, %6.3f) in its top frame", j / 2 + 1,
                  a.angle() * softarm::fem::kDeg, a.axis().x(), a.axis().y(), a.axis().z());
      if (!reference.is_null() && reference["joints"][j].contains("rotation_matrix")) {
        Eigen::Matrix3d top, bottom;
        for (int i = 0; i < 3; ++i)
          for (int k = 0; k < 3; ++k) {
            top(i, k) = reference["joints"][j]["rotation_matrix"][i][k].get<double>();
            bottom(i, k) = reference["joints"][j + 1]["rotation_matrix"][i][k].get<double>();
          }
        const Eigen::AngleAxisd b(top.transpose() * bottom);
        std::printf("; reference %7.2f° about (%6.3f, %6.3f, %6.3f)", b.angle() * softarm::fem::kDeg, b.axis().x(),
                    b.axis().y(), b.axis().z());
      }
      std::printf("\n");
    }
    if (count > 0) {
      const auto& q = reference["joints"].back()["position_mm"];
      const double travel = std::hypot(q[0].get<double>(), q[1].get<double>(), q[2].get<double>());
      const auto& p = r.joints.back().pose.position_mm;
      const double tip = std::hypot(p.x() - q[0].get<double>(), p.y() - q[1].get<double>(), p.z() - q[2].get<double>());
      std::printf("tip %.1f mm off, %.1f %% of the reference tip's %.0f mm travel; joints %.1f mm off on average\n", tip,
                  100 * tip / travel, travel, sum / count);
      // The reference's own estimates of the converged tip, where its file keeps them
      // (benchmarks/data/spl_thesis_pose_axial3_joints.json).
      if (reference.contains("richardson_tip_mm"))
        for (const auto& [order, q] : reference["richardson_tip_mm"].items())
          std::printf("tip %.1f mm off the reference's Richardson tip at %s\n",
                      std::hypot(p.x() - q[0].get<double>(), p.y() - q[1].get<double>(), p.z() - q[2].get<double>()),
                      order.c_str());
    }
  }
  return rc;
} catch (const fem::InputError& e) {
  std::fprintf(stderr, "%s\n", e.what());
  return 2;
}

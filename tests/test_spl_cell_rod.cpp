// The SPL on the spatial cell rod (fem/scenes/spl_cell_rod.hpp): with only its distal
// segment pressurised and no gravity, the two upper segments stay straight and the distal one
// bends exactly as the planar cell rod (tca_cell.hpp) bends the same 3CA from the same cells and
// end cells: the segments' order, the chambers' numbering, the bend's direction, the joints' frames
// and the end tables' turn.
#include <catch2/catch.hpp>
#include <Eigen/Geometry>
#include <cmath>
#include <string>
#include <vector>

#include "fem/core/json_reader.hpp"
#include "fem/scenes/scene_config.hpp"
#include "fem/scenes/solver_work_json.hpp"
#include "fem/scenes/spl_cell_job.hpp"
#include "fem/scenes/spl_cell_rod.hpp"
#include "fem/scenes/tca_cell_rod.hpp"
#include "support/short_spl.hpp"

using namespace softarm::fem;
using nlohmann::json;

TEST_CASE("a cell job's solver work travels between processes with its table, exactly", "[cell][spl]") {
  // MPI ranks return their cells as text (spl_cell_job.hpp): the counts and seconds come back too.
  CellJobResult r;
  r.dofs = 15444;
  r.work.paths = 1;
  r.work.dofs = 15444;
  r.work.newton_iterations = 123;
  r.work.factorizations = 66;
  r.work.shifted_factorizations = 70;
  r.work.lu_fallbacks = 3;
  r.work.cg_iterations = 1111;
  r.work.seconds = 48.812345678901234;
  r.work.longest_seconds = 48.812345678901234;
  const CellJobResult back = cell_job_from_text(to_text(r));
  CHECK(back.work.paths == 1);
  CHECK(back.work.dofs == 15444);
  CHECK(back.work.newton_iterations == 123);
  CHECK(back.work.factorizations == 66);
  CHECK(back.work.shifted_factorizations == 70);
  CHECK(back.work.lu_fallbacks == 3);
  CHECK(back.work.cg_iterations == 1111);
  CHECK(back.work.seconds == r.work.seconds);
  CHECK(back.work.longest_seconds == r.work.longest_seconds);
  SolverWork sum;
  sum.add(back.work);
  sum.add(back.work);
  CHECK(sum.paths == 2);
  CHECK(sum.newton_iterations == 246);
  CHECK(sum.seconds == 2 * r.work.seconds);
  CHECK(sum.longest_seconds == r.work.longest_seconds);  // the slowest of two equal cells: one's time
}

TEST_CASE("a cell rod's work keeps its slowest cell's seconds beside their sum", "[cell]") {
  // bench_speed's bound on a cell rod's wall time, max(longest, summed / threads), reads both.
  const PressurePathResult path;
  SolverWork ends, rings;
  ends.add(path, 100, 15.25);
  ends.add(path, 100, 8.5);
  rings.add(path, 50, 4.0);
  rings.add(path, 50, 4.5);
  CHECK(ends.longest_seconds == 15.25);
  CHECK(rings.longest_seconds == 4.5);
  SolverWork all = rings;
  all.add(ends);
  CHECK(all.paths == 4);
  CHECK(all.seconds == 32.25);
  CHECK(all.longest_seconds == 15.25);
  CHECK(solver_work_from_json(solver_work_to_json(all)).longest_seconds == 15.25);
}

TEST_CASE("The SPL cell rod bends a lone distal segment as the 3CA cell rod does", "[cell][spl][long]") {
  SplSceneSpec spl = load_scene_config(std::string(SOFTARM_SOURCE_DIR) + "/configs/spl_thesis_pose.json").spl;
  spl.chamber_pressure_kPa = {0, 0, 0, 0, 0, 0, 0, 59, 59};
  spl.gravity_m_s2.setZero();
  spl.output_levels = {0.25, 0.5, 0.75, 1.0};
  // What is compared is one model read two ways, on any mesh: level 1's layers (not the rung's 4)
  // keep the cells a sixth of the cost.
  const auto coarse_layers = [](TcaSceneSpec& s) { s.axial_level = 1; };
  const SplCells cells = spl_cells(spl, 4, coarse_layers);
  const SplCellRodResult r = pose_spl_cell_rod(cells, spl.output_levels);
  INFO(r.diagnosis);
  REQUIRE(r.converged);
  REQUIRE(r.joints.size() == 6);
  CHECK(cells.half_model[2]);

  TcaSceneSpec tca;
  tca.design = spl.design.segments[2];
  tca.tube_material = spl.tube_material;
  tca.ring_material = spl.ring_material;
  tca.sheath_material = spl.sheath_material;
  tca.chamber_pressure_kPa = {0, 59, 59};
  tca.gravity_m_s2.setZero();
  for (double level : spl.output_levels) tca.output_pressures_kPa.push_back(59 * level);
  tca.newton = spl.newton;
  tca.steps = spl.steps;
  tca.limit = spl.limit;
  use_cell_rod_rung(tca);
  coarse_layers(tca);
  const CellRodTcaResult planar = run_cell_rod_tca(tca);
  REQUIRE(planar.converged);
  // Both take end cells: the SPL's distal segment bonded to its connector at the top and free at the
  // tip, as the 3CA's clamped and free ends.
  CHECK(planar.end_rings == 2);
  CHECK(cells.end_rings[2] == 2);
  CHECK(cells.end_cells == 6);

  // The upper segments and connectors hang straight: segment 3's top is where it was.
  const Eigen::Vector3d top = r.joints[4].pose.position_mm;
  CHECK((top - Eigen::Vector3d(0, 0, spl.design.segment_extent(3)[1])).norm() < 1e-9);
  CHECK(r.joints[4].pose.tilt_deg < 1e-9);
  const Eigen::Vector3d bend = tca_bend_direction(tca.chamber_pressure_kPa).normalized();
  for (std::size_t i = 1; i < r.curve.size(); ++i) {
    const SplState& s = r.curve[i];
    const CellRodState& p = planar.curve.at(i);
    INFO("level " << s.load_fraction << ": SPL tip " << s.tip_position_mm.transpose() << ", tilt " << s.tip_tilt_deg
                  << "°; 3CA cell rod " << p.bending_angle_deg << "°, tip " << p.tip_along_bend_mm << " along the bend, "
                  << p.tip_z_mm << " up");
    CHECK(s.load_fraction * 59 == Approx(p.pressure_kPa));
    CHECK(s.tip_tilt_deg == Approx(p.bending_angle_deg).margin(1e-3));
    CHECK(s.tip_position_mm.dot(bend) == Approx(p.tip_along_bend_mm).margin(1e-2));
    CHECK(s.tip_position_mm.z() - top.z() == Approx(p.tip_z_mm - tca.design.actuator.length_mm).margin(1e-2));
    CHECK(std::abs(s.tip_position_mm.dot(Eigen::Vector3d::UnitZ().cross(bend))) < 1e-6);  // in the bend plane
  }
}

namespace {
/// Segment n's (1..3) own bend: the angle of its bottom joint's rotation against its top joint's.
double segment_bend_deg(const std::vector<SplJoint>& joints, int n) {
  const Eigen::Matrix3d relative = joints[2 * n - 2].pose.rotation.transpose() * joints[2 * n - 1].pose.rotation;
  return Eigen::AngleAxisd(relative).angle() * 180 / 3.14159265358979323846;
}
}  // namespace

TEST_CASE("End cells bonded to the connectors bend a short SPL as its 3D model does where rigid caps do not", "[cell][spl][long]") {
  // Measured: segments 1 and 2 bend 5.79° and 5.35° in 3D; the cell rod with end cells 5.70° and 5.26°
  // (−1.6 %, −1.7 %), with rigid caps 4.85° and 4.79° (−16 %, −10 %); the tip 0.3 mm off (2.5 % of its
  // 14 mm travel) against 1.7 mm (12.8 %). Segment 3's own bend is not compared: the tip's Kabsch
  // frame tilts with its cap, which chamber 7 alone bulges on one side (3D 7.2°, rod 3.9°).
  const SplSceneSpec spec = softarm::test::short_spl();
  const SplResult solid = run_spl_scene(spec);
  REQUIRE(solid.path.outcome == PathOutcome::completed);
  REQUIRE(solid.model.half);
  std::vector<SplCellRodResult> rods;
  for (int end_rings : {2, 0}) {
    const SplCells cells = spl_cells(spec, 2, [&](TcaSceneSpec& s) {
      s.axial_level = 1;  // the 3D model's layers
      s.cell_rod_end_rings = end_rings;
    });
    CHECK(cells.end_cells == (end_rings > 0 ? 6 : 0));
    rods.push_back(pose_spl_cell_rod(cells, spec.output_levels));
    INFO(rods.back().diagnosis);
    REQUIRE(rods.back().converged);
  }
  const Eigen::Vector3d tip = solid.joints.back().pose.position_mm, rest_tip = solid.curve.front().tip_position_mm;
  const double travel = (tip - rest_tip).norm();
  const auto tip_error = [&](const SplCellRodResult& r) { return (r.joints.back().pose.position_mm - tip).norm() / travel; };
  INFO("tip off by " << 100 * tip_error(rods[0]) << " % of its " << travel << " mm travel with end cells, "
                     << 100 * tip_error(rods[1]) << " % with rigid caps");
  CHECK(tip_error(rods[0]) < 0.04);
  CHECK(tip_error(rods[1]) > 3 * tip_error(rods[0]));
  for (int n : {1, 2}) {
    const double reference = segment_bend_deg(solid.joints, n);
    const auto error = [&](const SplCellRodResult& r) { return segment_bend_deg(r.joints, n) / reference - 1; };
    INFO("segment " << n << ": 3D " << reference << "°; end cells " << 100 * error(rods[0]) << " %, rigid caps "
                    << 100 * error(rods[1]) << " %");
    CHECK(std::abs(error(rods[0])) < 0.03);
    CHECK(std::abs(error(rods[1])) > 3 * std::abs(error(rods[0])));
  }
}

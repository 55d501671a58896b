// The SPL on the spatial cell rod (fem/scenes/spl_cell_rod.hpp): with only its distal
// segment pressurised and no gravity, the two upper segments stay straight and the distal one
// bends exactly as the planar cell rod (tca_cell.hpp) bends the same 3CA from the same cells and
// end cells: the segments' order, the chambers' numbering, the bend's direction, the joints' frames
// and the end tables' turn.
#include <catch2/catch.hpp>
#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "fem/scenes/scene_config.hpp"
#include "fem/scenes/spl_cell_rod.hpp"
#include "fem/scenes/tca_cell.hpp"

using namespace softarm::fem;

TEST_CASE("The SPL cell rod bends a lone distal segment as the 3CA cell rod does", "[cell][spl]") {
  SplSceneSpec spl = load_scene_config(std::string(SOFTARM_SOURCE_DIR) + "/configs/spl_thesis_pose.json").spl;
  spl.chamber_pressure_kPa = {0, 0, 0, 0, 0, 0, 0, 59, 59};
  spl.gravity_m_s2.setZero();
  spl.output_levels = {0.25, 0.5, 0.75, 1.0};
  const SplCells cells = spl_cells(spl, 4);
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

// The 3CA's end cells (fem/scenes/tca_end_cell.hpp) against the whole 3D model: a short
// untapered 3CA of seven rings, whose ends are most of its length, bends under two chambers
// as its 3D model does once the cell rod takes its ends from end cells (within 2 % through
// three rings, closer than through two); with rigid caps on the cells' response it bends 20 %
// too far. An end bonded to a rigid body at its end face (an SPL segment's on its connectors)
// turns as its mirror image, the clamped end, does, and a full model as the half one.
#include <catch2/catch.hpp>
#include <Eigen/Geometry>
#include <cmath>
#include <string>
#include <vector>

#include "fem/scenes/scene_config.hpp"
#include "fem/scenes/tca_cell_rod.hpp"
#include "support/untapered_3ca.hpp"

using namespace softarm::fem;

namespace {
/// Seven ring pitches (37.3 mm) of the distal section to 150 kPa in three outputs, level 2's layers
/// (22,602 dofs half).
TcaSceneSpec short_3ca() { return softarm::test::untapered_3ca(7, 2, 3); }
}  // namespace

TEST_CASE("End cells bend a short 3CA as its 3D model does, closer with each ring, where rigid caps do not", "[cell][long]") {
  // Measured: 3D 2.713°, 5.728°, 8.768° at 50, 100, 150 kPa; end cells through three rings +1.4 to
  // +1.5 %, through two +3.7 to +3.8 %, rigid caps +20 %: the ends' disturbance decays by about half
  // per ring pitch beyond the cut.
  TcaSceneSpec spec = short_3ca();
  const TcaResult solid = run_tca_scene(spec);
  REQUIRE(solid.path.outcome == PathOutcome::completed);
  std::vector<CellRodTcaResult> rods;
  TcaRodCells through_three;  // the ring-pitch cells, which do not depend on the end rings, run once
  for (int rings : {3, 2, 0}) {
    spec.cell_rod_end_rings = rings;
    const TcaRodCells pieces =
        run_tca_rod_cells(spec, tca_needs_spatial_rod(spec), {}, rings == 3 ? nullptr : &through_three);
    if (rings == 3) through_three = pieces;
    rods.push_back(pose_cell_rod_tca(spec, pieces));
    REQUIRE(rods.back().converged);
    CHECK(rods.back().end_rings == rings);
    CHECK(rods.back().end_cells_note.empty());
    REQUIRE(rods.back().curve.size() == solid.curve.size());
  }
  for (std::size_t i = 1; i < solid.curve.size(); ++i) {
    const double reference = solid.curve[i].bending_angle_deg;
    const auto error = [&](int k) { return rods[k].curve[i].bending_angle_deg / reference - 1; };
    INFO(solid.curve[i].pressure_kPa << " kPa: 3D " << reference << "°; end cells through 3 rings " << 100 * error(0)
                                     << " %, through 2 " << 100 * error(1) << " %, rigid caps " << 100 * error(2) << " %");
    CHECK(rods[0].curve[i].pressure_kPa == Approx(solid.curve[i].pressure_kPa));
    CHECK(std::abs(error(0)) < 0.02);
    CHECK(std::abs(error(0)) < std::abs(error(1)));
    CHECK(std::abs(error(1)) < 0.5 * std::abs(error(2)));
    CHECK(error(2) > 0.1);
  }
}

TEST_CASE("An end cell: unloaded it stays at rest, and too many rings for the 3CA are refused", "[cell]") {
  TcaSceneSpec spec = short_3ca();
  spec.chamber_pressure_kPa = {0, 0, 0};
  const TcaEndCellResult rest = run_tca_end_cell(spec, TcaEnd::bottom, 2, EndFaceSupport::free);
  REQUIRE(rest.states.size() == 1);
  CHECK(rest.states.front().rotation_rad == 0);
  CHECK(rest.states.front().elongation_mm == Approx(0).margin(1e-12));
  CHECK(rest.length_mm == Approx(2 * 160.0 / 30));
  CHECK_THROWS_AS(run_tca_end_cell(spec, TcaEnd::top, 4, EndFaceSupport::bonded), std::logic_error);  // 2·4 ≥ 7 rings
  // Ring-pitch cells handed on from a run about other rings, or without the torsion asked for, are refused.
  TcaRodCells other;
  other.rings = {1, 7};
  CHECK_THROWS_AS(run_tca_rod_cells(spec, false, {}, &other), std::logic_error);
  other.rings = cell_rod_rings(7);
  other.cells.resize(other.rings.size());
  CHECK_THROWS_AS(run_tca_rod_cells(spec, true, {}, &other), std::logic_error);
  // The cell rod asked for such ends takes rigid caps and says why.
  spec.cell_rod_end_rings = 4;
  const CellRodTcaResult rod = run_cell_rod_tca(spec);
  CHECK(rod.end_rings == 0);
  CHECK(rod.end_cells_note.find("7 rings") != std::string::npos);
}

TEST_CASE("A bonded end cell turns as its mirror image does and its full model as its half", "[cell][long]") {
  // The short 3CA is untapered with its rings centred in their pitches: its bottom end is its top
  // end mirrored through the mid-height plane. Bonded to a rigid body (an SPL segment's ends on
  // their connectors), the bottom end must deform as the top one at the clamp: the mirror flips
  // both the rotation's horizontal components and which face is the upper one, so the rotation
  // vector (upper face against lower) and the elongation are the same. Chambers 1 and 2 keep a
  // mirror plane 60° off the x-z plane: the half model's frame turns, the full one's does not.
  TcaSceneSpec spec = short_3ca();
  spec.chamber_pressure_kPa = {100, 100, 0};
  spec.output_pressures_kPa = {50, 100};
  const TcaEndCellResult top = run_tca_end_cell(spec, TcaEnd::top, 2, EndFaceSupport::bonded);
  const TcaEndCellResult bottom = run_tca_end_cell(spec, TcaEnd::bottom, 2, EndFaceSupport::bonded);
  spec.allow_symmetry = false;
  const TcaEndCellResult full = run_tca_end_cell(spec, TcaEnd::bottom, 2, EndFaceSupport::bonded);
  REQUIRE(top.model.half);
  REQUIRE(!full.model.half);
  CHECK(top.model.frame_angle_rad != 0);
  for (const auto* r : {&top, &bottom, &full}) {
    REQUIRE(r->path.outcome == PathOutcome::completed);
    REQUIRE(r->states.size() == top.states.size());
  }
  const Eigen::Vector3d bend = tca_bend_direction(spec.chamber_pressure_kPa).normalized();
  const Eigen::Vector2d about = Eigen::Vector3d::UnitZ().cross(bend).head<2>();
  for (std::size_t i = 1; i < top.states.size(); ++i) {
    const TcaEndState &t = top.states[i], &b = bottom.states[i], &f = full.states[i];
    INFO(t.pressure_kPa << " kPa: top (" << t.rotation_vector_rad.transpose() << ") rad, " << t.elongation_mm
                        << " mm; bottom (" << b.rotation_vector_rad.transpose() << "), " << b.elongation_mm
                        << "; full model's bottom (" << f.rotation_vector_rad.transpose() << "), " << f.elongation_mm);
    CHECK(t.rotation_rad > 0);  // towards the bend, as the 3CA's clamped end
    CHECK(t.rotation_vector_rad.dot(about) == Approx(t.rotation_vector_rad.norm()).epsilon(1e-6));
    CHECK(t.rotation_rad == Approx(t.rotation_vector_rad.norm()).epsilon(1e-6));
    CHECK((b.rotation_vector_rad - t.rotation_vector_rad).norm() < 1e-3 * t.rotation_vector_rad.norm());
    CHECK(b.elongation_mm == Approx(t.elongation_mm).epsilon(1e-3));
    CHECK((f.rotation_vector_rad - b.rotation_vector_rad).norm() < 1e-3 * b.rotation_vector_rad.norm());
    CHECK(f.elongation_mm == Approx(b.elongation_mm).epsilon(1e-3));
  }
}

// An arm's cells over its pressure space (fem/scenes/spl_pressure_cells.hpp), on the short SPL with
// its cells on level 1's layers: on the rays' own directions, turned or mirrored onto other chambers,
// the pressure cells give the tables and the pose of the arm's own cells run at those pressures; off
// them, the interpolation's error is bounded here on the grid of one division (the coarsest).
#include <catch2/catch.hpp>
#include <array>
#include <cmath>

#include "fem/scenes/spl_cell_rod.hpp"
#include "fem/scenes/spl_pressure_cells.hpp"
#include "support/short_spl.hpp"

using namespace softarm::fem;

namespace {
using softarm::test::short_spl_pressure_cells;
constexpr int kLevels = softarm::test::kShortSplCellLevels;
void coarse_layers(TcaSceneSpec& s) { softarm::test::short_spl_cell_layers(s); }

/// The arm's own cells at pressures p, posed at p.
struct Direct {
  SplCells cells;
  SplCellRodResult pose;
};
Direct direct(const std::array<double, 9>& p) {
  SplSceneSpec spec = softarm::test::short_spl();
  spec.chamber_pressure_kPa = p;
  Direct d{spl_cells(spec, kLevels, coarse_layers), {}};
  d.pose = pose_spl_cell_rod(d.cells, {1.0});
  return d;
}
}  // namespace

TEST_CASE("On the rays' directions turned or mirrored, the pressure cells are the arm's own cells", "[cell][spl][long][workspace]") {
  const SplPressureCells& cells = short_spl_pressure_cells();
  REQUIRE(cells.failure.empty());
  REQUIRE(cells.rays.size() == 3);
  // Segment 1: chamber 2 alone (ray (0, 0) turned by 120°); segment 2: chambers 1 and 3 (ray (1, 0)
  // mirrored); segment 3: chambers 2 and 3 at half the peak (ray (1, 0) turned, at its level 0.5).
  const std::array<double, 9> p = {0, 150, 0, 150, 0, 150, 0, 75, 75};
  const PressureRod rod = rod_at_pressures(cells, p);
  INFO(rod.why);
  REQUIRE(rod.ok);
  const Direct d = direct(p);
  REQUIRE(d.cells.failure.empty());
  REQUIRE(d.pose.converged);
  for (std::size_t piece = 0; piece < rod.rod.pieces.size(); ++piece) {
    const SpatialCellPiece &mine = rod.rod.pieces[piece], &theirs = d.cells.rod.pieces[piece];
    REQUIRE(mine.cells.size() == theirs.cells.size());
    REQUIRE(mine.ends.size() == theirs.ends.size());
    for (std::size_t c = 0; c < mine.cells.size(); ++c) {
      const SpatialCellTable &a = mine.cells[c], &b = theirs.cells[c];
      REQUIRE(b.level.back() == 1.0);
      INFO("piece " << piece << ", cell " << c << ": κ " << a.curvature_per_mm.back().transpose() << " against "
                    << b.curvature_per_mm.back().transpose() << " per mm, stretch " << a.stretch.back() << " against "
                    << b.stretch.back());
      CHECK((a.curvature_per_mm.back() - b.curvature_per_mm.back()).norm() <= 1e-3 * b.curvature_per_mm.back().norm() + 1e-9);
      CHECK(a.stretch.back() == Approx(b.stretch.back()).epsilon(1e-6));
      CHECK((a.bending_compliance_per_Nmm2.back() - b.bending_compliance_per_Nmm2.back()).norm() <=
            1e-3 * b.bending_compliance_per_Nmm2.back().norm());
      CHECK(a.axial_compliance_per_N.back() == Approx(b.axial_compliance_per_N.back()).epsilon(1e-3));
      CHECK(a.torsion_compliance_per_Nmm2 == Approx(b.torsion_compliance_per_Nmm2).epsilon(1e-9));
    }
    for (std::size_t e = 0; e < mine.ends.size(); ++e) {
      const SpatialEndTable &a = mine.ends[e], &b = theirs.ends[e];
      INFO("piece " << piece << ", end " << e << ": turn " << a.rotation_rad.back().transpose() << " against "
                    << b.rotation_rad.back().transpose() << " rad");
      CHECK((a.rotation_rad.back() - b.rotation_rad.back()).norm() <= 1e-3 * b.rotation_rad.back().norm() + 1e-9);
      CHECK(a.elongation_mm.back() == Approx(b.elongation_mm.back()).epsilon(1e-3).margin(1e-9));
    }
  }
  const SpatialCellRodState pose = pose_at_pressures(cells, p);
  REQUIRE(pose.ok);
  const Eigen::Vector3d tip = pose.position.back(), reference = d.pose.curve.back().tip_position_mm;
  const double travel = (reference - d.pose.curve.front().tip_position_mm).norm();
  INFO("tip " << tip.transpose() << " against " << reference.transpose() << " mm (travel " << travel << " mm)");
  CHECK((tip - reference).norm() < 1e-3 * travel);
}

TEST_CASE("Between the rays, the pressure cells interpolate the arm's own cells", "[cell][spl][long][workspace]") {
  const SplPressureCells& cells = short_spl_pressure_cells();
  REQUIRE(cells.failure.empty());
  // Each segment halfway between the grid's rays: (1, ½, 0), (1, ½, ½) and (1, 1, ½) of the peak,
  // in different chambers.
  const std::array<double, 9> p = {150, 75, 0, 75, 75, 150, 75, 150, 150};
  const Direct d = direct(p);
  REQUIRE(d.pose.converged);
  const SpatialCellRodState pose = pose_at_pressures(cells, p);
  INFO(pose.diagnosis);
  REQUIRE(pose.ok);
  const Eigen::Vector3d tip = pose.position.back(), reference = d.pose.curve.back().tip_position_mm;
  const double travel = (reference - d.pose.curve.front().tip_position_mm).norm();
  INFO("tip " << tip.transpose() << " against " << reference.transpose() << " mm: " << (tip - reference).norm()
              << " mm off, travel " << travel << " mm");
  // Measured: 0.28 mm of the tip's 10.3 mm travel (2.8 %).
  CHECK((tip - reference).norm() < 0.05 * travel);
}

TEST_CASE("The pressure cells refuse pressures outside their range", "[cell][spl][long][workspace]") {
  const SplPressureCells& cells = short_spl_pressure_cells();
  std::array<double, 9> p{};
  p[4] = 151;
  const PressureRod rod = rod_at_pressures(cells, p);
  CHECK_FALSE(rod.ok);
  CHECK(rod.why.find("chamber 5 at 151 kPa") != std::string::npos);
  p[4] = std::nan("");
  CHECK_FALSE(rod_at_pressures(cells, p).ok);
}

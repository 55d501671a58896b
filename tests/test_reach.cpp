// Inverse statics on the pressure cells (engine/workspace/reach.hpp), on the short SPL's cells: the
// tip of a pose at random pressures is reached again (within 0.5 mm); a target above the shoulder
// is not, and the nearest point found is given as such.
#include <catch2/catch.hpp>
#include <random>

#include "engine/workspace/reach.hpp"
#include "support/short_spl.hpp"

using namespace softarm;

TEST_CASE("reach finds again the tip of poses at random pressures", "[cell][spl][long][workspace][reach]") {
  const fem::SplPressureCells& cells = test::short_spl_pressure_cells();
  REQUIRE(cells.failure.empty());
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> pressure(0, test::kShortSplPeak_kPa);
  for (int trial = 0; trial < 4; ++trial) {
    std::array<double, 9> p{};
    for (double& x : p) x = pressure(rng);
    const fem::SpatialCellRodState forward = fem::pose_at_pressures(cells, p);
    REQUIRE(forward.ok);
    engine::ReachTarget target;
    target.position_mm = forward.position.back();
    const engine::ReachResult r = engine::reach(cells, target, {});
    INFO("trial " << trial << ": target " << target.position_mm.transpose() << " mm; nearest "
                  << (r.nearest ? r.nearest->distance_mm : -1) << " mm off after " << r.evaluations << " rod solves");
    REQUIRE(r.reachable);
    CHECK(r.solutions.front().distance_mm <= 0.5);
    for (const auto& s : r.solutions)
      for (double x : s.pressure_kPa) {
        CHECK(x >= 0);
        CHECK(x <= test::kShortSplPeak_kPa);
      }
    // The solution's pressures pose the tip where reach says.
    const fem::SpatialCellRodState again = fem::pose_at_pressures(cells, r.solutions.front().pressure_kPa);
    REQUIRE(again.ok);
    CHECK((again.position.back() - r.solutions.front().tip_mm).norm() < 1e-9);
  }
}

TEST_CASE("reach says a target beyond the arm is unreachable and gives the nearest point", "[cell][spl][long][workspace][reach]") {
  const fem::SplPressureCells& cells = test::short_spl_pressure_cells();
  REQUIRE(cells.failure.empty());
  engine::ReachTarget target;
  target.position_mm = {0, 0, 300};  // above the shoulder (the arm hangs from z ≈ 110 mm)
  const engine::ReachResult r = engine::reach(cells, target, {});
  CHECK_FALSE(r.reachable);
  CHECK(r.solutions.empty());
  REQUIRE(r.nearest);
  CHECK(r.nearest->distance_mm > 150);
}

// An arm's cells over its pressure space (fem/scenes/spl_pressure_cells.hpp), on the short SPL with
// its cells on level 1's layers: on the rays' own directions, turned or mirrored onto other chambers,
// the pressure cells give the tables and the pose of the arm's own cells run at those pressures; off
// them, the interpolation's error is bounded here on the grid of one division (the coarsest); and
// reach (engine/workspace/reach.hpp) on them finds again the tip of poses at random pressures, and the
// payload margin there; the chambers' stretch in a pose is checked against the posed fibres'. One
// test case of sections: the cells (a minute and a half) are made once per process, and ctest runs
// each test case in its own.
#include <catch2/catch.hpp>
#include <algorithm>
#include <array>
#include <cmath>

#include <random>

#include "engine/workspace/reach.hpp"
#include "engine/workspace/workspace_margins.hpp"
#include "studies/workspace.hpp"
#include "fem/scenes/chamber_stretch.hpp"
#include "fem/scenes/spl_cell_rod.hpp"
#include "fem/scenes/spl_pressure_cells.hpp"
#include "support/short_spl.hpp"

using namespace softarm::fem;
namespace engine = softarm::engine;
namespace test = softarm::test;
namespace studies = softarm::studies;

namespace {
using softarm::test::short_spl_pressure_cells;
constexpr int kLevels = softarm::test::kShortSplCellLevels;
void coarse_layers(TcaSceneSpec& s) { softarm::test::short_spl_cell_layers(s); }
/// Four local searches, not reach's 16: the short arm's targets need no more, and the test a quarter
/// of the time.
const engine::ReachSettings kFourStarts = [] {
  engine::ReachSettings s;
  s.starts = 4;
  return s;
}();

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

TEST_CASE("The short SPL's pressure cells: the arm's own cells on their rays, close between them, and reach on them", "[cell][spl][long][workspace]") {
  const SplPressureCells& cells = short_spl_pressure_cells();
  REQUIRE(cells.failure.empty());
  SECTION("On the rays' directions turned or mirrored, the pressure cells are the arm's own cells") {
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
  SECTION("Between the rays, the pressure cells interpolate the arm's own cells") {
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
  SECTION("A segment past where its cells reached is told apart from a pressure out of range") {
    // Segment 1's cells (piece 1: piece 0 is the shoulder's connector) cut to the first half of their
    // levels on every ray, as if they had stopped at a limit point there.
    SplPressureCells stopped = cells;
    for (SplCells& ray : stopped.rays)
      for (SpatialCellTable& t : ray.rod.pieces.at(1).cells) {
        const std::size_t keep = (t.level.size() + 1) / 2;
        t.level.resize(keep), t.stretch.resize(keep), t.axial_compliance_per_N.resize(keep);
        t.curvature_per_mm.resize(keep), t.bending_compliance_per_Nmm2.resize(keep);
      }
    const std::array<double, 9> high = {150, 0, 0, 0, 0, 0, 0, 0, 0};
    const PressureRod beyond = rod_at_pressures(stopped, high);
    CHECK_FALSE(beyond.ok);
    CHECK(beyond.beyond_cells);
    CHECK(pose_at_pressures(stopped, high).beyond_tables);
    CHECK(pose_at_pressures(cells, high).ok);  // the same pressures on the whole cells
    std::array<double, 9> out_of_range{};
    out_of_range[0] = 151;
    CHECK_FALSE(rod_at_pressures(stopped, out_of_range).beyond_cells);
    CHECK_FALSE(pose_at_pressures(stopped, out_of_range).beyond_tables);
  }
  SECTION("The pressure cells refuse pressures outside their range") {
    std::array<double, 9> p{};
    p[4] = 151;
    const PressureRod rod = rod_at_pressures(cells, p);
    CHECK_FALSE(rod.ok);
    CHECK(rod.why.find("chamber 5 at 151 kPa") != std::string::npos);
    p[4] = std::nan("");
    CHECK_FALSE(rod_at_pressures(cells, p).ok);
  }
  SECTION("A chamber's axial stretch in a pose is that of the fibre along its axis, measured on the posed rod") {
    // A pose in no plane, under its weight and a 0.2 kg tip mass hanging: the chambers' stretch from
    // the intervals' λ and κ (chamber_stretch.hpp) against the fibres' own, |Δ(r + R·d)| / ΔZ between
    // the posed nodes.
    const std::array<double, 9> p = {120, 30, 0, 0, 150, 60, 90, 90, 20};
    PressureRod rod = rod_at_pressures(cells, p);
    REQUIRE(rod.ok);
    rod.rod.gravity_m_s2 = Eigen::Vector3d(0, 0, -9.81);
    rod.rod.tip_mass_kg = 0.2;
    const SpatialCellRodState pose = solve_spatial_cell_rod(rod.rod, 1.0);
    REQUIRE(pose.ok);
    const SplDesign design = softarm::test::short_spl().design;
    const std::array<double, 3> stretch = chamber_axis_stretch(design, rod.rod, pose);
    for (std::size_t piece = 0, n = 0; piece < rod.rod.pieces.size(); ++piece) {
      const SpatialCellPiece& part = rod.rod.pieces[piece];
      if (part.cells.empty()) continue;
      const int first = pose.piece_first_node[piece], last = pose.piece_last_node[piece];
      const double dz = part.length_mm / (last - first);
      double measured = 1;
      for (int i = first; i < last; ++i) {
        const double z = part.length_mm - (i - first + 0.5) * dz;
        if (z < part.cap_mm || z > part.length_mm - part.cap_mm) continue;
        const double a = design.segments[n].axis_distance(z);
        for (int k = 0; k < 3; ++k) {
          const double angle = k * 2.0943951023931954923;
          const Eigen::Vector3d d(a * std::cos(angle), a * std::sin(angle), 0);
          const Eigen::Vector3d upper = pose.position[i] + pose.frame[i] * d;
          const Eigen::Vector3d lower = pose.position[i + 1] + pose.frame[i + 1] * d;
          measured = std::max(measured, (upper - lower).norm() / dz);
        }
      }
      INFO("segment " << n + 1 << ": " << stretch[n] << " against the fibres' " << measured);
      CHECK(stretch[n] > 1.01);  // every segment is pressurised: a chamber lengthens
      CHECK(stretch[n] == Approx(measured).epsilon(0).margin(1e-3 * (measured - 1) + 1e-5));
      ++n;
    }
  }
  SECTION("reach finds again the tip of poses at random pressures") {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> pressure(0, test::kShortSplPeak_kPa);
    for (int trial = 0; trial < 4; ++trial) {
      std::array<double, 9> p{};
      for (double& x : p) x = pressure(rng);
      const SpatialCellRodState forward = pose_at_pressures(cells, p);
      REQUIRE(forward.ok);
      engine::ReachTarget target;
      target.position_mm = forward.position.back();
      const engine::ReachResult r = engine::reach(cells, target, kFourStarts);
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
      const SpatialCellRodState again = pose_at_pressures(cells, r.solutions.front().pressure_kPa);
      REQUIRE(again.ok);
      CHECK((again.position.back() - r.solutions.front().tip_mm).norm() < 1e-9);
    }
  }
  SECTION("The payload margin at a target: the heaviest tip mass held there, whatever mass it starts from") {
    // The short arm hanging under gravity (its fixture has none), a target its tip reaches with 0.05 kg
    // when every segment bends the same way at three quarters of the bound.
    SplPressureCells hanging = cells;
    hanging.rays.front().rod.gravity_m_s2 = Eigen::Vector3d(0, 0, -9.81);
    const std::array<double, 9> p = {0, 110, 110, 0, 110, 110, 0, 110, 110};
    const SpatialCellRodState forward = pose_at_pressures(hanging, p, nullptr, 0.05);
    REQUIRE(forward.ok);
    const engine::ReachTarget target{"posed", forward.position.back(), {}};
    engine::ReachSettings light = kFourStarts;
    light.payload_kg = 0.05;
    const engine::ReachResult found = engine::reach(hanging, target, light);
    REQUIRE(found.reachable);
    const engine::PayloadMargin margin = engine::payload_margin(hanging, target, light, found);
    INFO("margin " << margin.margin_kg << " kg over " << margin.payload_kg << " kg (" << margin.searches
                   << " searches, " << margin.seconds << " s)");
    CHECK_FALSE(margin.at_least);  // measured: 2.2 kg more, a bracket closed well inside its 5 kg
    CHECK(margin.margin_kg > 0.05);
    // The heaviest mass's pressures, posed forward, hold the tip on the target, within the bounds.
    const SpatialCellRodState heavy = pose_at_pressures(hanging, margin.heaviest.pressure_kPa, nullptr,
                                                        margin.payload_kg + margin.margin_kg);
    REQUIRE(heavy.ok);
    CHECK((heavy.position.back() - target.position_mm).norm() <= light.tolerance_mm);
    for (int k = 0; k < 9; ++k) CHECK(margin.heaviest.pressure_kPa[k] <= segment_reach_kPa(hanging, k / 3) + 1e-9);
    // The same heaviest mass from a target reached with half the margin more.
    engine::ReachSettings heavier = light;
    heavier.payload_kg = margin.payload_kg + 0.5 * margin.margin_kg;
    const engine::PayloadMargin again =
        engine::payload_margin(hanging, target, heavier, engine::reach(hanging, target, heavier));
    INFO("from " << *heavier.payload_kg << " kg: margin " << again.margin_kg << " kg");
    CHECK(again.payload_kg + again.margin_kg ==
          Approx(margin.payload_kg + margin.margin_kg).margin(0.05 * margin.margin_kg + 0.02));
  }
  SECTION("A near miss is searched again from where it stopped, while each search gains") {
    // One start on a starved budget stops short of a pose's tip; restarts from there close in on it.
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> pressure(0, test::kShortSplPeak_kPa);
    std::array<double, 9> p{};
    for (double& x : p) x = pressure(rng);
    const SpatialCellRodState forward = pose_at_pressures(cells, p);
    REQUIRE(forward.ok);
    const engine::ReachTarget target{"posed", forward.position.back(), {}};
    engine::ReachSettings starved;
    starved.starts = 1;
    starved.seed_samples = 20;     // a start far off (the first corners of the pressure space) ...
    starved.max_evaluations = 30;  // ... and a few steps from it
    starved.restart_within_mm = 1000;
    starved.restarts = 0;
    const engine::ReachResult once = engine::reach(cells, target, starved);
    REQUIRE(once.nearest);
    const double first = once.nearest->distance_mm;
    INFO("one starved search stops " << first << " mm off");
    REQUIRE(first > starved.tolerance_mm);  // else this target tests nothing
    CHECK(once.starts == 1);
    starved.restarts = 4;
    const engine::ReachResult again = engine::reach(cells, target, starved);
    INFO("with restarts: " << again.nearest->distance_mm << " mm off after " << again.starts << " searches");
    CHECK(again.starts > 1);
    CHECK(again.starts <= 1 + starved.restarts);
    CHECK(again.nearest->distance_mm < 0.9 * first);
    // A miss farther than restart_within_mm is left as it is.
    starved.restart_within_mm = 0.5 * first;
    CHECK(engine::reach(cells, target, starved).starts == 1);
  }
  SECTION("The workspace's payload margins: at the first poses reached after the corners, as payload_margin finds them") {
    SplPressureCells hanging = cells;
    hanging.rays.front().rod.gravity_m_s2 = Eigen::Vector3d(0, 0, -9.81);
    studies::WorkspaceSettings settings;
    settings.samples = 516;
    settings.payload_kg = 0.05;
    studies::WorkspaceResult w = studies::sweep_workspace(hanging, settings);
    REQUIRE(w.reached == 516);
    CHECK(engine::margin_poses(w, 3) == std::vector<std::size_t>{512, 513, 514});
    CHECK(engine::margin_poses(w, 6) == std::vector<std::size_t>{512, 513, 514, 515, 0, 1});
    w.points[513].ok = false;  // a pose not reached is passed over
    CHECK(engine::margin_poses(w, 3) == std::vector<std::size_t>{512, 514, 515});
    w.points[513].ok = true;
    engine::margins_at_poses(hanging, w, 2, settings.payload_kg);
    for (std::size_t i = 0; i < w.points.size(); ++i) CHECK(w.points[i].payload_margin_kg.has_value() == (i == 512 || i == 513));
    // The same margin as payload_margin's from the pose's own pressures, one branch.
    const studies::WorkspacePoint& at = w.points[512];
    engine::ReachResult own;
    own.reachable = true;
    own.solutions.resize(1);
    own.solutions[0].pressure_kPa = at.pressure_kPa;
    own.solutions[0].tip_mm = at.tip_mm;
    engine::ReachSettings reach_settings;
    reach_settings.payload_kg = settings.payload_kg;
    engine::PayloadMarginSettings one_branch;
    one_branch.max_branches = 1;
    const engine::PayloadMargin direct =
        engine::payload_margin(hanging, {"pose", at.tip_mm, {}}, reach_settings, own, one_branch);
    INFO("pose 512: margin " << *at.payload_margin_kg << " kg");
    CHECK(*at.payload_margin_kg == Approx(direct.margin_kg).margin(1e-12));
    CHECK(at.payload_margin_at_least == direct.at_least);
    CHECK(*at.payload_margin_kg > 0);
  }
  SECTION("reach says a target beyond the arm is unreachable and gives the nearest point") {
    engine::ReachTarget target;
    target.position_mm = {0, 0, 300};  // above the shoulder (the arm hangs from z ≈ 110 mm)
    const engine::ReachResult r = engine::reach(cells, target, kFourStarts);
    CHECK_FALSE(r.reachable);
    CHECK(r.solutions.empty());
    REQUIRE(r.nearest);
    CHECK(r.nearest->distance_mm > 150);
  }
  SECTION("The workspace poses the corners first, then Roberts' sequence, and bounds what it reached") {
    studies::WorkspaceSettings settings;
    settings.samples = 1000;
    const studies::WorkspaceResult w = studies::sweep_workspace(cells, settings);
    REQUIRE(w.points.size() == 1000);
    CHECK(w.reached == 1000);  // within 150 kPa every pose of the short SPL has an equilibrium
    const auto pressures = studies::workspace_pressures(test::kShortSplPeak_kPa, 1000);
    CHECK(studies::workspace_pressures(test::kShortSplPeak_kPa, 600) ==
          std::vector<std::array<double, 9>>(pressures.begin(), pressures.begin() + 600));
    CHECK(pressures[0] == std::array<double, 9>{});  // rest
    CHECK(pressures[1] == std::array<double, 9>{150, 0, 0, 0, 0, 0, 0, 0, 0});
    CHECK(pressures[511] == std::array<double, 9>{150, 150, 150, 150, 150, 150, 150, 150, 150});
    for (std::size_t i = 0; i < pressures.size(); ++i) {
      CHECK(w.points[i].pressure_kPa == pressures[i]);
      for (double x : pressures[i]) {
        CHECK(x >= 0);
        CHECK(x <= test::kShortSplPeak_kPa);
      }
      if (!w.points[i].ok) continue;
      CHECK((w.points[i].tip_mm.array() >= w.lower_mm.array() - 1e-12).all());
      CHECK((w.points[i].tip_mm.array() <= w.upper_mm.array() + 1e-12).all());
      CHECK(w.points[i].tip_axis.norm() == Approx(1));
    }
    const SpatialCellRodState rest = pose_at_pressures(cells, {});
    REQUIRE(rest.ok);
    CHECK((w.points[0].tip_mm - rest.position.back()).norm() < 1e-12);
    CHECK(w.occupied_volume_mm3 > 0);
    // The centrelines drawn: rest first, then a pose at each end of the extent in x, y and z, once each.
    const std::vector<std::size_t> drawn = studies::extent_poses(w);
    REQUIRE(!drawn.empty());
    CHECK(drawn.front() == 0);
    CHECK(drawn.size() <= 7);
    for (std::size_t k = 0; k < drawn.size(); ++k)
      for (std::size_t l = k + 1; l < drawn.size(); ++l) CHECK(drawn[k] != drawn[l]);
    for (int axis = 0; axis < 3; ++axis) {
      INFO("axis " << axis);
      CHECK(std::any_of(drawn.begin(), drawn.end(), [&](std::size_t i) { return w.points[i].tip_mm[axis] == w.lower_mm[axis]; }));
      CHECK(std::any_of(drawn.begin(), drawn.end(), [&](std::size_t i) { return w.points[i].tip_mm[axis] == w.upper_mm[axis]; }));
    }
    // The same tips on a second sweep (the poses run side by side), this one with the chambers' stretch.
    settings.design = test::short_spl().design;
    studies::WorkspaceResult again = studies::sweep_workspace(cells, settings);
    for (std::size_t i = 0; i < w.points.size(); ++i) CHECK(again.points[i].tip_mm == w.points[i].tip_mm);
    // The tube's peaks: at rest (no gravity) the chambers are unstretched and so is the tube; the lone
    // RRAs' FEM paths cover every pose (no map read beyond them), and every pose stretches the tube.
    const TubePeakMaps maps = studies::judge_workspace_peaks(again, test::short_spl(), test::kShortSplPeak_kPa);
    CHECK(again.points[0].chamber_stretch[1] == Approx(1).margin(1e-9));
    CHECK(again.points[0].peak.stretch == Approx(1).margin(1e-3));
    for (const studies::WorkspacePoint& p : again.points) {
      REQUIRE(p.ok);
      CHECK_FALSE(p.peak.extrapolated);
      REQUIRE(p.peak.segment >= 1);
      CHECK(p.peak.stretch >= 1 - 1e-3);
    }
    const studies::WorkspacePoint& all = again.points[511];
    INFO("all chambers at 150 kPa: chamber stretches " << all.chamber_stretch[0] << ", " << all.chamber_stretch[1]
         << ", " << all.chamber_stretch[2] << "; peak " << all.peak.stretch << " in segment " << all.peak.segment
         << "; the lone RRAs' paths to " << maps.segment[0].last_pressure_kPa << ", " << maps.segment[1].last_pressure_kPa
         << ", " << maps.segment[2].last_pressure_kPa << " kPa");
    CHECK(all.peak.stretch > 1.05);
    CHECK(all.peak.stretch > again.points[1].peak.stretch);  // chamber 1 alone at 150 kPa
  }
}

// The 3D actuator scenes: the half model on a mirror plane gives the full
// model's answer (3CA with two chambers pressurised and gravity in the plane),
// the model choice follows the loads, the bending angle and tip agree with
// each other, and the SPL scene carries a pose, gravity and a tip mass.
// Short designs (20–30 mm, a few rings) keep the 3D models small.
#include <catch2/catch.hpp>
#include <cmath>

#include "fem/scenes/spl_scene.hpp"
#include "fem/scenes/tca_scene.hpp"
#include "support/short_3ca.hpp"

using namespace softarm::fem;

namespace {
TcaSceneSpec short_tca_scene(bool allow_symmetry) {
  TcaSceneSpec s = softarm::test::short_3ca_scene(40, {20, 40});
  s.allow_symmetry = allow_symmetry;
  return s;
}
}  // namespace

// One run of the short 3CA's half model serves four checks (it took 4.4 s, once in each of them):
// each SECTION below was a test case of its own, with the same assertions on the same run.
TEST_CASE("3CA, the short half model: the full model, the pressure ordering, a second run, the rings' rotation",
          "[tca_scene][long]") {
  static const TcaResult half = run_tca_scene(short_tca_scene(true));

  SECTION("the half model reproduces the full model") {
    const auto full = run_tca_scene(short_tca_scene(false));
    REQUIRE(half.model.half);
    REQUIRE(!full.model.half);
    REQUIRE(half.path.outcome == PathOutcome::completed);
    REQUIRE(full.path.outcome == PathOutcome::completed);
    CHECK(half.dofs < 0.6 * full.dofs);
    // Same mesh on either side of the plane, same equations: equal to solver tolerance.
    const auto& h = half.curve.back();
    const auto& f = full.curve.back();
    CAPTURE(h.bending_angle_deg, f.bending_angle_deg, h.tip_position_mm.transpose(), f.tip_position_mm.transpose());
    CHECK(h.bending_angle_deg == Approx(f.bending_angle_deg).epsilon(1e-6));
    CHECK((h.tip_position_mm - f.tip_position_mm).norm() < 1e-6);
    CHECK(std::abs(f.tip_position_mm.y()) < 1e-6);  // the full model keeps the mirror symmetry by itself
    CHECK(h.chamber_volume_mm3 == Approx(f.chamber_volume_mm3).epsilon(1e-9));
    CHECK(half.mass_kg == Approx(full.mass_kg).epsilon(1e-12));
    // Chambers 2 and 3 (at 120° and 240°) push the tip towards chamber 1 (+x), against gravity.
    CHECK(f.tip_displacement_mm.x() > 0);
    CHECK(f.bending_angle_deg > 0);
  }

  SECTION("bending angle and tip position agree with the pressure ordering") {
    const auto& r = half;
    REQUIRE(r.states.size() >= 3);
    // More pressure, more bending; the rest state sags under gravity against the bend.
    CHECK(r.states.front().bending_angle_deg < 0);
    for (std::size_t i = 1; i < r.curve.size(); ++i) CHECK(r.curve[i].bending_angle_deg > r.curve[i - 1].bending_angle_deg);
    // The interpolated pressure of an angle between two states lies between their pressures.
    const double mid = 0.5 * (r.curve[0].bending_angle_deg + r.curve[1].bending_angle_deg);
    const auto p = pressure_at_bending(r.states, mid);
    REQUIRE(p);
    CHECK(*p > r.curve[0].pressure_kPa);
    CHECK(*p < r.curve[1].pressure_kPa);
  }

  SECTION("two runs take the same path (factor reuse's CG budget counts flops, not seconds)") {
    // With the budget timed as it ran, the load on the machine decided which Newton steps
    // factorised, and the thesis 3CA's path differed run to run (17-24 load steps).
    const auto& a = half;
    const auto b = run_tca_scene(short_tca_scene(true));
    REQUIRE(a.path.reused_solves > 0);  // the budget was used
    CHECK(a.path.path.stats.newton_iterations == b.path.path.stats.newton_iterations);
    CHECK(a.path.factorizations == b.path.factorizations);
    // The cost of one factorisation, as summary.json reports it: L holds at least the diagonal,
    // and each column of L costs at least as many flops as it has entries.
    CHECK(a.path.factor_nonzeros >= a.dofs);
    CHECK(a.path.factor_flops >= a.path.factor_nonzeros);
    CHECK(a.path.cg_iterations == b.path.cg_iterations);
    CHECK(a.curve.back().bending_angle_deg == b.curve.back().bending_angle_deg);
  }

  SECTION("rotating the rings exactly under Newton's update gives the same curve") {
    // x + δx stretches a rotating ABS ring by |ω|²/2; at E = 2 GPa that dwarfs the silicone's
    // forces, and the line search cuts the step (fem/assembly/stiff_inclusions.hpp).
    TcaSceneSpec spec = short_tca_scene(true);
    REQUIRE(spec.newton.rotate_stiff_parts);  // the 3D default, so the shared run is the rotated one
    const auto& rotated = half;
    spec.newton.rotate_stiff_parts = false;
    const auto linear = run_tca_scene(spec);
    REQUIRE(rotated.path.outcome == PathOutcome::completed);
    REQUIRE(linear.path.outcome == PathOutcome::completed);
    const auto& r = rotated.curve.back();
    const auto& l = linear.curve.back();
    CAPTURE(r.bending_angle_deg, l.bending_angle_deg, rotated.path.path.stats.newton_iterations,
            linear.path.path.stats.newton_iterations);
    CHECK(r.bending_angle_deg == Approx(l.bending_angle_deg).epsilon(1e-6));
    CHECK((r.tip_position_mm - l.tip_position_mm).norm() < 1e-5);
    CHECK(rotated.path.path.stats.newton_iterations <= linear.path.path.stats.newton_iterations);  // 29 and 30
  }
}

TEST_CASE("3CA model choice follows the loads", "[tca_scene]") {
  TcaSceneSpec s = short_tca_scene(true);
  s.chamber_pressure_kPa = {30, 0, 30};  // symmetric about the plane through chamber 2 …
  s.gravity_m_s2 = Eigen::Vector3d(0, 0, -9.8);
  CHECK(choose_tca_model(s).mirror_chamber == 2);
  s.gravity_m_s2 = Eigen::Vector3d(-9.8 * std::cos(2.0943951023931953), -9.8 * std::sin(2.0943951023931953), 0);
  CHECK(choose_tca_model(s).mirror_chamber == 2);  // … and gravity along chamber 2's direction lies in it
  s.gravity_m_s2 = Eigen::Vector3d(0, -9.8, 0);  // not in that plane
  CHECK(!choose_tca_model(s).half);
  s.gravity_m_s2 = Eigen::Vector3d(0, 0, 9.8);
  s.chamber_pressure_kPa = {10, 20, 30};
  CHECK(!choose_tca_model(s).half);
}

TEST_CASE("SPL: a symmetric pose on the half model matches the full model, and a tip mass lowers the tip", "[spl_scene][long]") {
  SplSceneSpec s;
  for (auto& segment : s.design.segments) {
    RraDesign& a = segment.actuator;
    const double r_b = a.bottom_radius_mm;
    a.length_mm = 20;
    a.wall_thickness_mm = 0.466 * r_b;
    a.end_cap_thickness_mm = 0.25 * r_b;
    a.ring_count = 3;
    a.ring_diameter_mm = 0.4 * 20 / 3;
  }
  for (int n = 1; n <= 3; ++n) {  // the radii of eqs 5–7 with the default taper ratio
    const auto radii = spl_segment_radii(0.5, 9, n);
    s.design.segments[n - 1].actuator.top_radius_mm = radii[0];
    s.design.segments[n - 1].actuator.bottom_radius_mm = radii[1];
  }
  s.design.connector_thickness_mm = 5;
  s.tube_material = s.sheath_material = builtin_material("dragon_skin_30", "test");
  s.ring_material = s.connector_material = builtin_material("digital_abs", "test");
  s.mesh_level = 1;
  s.element_order = 1;  // a functional test of the scene, not of accuracy
  s.chamber_pressure_kPa = {0, 20, 20, 0, 10, 10, 0, 0, 0};
  s.output_levels = {1.0};
  const auto half = run_spl_scene(s);
  s.allow_symmetry = false;
  const auto full = run_spl_scene(s);
  REQUIRE(half.model.half);
  REQUIRE(half.path.outcome == PathOutcome::completed);
  REQUIRE(full.path.outcome == PathOutcome::completed);
  REQUIRE(full.joints.size() == 6);
  for (std::size_t j = 0; j < full.joints.size(); ++j) {
    CAPTURE(full.joints[j].name);
    CHECK((half.joints[j].pose.position_mm - full.joints[j].pose.position_mm).norm() < 1e-6);
  }
  CHECK(full.joints.front().pose.tilt_deg < 1e-3);   // segment 1's top is bonded to the (stiff) shoulder connector
  CHECK(full.curve.back().tip_position_mm.x() > 0);  // bends towards chamber 1
  s.tip_mass_kg = 0.2;
  const auto loaded = run_spl_scene(s);
  REQUIRE(loaded.path.outcome == PathOutcome::completed);
  CHECK(loaded.curve.back().tip_position_mm.z() < full.curve.back().tip_position_mm.z());
  CHECK(loaded.mass_kg == Approx(full.mass_kg));  // the payload is not part of the arm
}


// The RRA scene end to end: the thesis actuator inflates to 206.8 kPa, a thin
// neo-Hookean tube balloons at a genuine limit point that is reported as
// such, and an Ogden tube that CalculiX stalls on is carried on (a stall of a
// solver without the pressure load stiffness is not a limit point).
#include <catch2/catch.hpp>

#include "fem/materials/drucker_stability.hpp"
#include "fem/materials/material.hpp"
#include "fem/materials/yeoh.hpp"
#include "fem/scenes/rra_scene.hpp"
#include "support/test_problems.hpp"

using namespace softarm;
using namespace softarm::fem;

namespace {

RraSceneSpec thesis_rra(int level) {
  RraSceneSpec spec;
  spec.design.length_mm = 160;
  spec.design.bottom_radius_mm = 9;
  spec.design.top_radius_mm = 12;
  spec.design.wall_thickness_mm = 0.466 * 9;
  spec.design.end_cap_thickness_mm = 0.25 * 9;
  spec.design.ring_count = 30;
  spec.design.ring_diameter_mm = 0.4 * 160.0 / 30;
  spec.tube_material = builtin_material("dragon_skin_30", "test");
  spec.ring_material = builtin_material("digital_abs", "test");
  spec.mesh_level = level;
  spec.path.max_pressure_kPa = 206.8;
  for (int i = 1; i <= 10; ++i) spec.path.output_pressures_kPa.push_back(20.68 * i);
  return spec;
}

// The plain tube of shared/spec/calculix-notes.md: bore 4.5 mm, wall 2 mm, 160 mm, 2 mm caps.
RraSceneSpec plain_tube(const Material& material, double max_pressure_kPa) {
  RraSceneSpec spec;
  spec.design.length_mm = 160;
  spec.design.bottom_radius_mm = 6.5;
  spec.design.top_radius_mm = 6.5;
  spec.design.wall_thickness_mm = 2.0;
  spec.design.end_cap_thickness_mm = 2.0;
  spec.design.ring_count = 0;
  spec.design.ring_diameter_mm = 2.0;
  spec.tube_material = material;
  spec.ring_material = builtin_material("digital_abs", "test");
  spec.mesh_level = 1;
  spec.path.max_pressure_kPa = max_pressure_kPa;
  for (int i = 1; i <= 20; ++i) spec.path.output_pressures_kPa.push_back(max_pressure_kPa * i / 20);
  return spec;
}

}  // namespace

TEST_CASE("thesis RRA extends monotonically to 206.8 kPa", "[rra]") {
  const auto r = run_rra_scene(thesis_rra(1));
  INFO(r.path.diagnosis);
  REQUIRE(r.path.outcome == PathOutcome::completed);
  REQUIRE(r.curve.size() == 11);  // the unloaded state and the ten requested pressures
  CHECK(r.curve.front().pressure_kPa == 0.0);
  CHECK(r.curve.back().pressure_kPa == Approx(206.8).epsilon(1e-12));  // landed exactly
  for (std::size_t k = 1; k < r.curve.size(); ++k) {
    CHECK(r.curve[k].extension_mm > r.curve[k - 1].extension_mm);
    CHECK(r.curve[k].chamber_volume_mm3 > r.curve[k - 1].chamber_volume_mm3);
    CHECK(r.curve[k].pv_stiffness_kPa_per_mm3 > 0.0);
  }
  CHECK(r.curve.back().extension_mm > 5.0);   // rings turn pressure into elongation
  CHECK(r.curve.back().ring_max_principal_stress_MPa > r.curve.back().tube_max_principal_stress_MPa);
  // Ring mass: 30 tori 2π² R_k ρ² of ABS (1.17 g/cm³), computed here independently.
  double torus_mm3 = 0.0;
  const double rho = 0.2 * 160.0 / 30;
  for (int k = 1; k <= 30; ++k) torus_mm3 += 2 * 9.869604401089358 * (9.0 + 3.0 * (k - 0.5) / 30) * rho * rho;
  CHECK(r.ring_mass_kg == Approx(torus_mm3 * 1.17e-6).epsilon(1e-12));
  CHECK(r.tube_mass_kg > 0.030);  // 32.6 cm³ of Dragon Skin 30 (1.08 g/cm³): 35.2 g
  CHECK(r.tube_mass_kg < 0.040);
}

TEST_CASE("a thin neo-Hookean tube balloons: the limit point is detected and reported", "[rra][limit][long]") {
  // Same initial moduli as Dragon Skin 30 (μ0 = 0.1153 MPa, D1 = 0.7029/MPa).
  // CalculiX finds a real limit point near 31 kPa for this tube (calculix-notes.md);
  // the closed-end thin-membrane estimate is of the same order.
  const auto nh = test::material(std::make_shared<NeoHookean>(0.1153 / 2, VolumetricPolynomial({0.7029})), 1.08);
  const auto r = run_rra_scene(plain_tube(nh, 60.0));
  INFO(r.path.diagnosis);
  CHECK(r.path.outcome == PathOutcome::limit_point);
  CHECK(r.path.estimated_limit_pressure_kPa > 25.0);
  CHECK(r.path.estimated_limit_pressure_kPa < 40.0);
  CHECK(r.path.reached_pressure_kPa < 40.0);
}

TEST_CASE("chamber-volume control follows the ballooning tube past its pressure maximum", "[rra][limit][long]") {
  // The tube above: volume control takes over where pressure control stops and traces
  // the p–V curve over its maximum. Independent check: pressure control with a 100×
  // finer smallest increment (and no volume control) creeps up to the maximum from
  // below: the two estimates of the maximum must agree to 0.02 % (the parabola's
  // vertex through three traced states, against the last pressure that still converged).
  const auto nh = test::material(std::make_shared<NeoHookean>(0.1153 / 2, VolumetricPolynomial({0.7029})), 1.08);
  const auto r = run_rra_scene(plain_tube(nh, 60.0));
  INFO(r.path.diagnosis);
  REQUIRE(r.path.outcome == PathOutcome::limit_point);
  CHECK(r.path.diagnosis.find("volume control") != std::string::npos);
  REQUIRE(!r.path.beyond_limit.empty());
  // Past the last pressure-controlled state the volume grows throughout while the pressure
  // first rises to the maximum and then falls (the branch pressure control cannot follow).
  double p_max = r.path.history.back().pressure_kPa;
  for (std::size_t i = 0; i < r.path.beyond_limit.size(); ++i) {
    const double v_before = i ? r.path.beyond_limit[i - 1].chamber_volume_mm3 : r.path.history.back().chamber_volume_mm3;
    CHECK(r.path.beyond_limit[i].chamber_volume_mm3 > v_before);
    p_max = std::max(p_max, r.path.beyond_limit[i].pressure_kPa);
  }
  // It stops once the pressure has fallen: clearly (0.02 %), or at a state whose own tangent
  // gives dp/dV < 0.
  const auto& end = r.path.beyond_limit.back();
  CHECK(end.pressure_kPa < p_max);
  CHECK((end.pressure_kPa < (1 - 2e-4) * p_max || end.pv_stiffness_kPa_per_mm3 < 0));
  // Each state's dp/dV (from its tangent) against the secant to the next: on the concave top
  // of p(V) the secant lies between the tangents at its ends (mean value theorem).
  const PressureState* before = &r.path.history.back();
  for (const PressureState& s : r.path.beyond_limit) {
    const double secant = (s.pressure_kPa - before->pressure_kPa) / (s.chamber_volume_mm3 - before->chamber_volume_mm3);
    const double slack = 1e-3 * std::abs(before->pv_stiffness_kPa_per_mm3);
    INFO("V " << before->chamber_volume_mm3 << " -> " << s.chamber_volume_mm3 << ": dp/dV " << before->pv_stiffness_kPa_per_mm3
              << ", secant " << secant << ", dp/dV " << s.pv_stiffness_kPa_per_mm3);
    CHECK(secant <= before->pv_stiffness_kPa_per_mm3 + slack);
    CHECK(secant >= s.pv_stiffness_kPa_per_mm3 - slack);
    before = &s;
  }
  CHECK(r.path.estimated_limit_pressure_kPa >= p_max * (1 - 1e-9));
  CHECK(r.path.estimated_limit_pressure_kPa < p_max * 1.002);  // the parabola's vertex sits by the largest state

  auto creep = plain_tube(nh, 60.0);
  creep.path.limit.follow_with_volume_control = false;
  creep.path.steps.min_increment *= 0.01;
  const auto c = run_rra_scene(creep);
  INFO("pressure control creeps to " << c.path.reached_pressure_kPa << " kPa; volume control's maximum "
                                     << r.path.estimated_limit_pressure_kPa << " kPa");
  CHECK(c.path.reached_pressure_kPa == Approx(r.path.estimated_limit_pressure_kPa).epsilon(2e-4));
}

TEST_CASE("volume control by CG on the augmented tangent finds the maximum its LU finds", "[rra][limit][long]") {
  // The ballooning tube again, past its maximum both ways: each bordered step factorised (LU
  // where K is indefinite), or solved by CG on K + α∇V∇Vᵀ preconditioned with the starting
  // tangent's Cholesky factor (the 3D scenes' default). The two solve the same equations, so
  // they must find the same maximum, the second with fewer LUs and with CG iterations instead.
  const auto nh = test::material(std::make_shared<NeoHookean>(0.1153 / 2, VolumetricPolynomial({0.7029})), 1.08);
  auto spec = plain_tube(nh, 60.0);
  const auto lu = run_rra_scene(spec);
  spec.path.limit.volume_control_by_cg = true;
  const auto cg = run_rra_scene(spec);
  INFO(lu.path.diagnosis << "\n" << cg.path.diagnosis);
  REQUIRE(lu.path.outcome == PathOutcome::limit_point);
  REQUIRE(cg.path.outcome == PathOutcome::limit_point);
  CHECK(cg.path.estimated_limit_pressure_kPa == Approx(lu.path.estimated_limit_pressure_kPa).epsilon(1e-5));
  REQUIRE(!cg.path.beyond_limit.empty());
  CHECK(cg.path.beyond_limit.back().pv_stiffness_kPa_per_mm3 < 0);  // dp/dV by Sherman–Morrison: past the top
  INFO("LUs " << lu.path.lu_fallbacks << " vs " << cg.path.lu_fallbacks << "; CG iterations " << lu.path.cg_iterations
              << " vs " << cg.path.cg_iterations);
  CHECK(cg.path.lu_fallbacks < lu.path.lu_fallbacks);
  CHECK(cg.path.cg_iterations > lu.path.cg_iterations);
}

TEST_CASE("where dp/dV is blind to it, the tangent's lowest mode finds the limit point", "[rra][limit][long]") {
  // The ballooning tube again, with the dp/dV test switched off (a threshold it never reaches),
  // as for a long 3CA whose few ballooning gaps barely change the loaded volume: pressure control
  // stalls just below the maximum, and the lowest eigenvalue of the tangent, collapsed there
  // against its value at rest, must name it a limit point.
  const auto nh = test::material(std::make_shared<NeoHookean>(0.1153 / 2, VolumetricPolynomial({0.7029})), 1.08);
  auto spec = plain_tube(nh, 60.0);
  spec.path.limit.stiffness_fraction = 1e-9;
  spec.path.limit.follow_with_volume_control = false;  // which would find the maximum by the volume
  const auto r = run_rra_scene(spec);
  INFO(r.path.diagnosis << "\nlowest eigenvalue / rest: " << r.path.lowest_eigenvalue_ratio);
  CHECK(r.path.outcome == PathOutcome::limit_point);
  CHECK(r.path.diagnosis.find("local limit point") != std::string::npos);
  CHECK(r.path.lowest_eigenvalue_ratio < spec.path.limit.lowest_mode_fraction);
  // Volume control's maximum (docs/model.md, Chamber-volume control).
  CHECK(r.path.reached_pressure_kPa == Approx(30.651).epsilon(2e-3));
}

TEST_CASE("the Ogden tube that CalculiX stalls on near 56 kPa is carried on", "[rra][limit]") {
  const auto r = run_rra_scene(plain_tube(builtin_material("dragon_skin_30", "test"), 80.0));
  INFO(r.path.diagnosis);
  CHECK(r.path.outcome == PathOutcome::completed);
  CHECK(r.path.reached_pressure_kPa == Approx(80.0));
}

TEST_CASE("a solver that gives up early reports a stall, not a burst", "[rra][limit]") {
  // Newton limited to four iterations per step, a small first step, then one that grows tenfold and
  // little room to cut back: the path stops far below any limit point, and must say so. (With the
  // steps' defaults the thesis RRA converges within four iterations a step once its first step is
  // cut back: the tenfold step is the one that fails.)
  auto spec = thesis_rra(1);
  spec.path.newton.max_iterations = 4;
  spec.path.steps.initial_increment = 0.025;
  spec.path.steps.growth = 10;
  spec.path.steps.max_increment = 0.5;
  spec.path.steps.cutback = 0.05;
  spec.path.steps.min_increment = 0.02;
  const auto r = run_rra_scene(spec);
  INFO(r.path.diagnosis);
  CHECK(r.path.outcome == PathOutcome::stalled);
  CHECK(r.path.reached_pressure_kPa > 0.0);  // it made progress before stalling (5.2 kPa)
  CHECK(r.path.reached_pressure_kPa < 206.8);
  CHECK(r.path.diagnosis.find("not a limit point") != std::string::npos);
  // Nor is the tangent near an instability anywhere: its lowest mode is as stiff as at rest.
  INFO("lowest eigenvalue / rest: " << r.path.lowest_eigenvalue_ratio);
  CHECK(r.path.lowest_eigenvalue_ratio > 0.5);
  REQUIRE_FALSE(r.curve.empty());
  CHECK(r.curve.back().pressure_kPa == Approx(r.path.reached_pressure_kPa));  // the last state reached is reported
  for (const auto& p : r.curve) CHECK(std::isfinite(p.extension_mm));
}

TEST_CASE("a silicone past its Drucker stability ends in a material instability, named with its stretch", "[rra][limit]") {
  // A Yeoh law with C20 < 0 softens beyond moderate stretch (`softarm material check`: uniaxial
  // stable to 1.74, equibiaxial to 1.36). The thesis RRA in it stops where the stretch concentrates
  // (the bore's corner at the end cap); the same RRA with C20 = 0 carries the pressure.
  const auto soft = [](double C20) {
    return test::material(std::make_shared<Yeoh>(0.06, C20, 0.0, VolumetricPolynomial({0.7}), "test"), 1.08);
  };
  auto spec = thesis_rra(1);
  spec.path.max_pressure_kPa = 40.0;
  spec.path.output_pressures_kPa = {10.0, 20.0, 30.0, 40.0};
  // Fewer cut-backs at the stop, and no volume control after it (which cannot pass a softening law
  // either): the test's cost, not where the path stops.
  spec.path.steps.min_increment = 1e-2;
  spec.path.limit.follow_with_volume_control = false;
  spec.tube_material = soft(-0.01);
  const auto r = run_rra_scene(spec);
  INFO(r.path.diagnosis);
  REQUIRE(r.path.outcome == PathOutcome::material_instability);
  CHECK(is_answer(r.path.outcome));
  CHECK(r.path.reached_pressure_kPa > 10.0);  // 34.84 kPa; 35.06 with the default steps (docs/model.md)
  CHECK(r.path.reached_pressure_kPa < 40.0);
  CHECK(r.path.material.unstable_points >= 1);
  CHECK(r.path.material.max_stretch > 1.36);  // beyond every path's stable stretch but the uniaxial one's
  CHECK(r.path.diagnosis.find("not Drucker stable") != std::string::npos);
  CHECK(r.path.diagnosis.find("r = ") != std::string::npos);  // where
  CHECK(r.path.material.unstable_points < r.path.material.checked_points);
  spec.tube_material = soft(0.0);
  const auto stable = run_rra_scene(spec);
  INFO(stable.path.diagnosis);
  CHECK(stable.path.outcome == PathOutcome::completed);
}

TEST_CASE("an element that every step turns inside out is named, not reported as a stall", "[rra][limit]") {
  // A soft tube asked for 1 MPa in one step, with no line search and no room to cut back: the first
  // Newton step turns elements inside out at every step size the path may take.
  auto spec = plain_tube(test::neo_hookean(0.05, 1.0), 1000.0);
  spec.path.steps.initial_increment = 1.0;
  spec.path.steps.min_increment = 0.5;
  spec.path.newton.max_line_search = 1;
  const auto r = run_rra_scene(spec);
  INFO(r.path.diagnosis);
  REQUIRE(r.path.outcome == PathOutcome::element_inversion);
  CHECK(r.path.path.failure == Failure::inverted_element);
  CHECK(r.path.inverted_element >= 0);
  CHECK(r.path.inverted_element < r.mesh.num_elements());
  CHECK(r.path.diagnosis.find("element " + std::to_string(r.path.inverted_element)) != std::string::npos);
  CHECK(r.path.diagnosis.find("inside out") != std::string::npos);
}

TEST_CASE("thesis RRA with square rings of equal area extends at low pressure", "[rra]") {
  auto spec = thesis_rra(1);
  spec.design.ring_section = RraDesign::RingSection::square;
  spec.path.max_pressure_kPa = 20.0;
  spec.path.output_pressures_kPa = {10.0, 20.0};
  const auto r = run_rra_scene(spec);
  INFO(r.path.diagnosis);
  REQUIRE(r.path.outcome == PathOutcome::completed);
  REQUIRE(r.curve.size() == 3);
  CHECK(r.curve.back().pressure_kPa == Approx(20.0).epsilon(1e-12));
  CHECK(r.curve[1].extension_mm > 0.0);
  CHECK(r.curve[2].extension_mm > r.curve[1].extension_mm);
  CHECK(r.curve[2].chamber_volume_mm3 > r.curve[1].chamber_volume_mm3);
  CHECK(r.curve.back().ring_max_principal_stress_MPa > r.curve.back().tube_max_principal_stress_MPa);
  // Same section area at the same radius: the same ring mass as the circular rings.
  auto circle = thesis_rra(1);
  CHECK(r.ring_mass_kg == Approx(ring_volume_mm3(circle.design) * 1.17e-6).epsilon(1e-12));
  CHECK(r.tube_mass_kg == Approx(tube_volume_mm3(spec.design) * 1.08e-6).epsilon(1e-12));
}

namespace {
/// The ballooning tube with pressure control only, Newton patient (no unstable-branch guard) and
/// guarded (4 indefinite iterations without progress), shifted Cholesky or LU steps: past the maximum
/// every step meets indefinite tangents. Both must stop at the same limit, the guarded one for fewer
/// Newton iterations, with the failure named.
struct PatientAndGuarded {
  RraResult patient, guarded;
};
PatientAndGuarded patient_and_guarded(bool shifted_cholesky) {
  const auto nh = test::material(std::make_shared<NeoHookean>(0.1153 / 2, VolumetricPolynomial({0.7029})), 1.08);
  auto spec = plain_tube(nh, 60.0);
  spec.path.limit.follow_with_volume_control = false;
  spec.path.newton.shift_indefinite_tangent = shifted_cholesky;
  spec.path.newton.max_indefinite_iterations = 0;
  PatientAndGuarded out{run_rra_scene(spec), {}};
  spec.path.newton.max_indefinite_iterations = 4;
  out.guarded = run_rra_scene(spec);
  INFO(out.patient.path.diagnosis << "\n" << out.guarded.path.diagnosis);
  INFO("Newton iterations " << out.patient.path.path.stats.newton_iterations << " vs "
                            << out.guarded.path.path.stats.newton_iterations);
  CHECK(out.patient.path.outcome == PathOutcome::limit_point);
  CHECK(out.guarded.path.outcome == PathOutcome::limit_point);
  CHECK(out.patient.path.path.failure != Failure::unstable_branch);
  CHECK(out.guarded.path.path.failure == Failure::unstable_branch);
  CHECK(out.guarded.path.reached_pressure_kPa == Approx(out.patient.path.reached_pressure_kPa).epsilon(1e-3));
  CHECK(out.guarded.path.estimated_limit_pressure_kPa ==
        Approx(out.patient.path.estimated_limit_pressure_kPa).epsilon(1e-3));
  CHECK(out.guarded.path.path.stats.newton_iterations < out.patient.path.path.stats.newton_iterations);
  return out;
}
}  // namespace

TEST_CASE("Newton gives up early on an unstable branch and stops at the same limit point", "[rra][limit]") {
  // The 3D scenes' shifted-Cholesky Newton.
  const PatientAndGuarded r = patient_and_guarded(true);
  const RraResult &patient = r.patient, &guarded = r.guarded;
  // Past a limit point no start converges: a step that fails on an unstable branch is cut back
  // without a second start from the last converged state; other failures (the patient Newton's
  // max_iterations) still get one.
  INFO("second starts " << patient.path.path.stats.second_starts << " vs " << guarded.path.path.stats.second_starts
                        << "; cut-backs " << guarded.path.path.stats.cutbacks);
  CHECK(patient.path.path.stats.second_starts >= 1);
  REQUIRE(guarded.path.path.stats.cutbacks >= 1);
  CHECK(guarded.path.path.stats.second_starts == 0);
  // Below a level with only indefinite tangents the steps halve their distance to it: no
  // level is tried twice, each failure is below the last, and the stop is at the same limit.
  const auto& failed = guarded.path.path.stats.failed_levels;
  INFO("halved steps " << guarded.path.path.stats.halved_steps << ", failed levels " << failed.size());
  CHECK(guarded.path.path.stats.halved_steps >= 1);
  REQUIRE(failed.size() >= 2);
  for (std::size_t k = 1; k < failed.size(); ++k) CHECK(failed[k] < failed[k - 1]);
}

TEST_CASE("the axisymmetric scenes' LU Newton gives up on an unstable branch by default, at the patient one's limit",
          "[rra][limit][long]") {
  // Exact LU steps on indefinite tangents and the guard on, as the axisymmetric scenes come.
  const RraSceneSpec defaults = plain_tube(builtin_material("dragon_skin_30", "test"), 60.0);
  CHECK_FALSE(defaults.path.newton.shift_indefinite_tangent);
  CHECK(defaults.path.newton.max_indefinite_iterations == 4);
  patient_and_guarded(false);
}

TEST_CASE("handed to volume control ahead of its maximum, or once a step past it failed, the tube finds the same maximum for less work", "[rra][limit][long]") {
  // The ballooning tube again: pressure control stops before a step past the pressure where dp/dV,
  // extrapolated from its last two states, falls to zero, and volume control traces the top from
  // there; with the hand-over off, pressure control tries steps past the maximum until it stalls,
  // and volume control starts there. The two must find the same maximum (the creeping reference
  // above agrees with the latter to 2e-4), the first with fewer Newton iterations and factorisations.
  const auto nh = test::material(std::make_shared<NeoHookean>(0.1153 / 2, VolumetricPolynomial({0.7029})), 1.08);
  auto spec = plain_tube(nh, 60.0);
  // Newton patient past the maximum (20 iterations a try), as the three ways were compared: with the
  // unstable-branch guard, a step that fails past the maximum caps the levels below it, the steps
  // creep up to the stall under the pressure where dp/dV extrapolates to zero, and the hand-over
  // after a failure becomes the stall's.
  spec.path.newton.max_indefinite_iterations = 0;
  const auto ahead = run_rra_scene(spec);
  spec.path.limit.hand_over_ahead = false;
  const auto after_failure = run_rra_scene(spec);
  spec.path.limit.hand_over_after_failure = false;
  const auto at_stall = run_rra_scene(spec);
  INFO(ahead.path.diagnosis << "\n" << after_failure.path.diagnosis << "\n" << at_stall.path.diagnosis);
  REQUIRE(ahead.path.limit_kind == LimitKind::traced);
  REQUIRE(after_failure.path.limit_kind == LimitKind::traced);
  REQUIRE(at_stall.path.limit_kind == LimitKind::traced);
  CHECK(ahead.path.handed_over_kPa > 0);
  CHECK(at_stall.path.handed_over_kPa == 0);
  CHECK(ahead.path.diagnosis.find("handed the path over") != std::string::npos);
  CHECK(ahead.path.estimated_limit_pressure_kPa == Approx(at_stall.path.estimated_limit_pressure_kPa).epsilon(2e-4));
  INFO("Newton iterations " << ahead.path.path.stats.newton_iterations << ", " << after_failure.path.path.stats.newton_iterations
                            << " vs " << at_stall.path.path.stats.newton_iterations << "; factorisations "
                            << ahead.path.factorizations << ", " << after_failure.path.factorizations << " vs "
                            << at_stall.path.factorizations);
  CHECK(ahead.path.path.stats.newton_iterations < at_stall.path.path.stats.newton_iterations);
  CHECK(ahead.path.factorizations < at_stall.path.factorizations);
  // Up to the hand-over both ran the same pressure-controlled steps.
  REQUIRE(ahead.path.history.size() <= at_stall.path.history.size());
  for (std::size_t i = 0; i < ahead.path.history.size(); ++i)
    CHECK(ahead.path.history[i].chamber_volume_mm3 == at_stall.path.history[i].chamber_volume_mm3);
  // Handed over once a step past the last state has failed (the 3D scenes' way): after the first
  // failure, not at the stall, for less work than the stall's and the same maximum.
  REQUIRE_FALSE(after_failure.path.path.stats.failed_levels.empty());
  CHECK(after_failure.path.handed_over_kPa > 0);
  CHECK(after_failure.path.handed_over_kPa < at_stall.path.history.back().pressure_kPa);
  CHECK(after_failure.path.path.stats.failed_levels.front() * spec.path.max_pressure_kPa > after_failure.path.handed_over_kPa);
  CHECK(after_failure.path.diagnosis.find("where a step past it had failed") != std::string::npos);
  CHECK(after_failure.path.estimated_limit_pressure_kPa ==
        Approx(at_stall.path.estimated_limit_pressure_kPa).epsilon(2e-4));
  CHECK(after_failure.path.path.stats.newton_iterations < at_stall.path.path.stats.newton_iterations);
  CHECK(after_failure.path.factorizations < at_stall.path.factorizations);
  // Volume control's first step from a hand-over, over the last pressure step's volume: a quarter (a
  // whole step lands past the top too far to place it). The hand-over after a failure tells the two
  // apart (with a whole first step this check failed); ahead, the whole step is retraced in quarters from
  // the same state, so both give 0.25. (At the stall the first step tried is whole; here it fails and
  // is halved, so the state reached says nothing of it.)
  const auto first_step_share = [](const PressurePathResult& p) {
    REQUIRE(p.history.size() >= 2);
    REQUIRE_FALSE(p.beyond_limit.empty());
    const double last = p.history.back().chamber_volume_mm3;
    return (p.beyond_limit.front().chamber_volume_mm3 - last) / (last - p.history[p.history.size() - 2].chamber_volume_mm3);
  };
  CHECK(first_step_share(ahead.path) == Approx(0.25).epsilon(1e-6));
  CHECK(first_step_share(after_failure.path) == Approx(0.25).epsilon(1e-6));
}

TEST_CASE("where volume control finds no maximum ahead, pressure control goes on as without the hand-over", "[rra][limit]") {
  // The Dragon Skin 30 (Ogden) tube's dp/dV dips and recovers: from 22 kPa (a first step of a
  // quarter of 88 kPa) it extrapolates to zero at 41.7 kPa, short of the next step, so pressure
  // control hands over; volume control climbs to 88 kPa without a maximum, and pressure control goes
  // on from the handed-over state. It must end where pressure control alone ends.
  auto spec = plain_tube(builtin_material("dragon_skin_30", "test"), 88.0);
  spec.path.output_pressures_kPa = {88.0};
  spec.path.steps.initial_increment = 0.25;
  const auto ahead = run_rra_scene(spec);
  spec.path.limit.hand_over_ahead = false;
  spec.path.limit.hand_over_after_failure = false;
  const auto alone = run_rra_scene(spec);
  INFO(ahead.path.diagnosis << "\n" << alone.path.diagnosis);
  REQUIRE(ahead.path.outcome == PathOutcome::completed);
  REQUIRE(alone.path.outcome == PathOutcome::completed);
  CHECK(ahead.path.handed_over_kPa == Approx(22.0));
  CHECK(ahead.path.diagnosis.find("found no maximum before 88 kPa") != std::string::npos);
  CHECK(ahead.path.beyond_limit.empty());
  CHECK(ahead.path.history.back().chamber_volume_mm3 == Approx(alone.path.history.back().chamber_volume_mm3).epsilon(1e-9));
  REQUIRE(ahead.curve.size() == alone.curve.size());
  CHECK(ahead.curve.back().extension_mm == Approx(alone.curve.back().extension_mm).epsilon(1e-9));
}

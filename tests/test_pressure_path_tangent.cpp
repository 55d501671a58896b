// What a pressure path hands on with each converged state (fem/scenes/pressure_path.hpp,
// ConvergedTangent): the tangent at that state, and CG on the path's factor that solves with it as
// the tangent's own factorisation does. The ring-pitch cells take their end-face compliances so
// (fem/scenes/tca_cell.cpp), the path its own dp/dV; a wrong matrix (an iterate's, another load's) or
// a solve to the wrong tolerance fails here. A short plain 3D tube (Hex20 at 2×2×2 points, level 1,
// half model), Newton reusing factors as the 3D scenes do.
#include <catch2/catch.hpp>
#include <memory>

#include "fem/assembly/energy_problem.hpp"
#include "fem/forms/chamber_pressure_form.hpp"
#include "fem/forms/make_elastic_form.hpp"
#include "fem/mesh/tca_mesher.hpp"
#include "fem/scenes/pressure_path.hpp"
#include "fem/scenes/solid_scene_support.hpp"

using namespace softarm::fem;

TEST_CASE("Each converged state comes with its tangent, and CG on the path's factor solves with it as its own factor does",
          "[solver][rra3d]") {
  RraDesign tube;
  tube.length_mm = 30;
  tube.bottom_radius_mm = tube.top_radius_mm = 9;
  tube.wall_thickness_mm = 3;
  tube.end_cap_thickness_mm = 2;
  tube.ring_count = 0;
  SolidMeshOptions options{1, 2, true, 0};
  options.serendipity = true;
  const Mesh mesh = mesh_rra_3d(tube, options);
  LoadState load;
  load.chamber_pressure_MPa.assign(1, 0.0);
  EnergyProblem problem(flattened_positions(mesh), clamped_with_symmetry(mesh, "top"));
  const std::vector<Material> materials = {builtin_material("dragon_skin_30", "test"),
                                           builtin_material("digital_abs", "test")};  // the mesh's ring part is empty
  problem.add_form(make_elastic_form(mesh, materials, VolumetricTreatment::projected_dilatation, ElementIntegration::reduced));
  auto chamber = std::make_shared<ChamberPressureForm>(mesh, 0, load);
  problem.add_form(chamber);
  problem.finalize();
  PressurePathSpec path;
  path.max_pressure_kPa = 60;
  path.output_pressures_kPa = {20, 40, 60};
  path.newton.reuse_factor = true;
  path.newton.shift_indefinite_tangent = true;
  Vector x = problem.reference_positions();
  Vector b = Vector::LinSpaced(problem.num_dofs(), -1.0, 1.0);  // a load on every free dof
  problem.zero_prescribed(b);
  int states = 0, by_cg = 0;
  LinearSolver own;
  const auto result = run_pressure_path(problem, {chamber.get()}, load, x, path,
                                        [&](const PressureState& s, const Vector& xs, const ConvergedTangent& tangent) {
    ++states;
    REQUIRE(tangent.matrix);
    REQUIRE(tangent.solve_on_path_factor);
    // The tangent at this state under this state's pressure.
    const SparseMatrix K = problem.evaluate(xs, false, true).hessian;
    INFO("state at " << s.pressure_kPa << " kPa");
    CHECK((*tangent.matrix - K).norm() <= 1e-12 * K.norm());
    REQUIRE(own.factorize(K) == LinearSolver::Status::positive_definite);
    const Vector exact = own.solve(b);
    // dp/dV = 1/(∇Vᵀ K⁻¹ ∇V), which the path solves by CG on its factor to 10⁻⁵ (pressure_path.cpp: a
    // quadratic form, its error second order in CG's residual), against K's own factor. Measured within
    // 3·10⁻¹¹; with CG to 10⁻² instead, 1.1·10⁻⁷ at one state, which fails here.
    Vector g = chamber->volume_gradient(xs);
    problem.zero_prescribed(g);
    const double dp_dV_kPa_per_mm3 = 1e3 / g.dot(own.solve(g));
    CHECK(s.pv_stiffness_kPa_per_mm3 == Approx(dp_dV_kPa_per_mm3).epsilon(1e-8));
    Vector d;
    if (!tangent.solve_on_path_factor(b, 1e-10, d)) return;
    ++by_cg;
    CHECK((K * d - b).norm() <= 1e-10 * b.norm() * 1.0001);
    CHECK((d - exact).norm() <= 1e-6 * exact.norm());
  });
  REQUIRE(result.outcome == PathOutcome::completed);
  CHECK(states >= 4);  // the rest state and the three outputs at least
  INFO(by_cg << " of " << states << " states solved by CG on the path's factor");
  // Most states: where the path's factor is a few states old, CG on it can miss its budget (two of
  // eight here, the caller then factorises K itself), but a path whose CG never served would fail.
  CHECK(by_cg >= states / 2);
}

// Element and pressure-load tangents against central finite differences.
//
// Tolerances: central differences have truncation error O(h²)·|f'''| and
// round-off O(ε|f|/h). With coordinates O(1–10 mm), moduli O(0.1–3000 MPa)
// and h = 1e-6 mm, truncation is ~1e-12 relative and round-off ~1e-16/1e-6 ·
// (|Π|/|g|) ≈ 1e-9…1e-8 relative, so 1e-6 leaves two orders of margin while
// any wrong term (a missing geometric stiffness, a sign) shows as O(1).
#include <algorithm>

#include <catch2/catch.hpp>

#include "fem/forms/chamber_pressure_form.hpp"
#include "fem/forms/make_elastic_form.hpp"
#include "fem/mesh/quadratic_mesh.hpp"
#include "fem/mesh/structured_mesh.hpp"
#include "support/form_checks.hpp"
#include "support/test_problems.hpp"

using namespace softarm;
using namespace softarm::fem;

namespace {

// A distorted 3×3 patch of a thick tube (r from 2 to 5 mm), bottom fixed axially.
struct Patch {
  Mesh mesh;
  LoadState load;
  std::unique_ptr<EnergyProblem> problem;
};

std::unique_ptr<Patch> make_patch(const std::vector<Material>& materials, VolumetricTreatment treatment,
                                  double pressure_MPa, int order) {
  auto p = std::make_unique<Patch>();
  p->mesh = rectangle_mesh(2.0, 5.0, 0.0, 3.0, 3, 3, 0.2);
  if (order == 2) p->mesh = to_quadratic(p->mesh);
  p->load.chamber_pressure_MPa = {pressure_MPa};
  DirichletConstraints c;
  for (int n : p->mesh.node_sets.at("bottom")) c.fix(2 * n + 1);
  p->problem = std::make_unique<EnergyProblem>(flattened_positions(p->mesh), c);
  std::vector<Material> parts(p->mesh.part_names.size(), materials.front());
  p->problem->add_form(make_elastic_form(p->mesh, parts, treatment));
  if (pressure_MPa != 0.0) p->problem->add_form(std::make_shared<ChamberPressureForm>(p->mesh, 0, p->load));
  p->problem->finalize();
  return p;
}

}  // namespace

TEST_CASE("axisymmetric elastic form: gradient and Hessian match finite differences", "[forms]") {
  const double h = 1e-6;
  for (int order : {1, 2})
    for (const auto& c : test::form_cases()) {
      auto patch = make_patch({c.material}, c.treatment, 0.0, order);
      // A large, non-homogeneous deformation (up to ±0.4 mm on 1 mm elements; ±0.2 mm
      // for Q2, whose edge midpoints sit 0.5 mm from the corners).
      const Vector x = test::perturbed(patch->problem->reference_positions(), order == 1 ? 0.4 : 0.2);
      const auto err = test::finite_difference_errors(*patch->problem, x, h);
      INFO("Q" << order << ", " << c.name << ": gradient error " << err.gradient << ", Hessian error " << err.hessian);
      CHECK(err.gradient < 1e-6);
      CHECK(err.hessian < 1e-6);
    }
}

TEST_CASE("The Hessian is the identity at prescribed dofs, and a moved Evaluation hands it over uncopied", "[forms]") {
  auto patch = make_patch({test::form_cases().front().material}, test::form_cases().front().treatment, 0.01, 2);
  const EnergyProblem& problem = *patch->problem;
  const Vector x = test::perturbed(problem.reference_positions(), 0.2);
  Evaluation e = problem.evaluate(x, true, true);
  REQUIRE(e.status.ok);
  const auto& prescribed = problem.is_prescribed();
  REQUIRE(std::count(prescribed.begin(), prescribed.end(), 1) > 0);
  int free_couplings = 0;
  for (int c = 0; c < e.hessian.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(e.hessian, c); it; ++it) {
      const int r = static_cast<int>(it.row());
      if (prescribed[c] || prescribed[r]) CHECK(it.value() == (r == c ? 1.0 : 0.0));
      else free_couplings += it.value() != 0.0;
    }
  CHECK(free_couplings > 0);

  // Eigen 3.4's SparseMatrix cannot move; Evaluation's moves swap it (energy_problem.hpp).
  const double* values = e.hessian.valuePtr();
  const SparseMatrix copy = e.hessian;
  Evaluation moved(std::move(e));
  CHECK(moved.hessian.valuePtr() == values);
  Evaluation assigned;
  assigned = std::move(moved);
  CHECK(assigned.hessian.valuePtr() == values);
  CHECK((assigned.hessian - copy).norm() == 0.0);
  const Evaluation copied = assigned;  // a copy stays a copy
  CHECK(copied.hessian.valuePtr() != values);
  CHECK((copied.hessian - copy).norm() == 0.0);
}

TEST_CASE("chamber pressure form: exact volume, gradient and load stiffness", "[forms]") {
  for (int order : {1, 2}) {
  const Mesh mesh = order == 1 ? rectangle_mesh(2.0, 5.0, 0.0, 3.0, 3, 3, 0.2)
                               : to_quadratic(rectangle_mesh(2.0, 5.0, 0.0, 3.0, 3, 3, 0.2));
  const test::PressureOnly pressure(mesh, 0.3);
  // Reference: the chain along r = 2 from z = 0 to 3 sweeps a cylinder π r² h.
  CHECK(pressure.chamber->volume(pressure.problem->reference_positions()) ==
        Approx(3.141592653589793 * 4.0 * 3.0).epsilon(1e-14));
  pressure.check_derivatives(0.4, order == 1 ? "Q1" : "Q2");
  }
}

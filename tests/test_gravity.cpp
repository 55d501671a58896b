// Self-weight: the support reaction of a block hanging under gravity equals
// its weight ρ g V, in 3D and in axisymmetry, and the gravity form's gradient
// (and zero Hessian) match central finite differences.
#include <catch2/catch.hpp>
#include <stdexcept>

#include "fem/core/angles.hpp"
#include "fem/forms/gravity_form.hpp"
#include "fem/forms/make_elastic_form.hpp"
#include "fem/mesh/quadratic_mesh.hpp"
#include "fem/mesh/structured_mesh.hpp"
#include "fem/solver/load_stepper.hpp"
#include "support/test_problems.hpp"

using namespace softarm;
using namespace softarm::fem;

namespace {
constexpr double kStandardGravity = 9.80665;  // m/s²

struct HangingBlock {
  Mesh mesh;
  LoadState load;
  std::shared_ptr<GravityForm> gravity;
  std::unique_ptr<EnergyProblem> problem;
  std::vector<int> fixed_dofs;
};

// A body of soft silicone (ρ = 1.08 g/cm³, Dragon Skin 30) with its "top" node set
// clamped, under gravity −g e_z.
std::unique_ptr<HangingBlock> hanging(Mesh mesh, const std::string& top) {
  auto b = std::make_unique<HangingBlock>();
  b->mesh = std::move(mesh);
  const Material silicone = test::material(test::dragon_skin_30_ogden(2.0 / 0.7029).law, 1.08);
  DirichletConstraints c;
  for (int n : b->mesh.node_sets.at(top))
    for (int i = 0; i < b->mesh.dim; ++i) {
      c.fix(b->mesh.dim * n + i);
      b->fixed_dofs.push_back(b->mesh.dim * n + i);
    }
  b->problem = std::make_unique<EnergyProblem>(flattened_positions(b->mesh), c);
  const std::vector<Material> parts{silicone};
  b->problem->add_form(b->mesh.dim == 3 ? make_elastic_form(b->mesh, parts)
                                        : make_elastic_form(b->mesh, parts));
  b->gravity = std::make_shared<GravityForm>(b->mesh, parts, Eigen::Vector3d(0, 0, -kStandardGravity), b->load);
  b->problem->add_form(b->gravity);
  b->problem->finalize();
  return b;
}

// Hangs the block at full gravity; returns the z force R that the support exerts on it.
// Treating R as an external load on the clamped dofs, Π − R·x is stationary at
// equilibrium, so R = ∂Π/∂x there: the elastic force plus the weight of the clamped
// nodes' share, which goes straight into the support.
double support_force_z(HangingBlock& b) {
  Vector x = b.problem->reference_positions();
  LinearSolver solver;
  PathCallbacks cb{[&](double level) { b.load.gravity_scale = level; }, {}};
  const auto result = follow_load_path(*b.problem, x, solver, {1.0}, cb, NewtonSettings{}, StepSettings{});
  REQUIRE(result.completed);
  Vector g = Vector::Zero(x.size());
  for (const auto& form : b.problem->forms()) REQUIRE(form->add(x, nullptr, &g, nullptr).ok);
  double force = 0.0;
  for (int d : b.fixed_dofs)
    if (d % b.mesh.dim == b.mesh.dim - 1) force += g[d];
  return force;
}
}  // namespace

TEST_CASE("gravity: a hanging block's support carries exactly its weight", "[gravity]") {
  // Σ_a f_a = ∫ ρ g Σ_a N_a dV = ρ g V because the shape functions sum to one and
  // the Gauss rules integrate det(∂X/∂ξ) (and 2πR det in axisymmetry) exactly on
  // these meshes; the equilibrium residual at the free dofs (~1e-10 relative after
  // Newton) is what separates the support force from it, so 1e-8 is the bound.
  const double rho = 1.08e-6;  // kg/mm³
  for (int order : {1, 2}) {
    const Mesh linear = box_mesh(Eigen::Vector3d::Zero(), Eigen::Vector3d(10, 10, 20), 2, 2, 4, 0.5);
    auto block = hanging(order == 1 ? linear : to_quadratic_3d(linear), "z1");
    const double weight = rho * kStandardGravity * 10 * 10 * 20;  // N
    const double support = support_force_z(*block);
    INFO("Hex" << (order == 1 ? 8 : 27) << ": support force " << support << " N, weight " << weight << " N");
    CHECK(block->gravity->nodal_forces().sum() == Approx(-weight).epsilon(1e-13));
    CHECK(support == Approx(weight).epsilon(1e-8));
  }
  for (int order : {1, 2}) {  // axisymmetric: a thick tube, r from 2 to 5 mm, 10 mm long, clamped at the top
    const Mesh linear = rectangle_mesh(2.0, 5.0, 0.0, 10.0, 3, 6, 0.3);
    auto tube = hanging(order == 1 ? linear : to_quadratic(linear), "top");
    const double weight = rho * kStandardGravity * kPi * (25.0 - 4.0) * 10.0;
    const double support = support_force_z(*tube);
    INFO("Q" << order << ": support force " << support << " N, weight " << weight << " N");
    CHECK(support == Approx(weight).epsilon(1e-8));
  }
}

TEST_CASE("gravity: gradient and zero Hessian match finite differences, and off-axis gravity is refused", "[gravity]") {
  // The FD tolerance is test_forms.cpp's; gravity's gradient is constant, so any
  // error would be a wrong nodal force, not a truncation effect.
  for (int dim : {2, 3}) {
    auto b = dim == 3 ? hanging(box_mesh(Eigen::Vector3d::Zero(), Eigen::Vector3d(2, 2, 2), 2, 2, 2, 1.0), "z1")
                      : hanging(rectangle_mesh(2.0, 5.0, 0.0, 3.0, 3, 3, 0.2), "top");
    b->load.gravity_scale = 5e4;  // large enough that the weight competes with the elastic forces
    const Vector x = test::perturbed(b->problem->reference_positions(), 0.1, 3);
    const auto err = test::finite_difference_errors(*b->problem, x, 1e-6);
    INFO("dim " << dim << ": gradient error " << err.gradient << ", Hessian error " << err.hessian);
    CHECK(err.gradient < 1e-6);
    CHECK(err.hessian < 1e-6);
  }
  const Mesh rz = rectangle_mesh(2.0, 5.0, 0.0, 3.0, 1, 1);
  LoadState load;
  CHECK_THROWS_AS(GravityForm(rz, {test::neo_hookean(1, 100)}, Eigen::Vector3d(1, 0, -9.8), load), std::logic_error);
}

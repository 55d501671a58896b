// The 3D (hexahedral) core: element and pressure-load derivatives against
// central finite differences, the exact volume of a box cavity, the patch test
// under a non-symmetric homogeneous deformation, and nearly incompressible
// Ogden uniaxial tension against the closed form; Hex8 (H1/P0), Hex20 (serendipity,
// H2s/P1, at 3×3×3 and at 2×2×2 Gauss points) and Hex27 (H2/P1).
//
// Finite-difference tolerance 1e-6, as in test_forms.cpp: with coordinates
// O(1 mm), moduli O(0.1–3000 MPa) and h = 1e-6 mm, the truncation error is
// ~1e-12 relative and round-off ~1e-16/1e-6·|Π|/|g| ≈ 1e-9…1e-8, so 1e-6
// leaves two orders of margin while a wrong term shows as O(1).
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <cstdlib>
#include <map>
#include <vector>

#include "fem/elements/hexahedron.hpp"
#include "fem/elements/serendipity_quad.hpp"
#include "fem/forms/chamber_pressure_form.hpp"
#include "fem/forms/make_elastic_form.hpp"
#include "fem/forms/mean_displacement_form.hpp"
#include "fem/forms/periodic_face_form.hpp"
#include "fem/forms/plane_face_form.hpp"
#include "fem/mesh/chamber_lids.hpp"
#include "fem/mesh/quadratic_mesh.hpp"
#include "fem/mesh/serendipity_mesh.hpp"
#include "fem/mesh/structured_mesh.hpp"
#include "fem/solver/load_stepper.hpp"
#include "fem/solver/lowest_modes.hpp"
#include "support/form_checks.hpp"
#include "support/test_problems.hpp"
#include "support/tube_meshes.hpp"

using namespace softarm;
using namespace softarm::fem;

namespace {

constexpr int kHexKinds[3] = {8, 20, 27};  // nodes per element

/// The element formulations: a mesh's nodes per element and the Gauss rule.
struct ElementKind {
  int nodes;
  ElementIntegration integration;
  const char* name;
};
constexpr ElementKind kElementKinds[4] = {{8, ElementIntegration::full, "Hex8"},
                                          {20, ElementIntegration::full, "Hex20"},
                                          {20, ElementIntegration::reduced, "Hex20 reduced"},
                                          {27, ElementIntegration::full, "Hex27"}};

/// A Hex8 mesh as it is, or promoted to Hex27 or Hex20 (`nodes`).
Mesh promoted(const Mesh& linear, int nodes) {
  if (nodes == 8) return linear;
  const Mesh hex27 = to_quadratic_3d(linear);
  return nodes == 27 ? hex27 : serendipity_from_triquadratic(hex27);
}

Mesh box(const Eigen::Vector3d& hi, int nx, int ny, int nz, double distortion, int nodes) {
  return promoted(box_mesh(Eigen::Vector3d::Zero(), hi, nx, ny, nz, distortion), nodes);
}

/// The boundary faces of a Hex8 mesh as a chamber whose cavity is the meshed body
/// itself (normals outward): the closed surface of a box-shaped cavity.
Chamber boundary_chamber(const Mesh& mesh) {
  // Faces of the VTK hexahedron, ordered so that x_s × x_t points out of the element.
  constexpr int kFaces[6][4] = {{0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4}, {3, 7, 6, 2}, {0, 3, 2, 1}, {4, 5, 6, 7}};
  std::map<std::vector<int>, std::vector<std::vector<int>>> faces;  // sorted corners → the faces with them
  for (int e = 0; e < mesh.num_elements(); ++e)
    for (const auto& local : kFaces) {
      std::vector<int> face;
      for (int a : local) face.push_back(mesh.element(e)[a]);
      auto key = face;
      std::sort(key.begin(), key.end());
      faces[key].push_back(face);
    }
  Chamber chamber{1, "box", {}, {}};
  for (const auto& [key, list] : faces)
    if (list.size() == 1) chamber.facets.push_back(list.front());
  return chamber;
}

/// Solves the problem from its reference state to full load; returns the final positions.
Vector solve(const EnergyProblem& problem, const std::vector<double>& levels, const PathCallbacks& cb) {
  Vector x = problem.reference_positions();
  LinearSolver solver;
  const auto result = follow_load_path(problem, x, solver, levels, cb, NewtonSettings{}, StepSettings{});
  REQUIRE(result.completed);
  return x;
}

}  // namespace

TEST_CASE("3D elastic form: gradient and Hessian match finite differences", "[solid3d]") {
  for (const auto& kind : kElementKinds)
    for (const auto& c : test::form_cases()) {
      const int nodes = kind.nodes;
      // Two elements along each axis of 1 mm: every node couples across element faces.
      const Mesh mesh = nodes == 8 ? box({2, 2, 2}, 2, 2, 2, 1.0, 8) : box({2, 1, 1}, 2, 1, 1, 1.0, nodes);
      EnergyProblem problem(flattened_positions(mesh), DirichletConstraints{});
      problem.add_form(make_elastic_form(mesh, {c.material}, c.treatment, kind.integration));
      problem.finalize();
      // A large, non-homogeneous deformation: ±0.2 mm on 1 mm elements (±0.1 mm for
      // the quadratic elements, whose mid-edge nodes sit 0.5 mm from the corners).
      const Vector x = test::perturbed(problem.reference_positions(), nodes == 8 ? 0.2 : 0.1);
      const auto err = test::finite_difference_errors(problem, x, 1e-6);
      INFO(kind.name << ", " << c.name << ": gradient error " << err.gradient
                 << ", Hessian error " << err.hessian);
      CHECK(err.gradient < 1e-6);
      CHECK(err.hessian < 1e-6);
    }
}

TEST_CASE("3D chamber pressure form: exact box volume, gradient and load stiffness", "[solid3d]") {
  for (int nodes : kHexKinds) {
    Mesh linear = box_mesh(Eigen::Vector3d::Zero(), Eigen::Vector3d(2, 3, 4), 2, 2, 2, 1.0);
    linear.chambers.push_back(boundary_chamber(linear));
    const Mesh mesh = promoted(linear, nodes);
    const test::PressureOnly pressure(mesh, 0.3);
    // The facets are bilinear (or quadratic reproducing bilinear) patches of the
    // planar box faces (distortion moves interior nodes only): V = 2·3·4 to round-off.
    CHECK(pressure.chamber->volume(pressure.problem->reference_positions()) == Approx(24.0).epsilon(1e-14));
    // A homogeneous deformation maps the box to a parallelepiped of volume det F0 · 24.
    Eigen::Matrix3d F0;
    F0 << 1.2, 0.3, 0.1, -0.1, 0.9, 0.2, 0.05, 0.15, 1.1;
    Vector y(3 * mesh.num_nodes());
    for (int n = 0; n < mesh.num_nodes(); ++n) y.segment<3>(3 * n) = F0 * mesh.X.row(n).transpose();
    CHECK(pressure.chamber->volume(y) == Approx(24.0 * F0.determinant()).epsilon(1e-13));
    pressure.check_derivatives(0.3, std::to_string(nodes == 8 ? 4 : nodes == 20 ? 8 : 9) + "-node facets");
  }
}

namespace {
/// The [0,2]×[0,3]×[0,4] box as a cavity of `nodes`-node hexahedra with its top face (z = 4) cut
/// away, and with `half` its y = 0 face too, closed by add_chamber_lids along the cut.
Mesh cut_box_cavity(int nodes, bool half) {
  Mesh linear = box_mesh(Eigen::Vector3d::Zero(), Eigen::Vector3d(2, 3, 4), 2, 2, 2, 1.0);
  linear.chambers.push_back(boundary_chamber(linear));
  Mesh mesh = promoted(linear, nodes);
  std::vector<int> top;
  for (int n = 0; n < mesh.num_nodes(); ++n)
    if (mesh.X(n, 2) == 4.0) top.push_back(n);
  const auto on = [&](const std::vector<int>& f, int axis, double value) {
    return std::all_of(f.begin(), f.end(), [&](int n) { return mesh.X(n, axis) == value; });
  };
  std::erase_if(mesh.chambers[0].facets,
                [&](const std::vector<int>& f) { return on(f, 2, 4.0) || (half && on(f, 1, 0.0)); });
  add_chamber_lids(mesh, top);
  return mesh;
}
}  // namespace

TEST_CASE("3D chamber lids close a cavity cut open, on a closed loop and on a chain ending on y = 0", "[solid3d][cell]") {
  // The box cavity with its top face (z = 4) cut away, and once also its y = 0 face: a
  // symmetry plane through the origin adds nothing to V (chamber_pressure_form.hpp), so
  // the lid's chain then ends on it and its fan closes along it.
  for (int nodes : kHexKinds)
    for (const bool half : {false, true}) {
      const Mesh mesh = cut_box_cavity(nodes, half);
      const std::string label = std::to_string(nodes) + "-node facets" + (half ? ", open at y = 0" : "");
      INFO(label);
      REQUIRE(mesh.chambers[0].lids.size() == 1);
      // The loop runs round the top face's edges: 8 corner nodes, and 8 midside ones on quadratic facets;
      // the half chain has one node more than the edges it runs along (it does not return to its start).
      const std::size_t edges = half ? 6 : 8;
      CHECK(mesh.chambers[0].lids[0].size() == (nodes == 8 ? edges : 2 * edges) + (half ? 1 : 0));
      const test::PressureOnly pressure(mesh, 0.3);
      const Vector X = pressure.problem->reference_positions();
      // The fan spans the flat top exactly, and maps with it under a homogeneous deformation.
      CHECK(pressure.chamber->volume(X) == Approx(24.0).epsilon(1e-13));
      Eigen::Matrix3d F0;
      F0 << 1.2, 0.0, 0.1, 0.0, 0.9, 0.0, 0.05, 0.0, 1.1;  // keeps y = 0 on itself
      Vector y(X.size()), shifted(X.size());
      for (int n = 0; n < mesh.num_nodes(); ++n) {
        y.segment<3>(3 * n) = F0 * X.segment<3>(3 * n);
        shifted.segment<3>(3 * n) = X.segment<3>(3 * n) + Eigen::Vector3d(0.7, 0.0, -1.3);
      }
      CHECK(pressure.chamber->volume(y) == Approx(24.0 * F0.determinant()).epsilon(1e-13));
      // A closed surface's volume does not depend on the origin (in the plane y = 0 for the half).
      CHECK(pressure.chamber->volume(shifted) == Approx(24.0).epsilon(1e-13));
      pressure.check_derivatives(0.3, label);
    }
}

TEST_CASE("3D chamber lids follow the quadratic facets' curved edges on the cut", "[solid3d][cell]") {
  // The box cavity cut open at z = 4 as above, mapped by φ(x, y, z) = (x + a y², y (1 + b x), z):
  // the cut stays flat but its edges along y become parabolas, which quadratic facets carry exactly.
  // det ∇φ = 1 + b x − 2ab y², so the cavity's volume is 24 + 24 b − 144 a b over [0,2]×[0,3]×[0,4];
  // a fan of chords would leave slivers open between them and the edges (the volume then moves
  // under a rigid translation). φ keeps y = 0 on itself, so the half chain closes along it too.
  const double a = 0.05, b = 0.04, exact = 24 + 24 * b - 144 * a * b;
  for (int nodes : {20, 27})
    for (const bool half : {false, true}) {
      const Mesh mesh = cut_box_cavity(nodes, half);
      INFO(nodes << "-node facets" << (half ? ", open at y = 0" : ""));
      const test::PressureOnly pressure(mesh, 0.3);
      const Vector X = pressure.problem->reference_positions();
      Vector y(X.size()), shifted(X.size());
      for (int n = 0; n < mesh.num_nodes(); ++n) {
        const Eigen::Vector3d p = X.segment<3>(3 * n);
        y.segment<3>(3 * n) = Eigen::Vector3d(p.x() + a * p.y() * p.y(), p.y() * (1 + b * p.x()), p.z());
        shifted.segment<3>(3 * n) = y.segment<3>(3 * n) + Eigen::Vector3d(0.7, 0.0, -1.3);
      }
      CHECK(pressure.chamber->volume(y) == Approx(exact).epsilon(1e-12));
      CHECK(pressure.chamber->volume(shifted) == Approx(exact).epsilon(1e-12));
      pressure.check_derivatives(0.3, "curved cut");
    }
}

TEST_CASE("Plane face form: gradient and Hessian match finite differences", "[solid3d][cell]") {
  const Mesh mesh = box({2, 1, 1}, 2, 1, 1, 1.0, 20);
  std::vector<int> top;
  for (int n = 0; n < mesh.num_nodes(); ++n)
    if (mesh.X(n, 2) == 1.0) top.push_back(n);
  const int pilot = mesh.num_nodes();
  Vector X(3 * (pilot + 1));
  X << flattened_positions(mesh), 0.0, 0.0, 0.0;
  EnergyProblem problem(X, DirichletConstraints{});
  auto plane = std::make_shared<PlaneFaceForm>(top, pilot, 1.0, 3.7);
  problem.add_form(plane);
  problem.finalize();
  Vector x = test::perturbed(X, 0.1);
  x.tail<3>() << 0.05, -0.2, 0.15;  // offset and both slopes
  const auto err = test::finite_difference_errors(problem, x, 1e-6);
  INFO("gradient error " << err.gradient << ", Hessian error " << err.hessian);
  CHECK(err.gradient < 1e-6);
  CHECK(err.hessian < 1e-6);
  // On the plane the penalty vanishes with its gradient.
  Vector on_plane = x;
  for (int n : top) on_plane[3 * n + 2] = 1.0 + 0.05 - 0.2 * x[3 * n] + 0.15 * x[3 * n + 1];
  CHECK(plane->max_gap(on_plane) < 1e-15);
  CHECK(problem.evaluate(on_plane, true, false).gradient.norm() < 1e-13);
}

TEST_CASE("Plane face form referenced to a node: derivatives match finite differences, translations cost nothing",
          "[solid3d][cell]") {
  const Mesh mesh = box({2, 1, 1}, 2, 1, 1, 1.0, 20);
  std::vector<int> top;
  for (int n = 0; n < mesh.num_nodes(); ++n)
    if (mesh.X(n, 2) == 1.0) top.push_back(n);
  const int pilot = mesh.num_nodes(), reference = 0;  // a bottom corner
  Vector X(3 * (pilot + 1));
  X << flattened_positions(mesh), 0.0, 0.0, 0.0;
  EnergyProblem problem(X, DirichletConstraints{});
  auto plane = std::make_shared<PlaneFaceForm>(top, pilot, 1.0, 3.7, reference,
                                               mesh.X.row(reference).head<2>().transpose());
  problem.add_form(plane);
  problem.finalize();
  Vector x = test::perturbed(X, 0.1);
  x.tail<3>() << 0.05, -0.2, 0.15;
  const auto err = test::finite_difference_errors(problem, x, 1e-6);
  INFO("gradient error " << err.gradient << ", Hessian error " << err.hessian);
  CHECK(err.gradient < 1e-6);
  CHECK(err.hessian < 1e-6);
  // Every node moved by (0.3, −0.7) in-plane, the pilot kept: the same energy and gradient.
  Vector shifted = x;
  for (int n = 0; n < pilot; ++n) shifted.segment<2>(3 * n) += Eigen::Vector2d(0.3, -0.7);
  const Evaluation e0 = problem.evaluate(x, true, false), e1 = problem.evaluate(shifted, true, false);
  CHECK(e1.energy == Approx(e0.energy).epsilon(1e-12));
  CHECK((e1.gradient - e0.gradient).norm() <= 1e-12 * e0.gradient.norm());
}

TEST_CASE("Mean displacement hold: derivatives match finite differences", "[solid3d][cell]") {
  const Vector X = Vector::LinSpaced(12, -1.0, 2.0);
  EnergyProblem problem(X, DirichletConstraints{});
  auto hold = std::make_shared<MeanDisplacementForm>(std::vector<int>{1, 4, 7, 10}, std::vector<double>{X[1], X[4], X[7], X[10]}, 2.5);
  problem.add_form(hold);
  problem.finalize();
  const Vector x = test::perturbed(X, 0.3);
  const auto err = test::finite_difference_errors(problem, x, 1e-6);
  INFO("gradient error " << err.gradient << ", Hessian error " << err.hessian);
  CHECK(err.gradient < 1e-6);
  CHECK(err.hessian < 1e-6);
  const double m = (x[1] - X[1] + x[4] - X[4] + x[7] - X[7] + x[10] - X[10]) / 4;
  CHECK(hold->mean_displacement(x) == Approx(m).epsilon(1e-14));
  CHECK(problem.evaluate(x, false, false).energy == Approx(0.5 * 2.5 * m * m).epsilon(1e-14));
}

TEST_CASE("A half cell's in-plane translation held by its face's mean: no force at equilibrium, no soft mode",
          "[solid3d][cell]") {
  // Half of a squat 8 × 8 × 2 mm block (y ≥ 0, the mirror plane y = 0 held in y), like a ring-pitch
  // cell: bottom held in z, the top face on a plane referenced to the bottom node at (4, 0, 0), a
  // stretching force on the plane's offset a and a moment on its slope b. Its x translation held at
  // that node, as the cells once were, or by the bottom face's mean x displacement.
  const Mesh mesh = box({8, 4, 2}, 8, 4, 2, 0.0, 20);
  const int pilot = mesh.num_nodes();
  int centre = -1;
  std::vector<int> top, bottom;
  for (int n = 0; n < pilot; ++n) {
    if (mesh.X(n, 2) == 2.0) top.push_back(n);
    if (mesh.X(n, 2) == 0.0) bottom.push_back(n);
    if ((mesh.X.row(n) - Eigen::RowVector3d(4, 0, 0)).norm() < 1e-12) centre = n;
  }
  REQUIRE(centre >= 0);
  Vector X(3 * (pilot + 1));
  X << flattened_positions(mesh), 0.0, 0.0, 0.0;
  LoadState load;
  enum class Hold { pin, mean, none };
  const auto make = [&](Hold hold, bool referenced) {
    DirichletConstraints bc;
    for (int n : bottom) bc.fix(3 * n + 2);
    for (int n : mesh.node_sets.at("y0")) bc.fix(3 * n + 1);
    bc.fix(3 * pilot + 2);
    if (hold == Hold::pin) bc.fix(3 * centre);
    auto p = std::make_unique<EnergyProblem>(X, bc);
    const double mu = 0.1;  // MPa
    p->add_form(make_elastic_form(mesh, {test::neo_hookean(mu, 100 * mu)}, VolumetricTreatment::projected_dilatation));
    p->add_form(referenced ? std::make_shared<PlaneFaceForm>(top, pilot, 2.0, 1e4 * mu, centre, Eigen::Vector2d(4, 0))
                           : std::make_shared<PlaneFaceForm>(top, pilot, 2.0, 1e4 * mu));
    if (hold == Hold::mean) {
      std::vector<int> dofs;
      std::vector<double> reference;
      for (int n : bottom) dofs.push_back(3 * n), reference.push_back(mesh.X(n, 0));
      p->add_form(std::make_shared<MeanDisplacementForm>(dofs, reference, mu * bottom.size()));
    }
    p->add_form(std::make_shared<DofLoadForm>(std::vector<int>{3 * pilot, 3 * pilot + 1}, std::vector<double>{0.2, 0.5}, load));
    p->finalize();
    return p;
  };
  const PathCallbacks ramp{[&](double level) { load.gravity_scale = level; }, {}};
  const auto pinned = make(Hold::pin, true), held = make(Hold::mean, true);
  const Vector xp = solve(*pinned, {1.0}, ramp), xm = solve(*held, {1.0}, ramp);
  const double scale = pinned->evaluate(xp, true, false).force_scale();
  // The same plane (a, b) either way: the cells' readings.
  CHECK(xm[3 * pilot] == Approx(xp[3 * pilot]).epsilon(1e-7));
  CHECK(xm[3 * pilot + 1] == Approx(xp[3 * pilot + 1]).epsilon(1e-7));
  // The pin carries no force: the pinned state moved by minus its bottom face's mean x displacement
  // is the mean-held problem's equilibrium, the formerly pinned dof included.
  double t = 0;
  for (int n : bottom) t += (xp[3 * n] - X[3 * n]) / static_cast<double>(bottom.size());
  Vector moved = xp;
  for (int n = 0; n < pilot; ++n) moved[3 * n] -= t;
  Vector g = held->evaluate(moved, true, false).gradient;
  held->zero_prescribed(g);
  INFO("force scale " << scale << " N, slope " << xp[3 * pilot + 1] << ", translation " << t << " mm");
  CHECK(g.norm() < 1e-7 * scale);
  // Against a plane whose origin stays at x = 0 the pin carries the axial force times the slope
  // (the gradient's x component there, the force on the body being its negative).
  const auto unreferenced = make(Hold::pin, false);
  const Vector xu = solve(*unreferenced, {1.0}, ramp);
  const double reaction = make(Hold::none, false)->evaluate(xu, true, false).gradient[3 * centre];
  INFO("the unreferenced plane's pin: " << reaction << " N");
  CHECK(std::abs(reaction - 0.2 * xu[3 * pilot + 1]) < 1e-3 * std::abs(reaction));
  // The tangent's two lowest eigenvalues at the loaded state: one node holding the translation
  // leaves it far softer than the block's softest deformation; the mean does not.
  const auto lowest = [](const EnergyProblem& problem, const Vector& x) {
    const Evaluation e = problem.evaluate(x, false, true);
    LinearSolver solver;
    REQUIRE(solver.factorize(e.hessian) == LinearSolver::Status::positive_definite);
    const LowestModes m = lowest_modes(solver, e.hessian, problem.is_prescribed(), 2, 200, 1e-10);
    REQUIRE(m.converged);
    return m.eigenvalues;
  };
  const std::vector<double> lp = lowest(*pinned, xp), lm = lowest(*held, xm);
  INFO("pinned: " << lp[0] << ", " << lp[1] << " N/mm; held by the mean: " << lm[0] << ", " << lm[1] << " N/mm");
  CHECK(lp[0] < 0.1 * lp[1]);
  CHECK(lm[0] > 0.5 * lp[1]);
}

TEST_CASE("Periodic face form: derivatives match finite differences, and a uniform twist and stretch cost nothing",
          "[solid3d][cell]") {
  const Mesh mesh = box({2, 1, 1}, 2, 1, 1, 1.0, 20);
  std::vector<int> top, bottom;
  for (int n = 0; n < mesh.num_nodes(); ++n) {
    if (mesh.X(n, 2) == 1.0) top.push_back(n);
    if (mesh.X(n, 2) == 0.0) bottom.push_back(n);
  }
  const int n = mesh.num_nodes();
  Vector X(3 * (n + 2));
  X << flattened_positions(mesh), Vector::Zero(6);
  const auto pairs = facing_nodes(top, bottom, X);
  REQUIRE(pairs.size() == top.size());
  EnergyProblem problem(X, DirichletConstraints{});
  problem.add_form(std::make_shared<PeriodicFaceForm>(pairs, X, n, n + 1, 2.3));
  problem.finalize();
  Vector x = test::perturbed(X, 0.1);
  x.tail<6>() << 0.02, -0.03, 0.1, 0.05, -0.2, 0.15;
  const auto err = test::finite_difference_errors(problem, x, 1e-6);
  INFO("gradient error " << err.gradient << ", Hessian error " << err.hessian);
  CHECK(err.gradient < 1e-6);
  CHECK(err.hessian < 1e-6);
  // u = (−θ z y, θ z x, ε z) is periodic with φ = θ·1, a = ε·1 over the unit height: no residual.
  const double theta = 0.07, eps = 0.04;
  Vector twisted = X;
  for (int k = 0; k < n; ++k) {
    const double px = X[3 * k], py = X[3 * k + 1], pz = X[3 * k + 2];
    twisted.segment<3>(3 * k) += Eigen::Vector3d(-theta * pz * py, theta * pz * px, eps * pz);
  }
  twisted.tail<6>() << 0, 0, theta, eps, 0, 0;
  CHECK(problem.evaluate(twisted, true, false).gradient.norm() < 1e-13);
  twisted[3 * n + 2] += 1e-3;  // another twist on the pilot than in the body
  CHECK(problem.evaluate(twisted, true, false).gradient.norm() > 1e-4);
  // A top face that is no copy of the bottom one has no pairs.
  CHECK_THROWS_AS(facing_nodes(top, {bottom.front()}, X), std::invalid_argument);
  // Weighted pairs (a half model's mirror plane): each pair's penalty times its weight. Every weight
  // ½: half the energy and gradient; weights ½ and 1 in turn: derivatives still consistent.
  std::vector<double> halves(pairs.size(), 0.5), mixed(pairs.size(), 1.0);
  for (std::size_t k = 0; k < mixed.size(); k += 2) mixed[k] = 0.5;
  EnergyProblem halved(X, DirichletConstraints{}), weighted(X, DirichletConstraints{});
  halved.add_form(std::make_shared<PeriodicFaceForm>(pairs, X, n, n + 1, 2.3, halves));
  weighted.add_form(std::make_shared<PeriodicFaceForm>(pairs, X, n, n + 1, 2.3, mixed));
  halved.finalize();
  weighted.finalize();
  const Evaluation whole = problem.evaluate(x, true, false), half = halved.evaluate(x, true, false);
  CHECK(half.energy == Approx(0.5 * whole.energy).epsilon(1e-14));
  CHECK((half.gradient - 0.5 * whole.gradient).norm() <= 1e-14 * whole.gradient.norm());
  const auto weighted_err = test::finite_difference_errors(weighted, x, 1e-6);
  CHECK(weighted_err.gradient < 1e-6);
  CHECK(weighted_err.hessian < 1e-6);
  CHECK(weighted.evaluate(x, false, false).energy < whole.energy);
  CHECK_THROWS_AS(PeriodicFaceForm(pairs, X, n, n + 1, 2.3, {1.0}), std::invalid_argument);
}

TEST_CASE("3D patch test: a distorted box reproduces a non-symmetric homogeneous deformation", "[solid3d]") {
  // x = F0 X with shear (F0 non-symmetric) is homogeneous, hence in equilibrium with
  // no body force. With every boundary node prescribed, interior nodes must land on
  // it to round-off: the trilinear geometry makes ∂N/∂X·det(∂X/∂ξ) polynomial, of a
  // degree the 2×2×2 (Hex8) and 3×3×3 (Hex20, Hex27) rules integrate exactly (the
  // serendipity space holds every trilinear function, ξηζ included), and J is
  // constant, so the projected dilatation equals it. Hex20's 2×2×2 rule passes too:
  // ∂N_a/∂ξ_k times a cofactor of ∂X/∂ξ is at most cubic in each direction, which
  // two Gauss points per direction still integrate exactly.
  Eigen::Matrix3d F0;
  F0 << 1.2, 0.3, 0.1, -0.1, 0.9, 0.2, 0.05, 0.15, 1.1;
  for (const auto& kind : kElementKinds) {
    const int nodes = kind.nodes, n = nodes == 8 ? 3 : 2;
    const Mesh mesh = box({2, 3, 4}, n, n, n, 1.0, nodes);
    DirichletConstraints c;
    for (int n : mesh.node_sets.at("boundary")) {
      const Eigen::Vector3d u = (F0 - Eigen::Matrix3d::Identity()) * mesh.X.row(n).transpose();
      for (int i = 0; i < 3; ++i) c.fix(3 * n + i, u[i]);
    }
    EnergyProblem problem(flattened_positions(mesh), c);
    problem.add_form(make_elastic_form(mesh, {test::dragon_skin_30_ogden(1000.0)},
                                       VolumetricTreatment::projected_dilatation, kind.integration));
    problem.finalize();
    const Vector x = solve(problem, {1.0}, PathCallbacks{[](double) {}, {}});
    double max_error = 0.0;
    for (int n = 0; n < mesh.num_nodes(); ++n)
      max_error = std::max(max_error, (x.segment<3>(3 * n) - F0 * mesh.X.row(n).transpose()).cwiseAbs().maxCoeff());
    // Newton stops at its residual tolerance, which leaves nodal errors of ~1e-9 mm
    // (Hex20: 2.5e-9); an element that fails the patch test is off by > 1e-4 mm.
    INFO(kind.name << ": max nodal error " << max_error << " mm");
    CHECK(max_error < 1e-8);
  }
}

TEST_CASE("3D uniaxial tension of nearly incompressible Ogden matches the incompressible closed form", "[solid3d]") {
  // As in test_exact_solutions.cpp: Dragon Skin 30's Ogden fit with K/μ0 = 1e4, closed
  // form P = Σ (2μ_i/α_i)(λ^(α_i−1) − λ^(−α_i/2−1)); the deviation is the
  // compressibility, O(μ/K) = 1e-4, so 2e-3 is safe and still catches a wrong term.
  // Symmetry constraints (rollers on the x = 0, y = 0 and z = 0 faces) on a distorted
  // 1 × 1 × 2 mm bar: the solution is homogeneous, which the patch test covers.
  const std::vector<double> mu{1.1806, 0.8743, -1.9396}, alpha{1.0698, -1.2370, 0.1347};
  const double kappa = 1e4 * (mu[0] + mu[1] + mu[2]), stretch = 1.8;
  for (int nodes : kHexKinds) {
    const Mesh mesh = nodes == 8 ? box({1, 1, 2}, 2, 2, 4, 0.5, 8) : box({1, 1, 2}, 1, 1, 2, 0.5, nodes);
    DirichletConstraints c;
    for (int n : mesh.node_sets.at("x0")) c.fix(3 * n);
    for (int n : mesh.node_sets.at("y0")) c.fix(3 * n + 1);
    for (int n : mesh.node_sets.at("z0")) c.fix(3 * n + 2);
    for (int n : mesh.node_sets.at("z1")) c.fix(3 * n + 2, (stretch - 1.0) * 2.0);
    auto elastic = make_elastic_form(mesh, {test::dragon_skin_30_ogden(kappa)});
    EnergyProblem problem(flattened_positions(mesh), c);
    problem.add_form(elastic);
    problem.finalize();
    int checked = 0;
    PathCallbacks cb;
    cb.apply_load = [](double) {};
    cb.on_converged = [&](double level, const Vector& xs, bool is_output, const NewtonReport&) {
      if (!is_output) return;
      Vector g = Vector::Zero(xs.size());
      REQUIRE(elastic->add(xs, nullptr, &g, nullptr).ok);
      double force = 0.0;  // axial reaction on the z = 2 face = internal force there
      for (int n : mesh.node_sets.at("z1")) force += g[3 * n + 2];
      const double lambda = 1.0 + level * (stretch - 1.0);
      double exact = 0.0;
      for (int i = 0; i < 3; ++i)
        exact += 2 * mu[i] / alpha[i] * (std::pow(lambda, alpha[i] - 1) - std::pow(lambda, -alpha[i] / 2 - 1));
      INFO("Hex" << nodes << ", stretch " << lambda << ": FEM nominal stress " << force
                 << " MPa (1 mm² section), closed form " << exact);
      CHECK(force == Approx(exact).epsilon(2e-3));
      const int corner = mesh.node_sets.at("x1").back();  // on x = 1: lateral stretch λ^(−1/2)
      CHECK(xs[3 * corner] / mesh.X(corner, 0) == Approx(1.0 / std::sqrt(lambda)).epsilon(2e-3));
      ++checked;
    };
    solve(problem, {0.25, 0.5, 0.75, 1.0}, cb);
    CHECK(checked == 4);
  }
}

namespace {

// Positions of the mesh's body (elastic form `elastic`) with chamber 0 at pressure p.
Vector solve_pressurised(const Mesh& mesh, const DirichletConstraints& c, std::shared_ptr<ElasticForm> elastic,
                         double p) {
  LoadState load;
  load.chamber_pressure_MPa = {0.0};
  EnergyProblem problem(flattened_positions(mesh), c);
  problem.add_form(std::move(elastic));
  problem.add_form(std::make_shared<ChamberPressureForm>(mesh, 0, load));
  problem.finalize();
  return solve(problem, {1.0}, PathCallbacks{[&](double level) { load.chamber_pressure_MPa[0] = level * p; }, {}});
}

// Bore radius under pressure p of an incompressible-ish neo-Hookean tube A → B in plane
// strain (all u_z = 0): 3D Hex27 (nr × nc × 1) and axisymmetric Q2 (nr × 1).
double bore_radius_3d(int nr, int nc, double A, double B, double L, const Material& m, double p) {
  Mesh mesh = to_quadratic_3d(hollow_cylinder_mesh(A, B, L, nr, nc, 1));
  test::snap_to_cylinders(mesh, nc);
  const int solid_nodes = mesh.num_nodes();
  const std::vector<int> lid_nodes = test::close_bore(mesh, L);
  DirichletConstraints c;
  for (int n = 0; n < solid_nodes; ++n) {
    c.fix(3 * n + 2);                                        // plane strain
    if (std::abs(mesh.X(n, 1)) < 1e-12) c.fix(3 * n + 1);    // symmetry plane y = 0
    if (std::abs(mesh.X(n, 0)) < 1e-12) c.fix(3 * n);        // symmetry plane x = 0
  }
  for (int n : lid_nodes)
    for (int i = 0; i < 3; ++i) c.fix(3 * n + i);
  const Vector x = solve_pressurised(mesh, c, make_elastic_form(mesh, {m}), p);
  double r = 0.0;  // mean over the bore nodes (they agree to the circumferential discretisation)
  const auto& inner = mesh.node_sets.at("inner");
  for (int n : inner) r += x.segment<2>(3 * n).norm();
  return r / static_cast<double>(inner.size());
}

double bore_radius_axisymmetric(int nr, double A, double B, double L, const Material& m, double p) {
  const Mesh mesh = to_quadratic(rectangle_mesh(A, B, 0.0, L, nr, 1));
  DirichletConstraints c;
  for (int n = 0; n < mesh.num_nodes(); ++n) c.fix(2 * n + 1);
  const Vector x = solve_pressurised(mesh, c, make_elastic_form(mesh, {m}), p);
  return x[2 * mesh.node_sets.at("inner").front()];
}

}  // namespace

TEST_CASE("3D tube under internal pressure agrees with the axisymmetric model", "[solid3d]") {
  // Plane strain, A = 5, B = 10 mm, neo-Hookean μ = 1 MPa, K = 1e3 μ, p = 0.3 MPa (the
  // bore grows by 28 %). Both models use two quadratic elements through the wall, so
  // they differ only by the 3D model's circumferential interpolation (of the circle
  // and of the displacement), whose error falls as (2π/nc)^4 for biquadratic arcs
  // (isoparametric interpolation of order 2, h^(2+2) for the geometry; e.g. Strang &
  // Fix §4.4). So the difference must fall by ~2^4 when nc doubles (we ask for an
  // order above 3) and be small: below 1e-4 of the bore's growth at nc = 32.
  const double A = 5.0, B = 10.0, L = 1.0, p = 0.3;
  const Material m = test::neo_hookean(1.0, 1000.0);
  const double r_axi = bore_radius_axisymmetric(2, A, B, L, m, p);
  std::vector<double> differences;
  for (int nc : {16, 32}) {
    const double r_3d = bore_radius_3d(2, nc, A, B, L, m, p);
    differences.push_back(std::abs(r_3d - r_axi) / (r_axi - A));
    INFO("nc = " << nc << ": bore radius 3D " << r_3d << " mm, axisymmetric " << r_axi
                 << " mm, difference " << differences.back() << " of the growth " << r_axi - A << " mm");
    CHECK(std::isfinite(r_3d));
  }
  const double order = std::log2(differences[0] / differences[1]);
  INFO("differences " << differences[0] << ", " << differences[1] << ": observed order " << order);
  CHECK(order > 3.0);
  CHECK(differences[1] < 1e-4);
}

TEST_CASE("Hex20 and Quad8 shape functions: Kronecker property, partition of unity, exact gradients", "[solid3d]") {
  // The serendipity functions are 1 at their own node and 0 at the 19 others, sum
  // to 1 with gradients summing to 0 anywhere, and their gradients match central
  // differences (quadratic per direction: the difference is exact to round-off).
  Eigen::Matrix<double, 20, 3> dN;
  double N[20];
  for (int a = 0; a < 20; ++a) {
    const Eigen::Vector3d node(hex::Hex27::kReference[a][0], hex::Hex27::kReference[a][1], hex::Hex27::kReference[a][2]);
    hex::Hex20::shape(node, N, dN);
    for (int b = 0; b < 20; ++b) CHECK(N[b] == Approx(a == b ? 1.0 : 0.0).margin(1e-15));
  }
  const Eigen::Vector3d xi(0.31, -0.72, 0.55);
  hex::Hex20::shape(xi, N, dN);
  double sum = 0;
  for (double v : N) sum += v;
  CHECK(sum == Approx(1.0).epsilon(1e-14));
  CHECK(dN.colwise().sum().norm() < 1e-14);
  const double h = 1e-5;
  for (int d = 0; d < 3; ++d) {
    Eigen::Vector3d up = xi, down = xi;
    up[d] += h, down[d] -= h;
    double Nu[20], Nd[20];
    Eigen::Matrix<double, 20, 3> unused;
    hex::Hex20::shape(up, Nu, unused);
    hex::Hex20::shape(down, Nd, unused);
    for (int a = 0; a < 20; ++a) CHECK((Nu[a] - Nd[a]) / (2 * h) == Approx(dN(a, d)).margin(1e-9));
  }
  // The face: Quad8 is the trace of Hex20 on ζ = −1 (nodes 0–3, 8–11).
  double M[8], Ms[8], Mt[8];
  Quad8::shape(0.31, -0.72, M, Ms, Mt);
  hex::Hex20::shape(Eigen::Vector3d(0.31, -0.72, -1.0), N, dN);
  constexpr int kBottom[8] = {0, 1, 2, 3, 8, 9, 10, 11};
  for (int a = 0; a < 8; ++a) {
    CHECK(M[a] == Approx(N[kBottom[a]]).margin(1e-15));
    CHECK(Ms[a] == Approx(dN(kBottom[a], 0)).margin(1e-14));
    CHECK(Mt[a] == Approx(dN(kBottom[a], 1)).margin(1e-14));
  }
}

TEST_CASE("The hexahedra's BᵀDB kernel: its AVX and SSE2 instances round alike, and both are the dense product", "[solid3d]") {
  // The tangent's hot loop runs four doubles wide where the processor has AVX and two wide
  // otherwise; a design must not change with the processor, so the two instances must agree to
  // the bit, not to a tolerance (in the upper triangle: the lower one is scratch). Random gradients
  // and a random symmetric D at Hex8's, Hex20's and Hex27's sizes (four rows at a pass for the first
  // two, row by row for the third).
  const auto check = [](auto element) {
    using E = decltype(element);
    constexpr int m = 3 * E::kNodes;
    srand(7);
    hex::ReferencePoint<E> p;
    p.dN_dX.setRandom();
    Eigen::Matrix<double, 9, 9> D = Eigen::Matrix<double, 9, 9>::Random();
    D = (D + D.transpose()).eval();
    using Upper = Eigen::Matrix<double, m, m, Eigen::RowMajor>;
    Upper sse2 = Upper::Random(), avx = sse2;  // accumulates: start from the same non-zero matrix
    const Upper start = sse2;
    hex::detail::add_BtDB_upper_sse2<E::kNodes>(p.dN_dX.data(), D.data(), sse2.data());
#ifdef SOFTARM_KERNEL_AVX
    if (hex::detail::processor_has_avx()) {
      hex::detail::add_BtDB_upper_avx<E::kNodes>(p.dN_dX.data(), D.data(), avx.data());
      int differ = 0;  // bits, in the upper triangle (the lower one is the kernel's scratch)
      for (int r = 0; r < m; ++r) differ += std::memcmp(&avx(r, r), &sse2(r, r), sizeof(double) * (m - r)) != 0;
      CHECK(differ == 0);
    } else {
      WARN("this processor has no AVX: only the SSE2 instance is checked");
    }
#else
    WARN("not an x86 processor: the kernel has one instance");
#endif
    const auto B = hex::gradient_operator<E>(p);
    const Eigen::Matrix<double, m, m> dense = B.transpose() * D * B;
    for (int r = 0; r < m; ++r)
      for (int c = 0; c < m; ++c) {
        if (c < r) continue;  // scratch: the form reads the upper triangle
        REQUIRE(sse2(r, c) - start(r, c) == Approx(dense(r, c)).margin(1e-12 * dense.cwiseAbs().maxCoeff()));
      }
  };
  check(hex::Hex8{});
  check(hex::Hex20{});
  check(hex::Hex27{});
}

TEST_CASE("Hex20 at 2x2x2 Gauss points: a lone element's spurious modes do not survive in a mesh", "[solid3d]") {
  // Zero-energy modes of the tangent at rest, unconstrained: a sound element has
  // only the six rigid-body modes. The 2×2×2 rule leaves a lone 20-node element
  // with spurious ones too (Bathe, Finite Element Procedures, §5.5.6): here the
  // rank is 8 points × 5 deviatoric strains + 4 dilatation modes = 44 of 60, so
  // 16 zero modes, 10 spurious. A row of elements one wide in two directions still
  // keeps 6; two or more elements across in two directions share none, so such a
  // mesh has only the rigid modes (why C3D20R needs no hourglass control; the
  // actuator meshes are several elements across everywhere, and their clamped
  // tangents factorise by Cholesky at rest). Counted as eigenvalues below 1e-9 of
  // the largest.
  const auto zero_modes = [](const Mesh& mesh, ElementIntegration integration) {
    EnergyProblem problem(flattened_positions(mesh), DirichletConstraints{});
    problem.add_form(make_elastic_form(mesh, {test::neo_hookean(1.0, 1000.0)},
                                       VolumetricTreatment::projected_dilatation, integration));
    problem.finalize();
    const Eigen::MatrixXd K(problem.evaluate(problem.reference_positions(), false, true).hessian);
    const Eigen::VectorXd lambda = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(K, Eigen::EigenvaluesOnly).eigenvalues();
    int zero = 0;
    for (double l : lambda) zero += std::abs(l) < 1e-9 * lambda.cwiseAbs().maxCoeff();
    return zero;
  };
  struct Case {
    int n, m, k, reduced_zero_modes;
  };
  for (const auto& c : std::vector<Case>{{1, 1, 1, 16}, {2, 1, 1, 12}, {2, 2, 1, 6}, {2, 2, 2, 6}, {3, 3, 1, 6}}) {
    const Mesh mesh = box({1.0 * c.n, 1.0 * c.m, 1.0 * c.k}, c.n, c.m, c.k, 1.0, 20);
    const int full = zero_modes(mesh, ElementIntegration::full), reduced = zero_modes(mesh, ElementIntegration::reduced);
    INFO(c.n << "x" << c.m << "x" << c.k << " Hex20: " << full << " zero modes at 3x3x3, " << reduced << " at 2x2x2");
    CHECK(full == 6);
    CHECK(reduced == c.reduced_zero_modes);
  }
}

// The solver layer: the direct solver's indefinite fallbacks (LU, shifted
// Cholesky), and the load
// stepper's exact landing, cut-back after a typed failure, and honest report
// of a path it cannot finish.
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <span>
#include <stdexcept>
#include <vector>

#include "fem/core/parallel.hpp"
#include "fem/forms/make_elastic_form.hpp"
#include "fem/mesh/structured_mesh.hpp"
#include "fem/solver/load_stepper.hpp"
#include "fem/solver/lowest_modes.hpp"
#include "fem/solver/permuted_triangle.hpp"
#include "fem/solver/preconditioned_cg.hpp"
#include "fem/solver/remaining_error.hpp"
#include "fem/solver/symbolic_analysis_cache.hpp"
#include "fem/solver/unstable_branch_count.hpp"
#include "support/test_problems.hpp"

using namespace softarm;
using namespace softarm::fem;

TEST_CASE("linear solver: Cholesky for SPD, LU fallback for an indefinite matrix", "[solver]") {
  // 1D Laplacian (SPD) and the same with a negative diagonal entry (indefinite, nonsingular).
  const int n = 50;
  auto make = [&](double first_diagonal) {
    std::vector<Eigen::Triplet<double>> t;
    for (int i = 0; i < n; ++i) {
      t.emplace_back(i, i, i == 0 ? first_diagonal : 2.0);
      if (i + 1 < n) t.emplace_back(i, i + 1, -1.0), t.emplace_back(i + 1, i, -1.0);
    }
    SparseMatrix K(n, n);
    K.setFromTriplets(t.begin(), t.end());
    return K;
  };
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, 1.0, 2.0);
  LinearSolver solver;
  for (double d : {2.0, -3.0, 2.0}) {  // back to SPD after an indefinite matrix on the same pattern
    const SparseMatrix K = make(d);
    const auto status = solver.factorize(K);
    CHECK(status == (d > 0 ? LinearSolver::Status::positive_definite : LinearSolver::Status::indefinite));
    const Eigen::VectorXd x = solver.solve(b);
    CHECK((K * x - b).norm() < 1e-10 * b.norm());
  }
}

TEST_CASE("linear solver: an indefinite matrix shifted to K + sigma I, the smallest of the ladder that is SPD", "[solver]") {
  // The 1D Laplacian with its first diagonal entry made −3: its lowest eigenvalue
  // is about −3.2, so K + σI is positive definite once σ ≳ 3.2. With the mean
  // |diagonal| d̄ = 2.02 the ladder σ = 10^k d̄ (k = −6 … 2) first works at k = 1.
  const int n = 50;
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, i == 0 ? -3.0 : 2.0);
    if (i + 1 < n) t.emplace_back(i, i + 1, -1.0), t.emplace_back(i + 1, i, -1.0);
  }
  SparseMatrix K(n, n);
  K.setFromTriplets(t.begin(), t.end());
  const double mean_diagonal = K.diagonal().cwiseAbs().mean();
  const double lowest = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Eigen::MatrixXd(K)).eigenvalues()[0];
  REQUIRE(lowest < 0);
  LinearSolver solver;
  CHECK(solver.factorize_shifted(K) == LinearSolver::Status::indefinite);
  CHECK(solver.last_shift == Approx(10 * mean_diagonal));
  CHECK(solver.last_shift > -lowest);
  CHECK(solver.last_shift / 10 < -lowest);  // the step below was not positive definite
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, 1.0, 2.0);
  SparseMatrix shifted = K;
  for (int i = 0; i < n; ++i) shifted.coeffRef(i, i) += solver.last_shift;
  const Eigen::VectorXd x = solver.solve(b);
  CHECK((shifted * x - b).norm() < 1e-10 * b.norm());
  CHECK(b.dot(x) > 0);  // −x is a descent direction for a gradient b
  // An SPD matrix on the same solver is factorised as it is, with no shift left over.
  for (int i = 0; i < n; ++i) shifted.coeffRef(i, i) = 2.0;
  CHECK(solver.factorize_shifted(shifted) == LinearSolver::Status::positive_definite);
  CHECK(solver.last_shift == 0.0);
  CHECK((shifted * solver.solve(b) - b).norm() < 1e-10 * b.norm());
}

namespace {
// A solid cylinder compressed axially to 40 % of its height: one step would invert elements.
struct Compression {
  static Mesh grid() { return rectangle_mesh(0.0, 1.0, 0.0, 1.0, 4, 4, 0.0); }
  Mesh mesh = grid();
  std::unique_ptr<EnergyProblem> problem;
  explicit Compression(double final_height, std::shared_ptr<Form> extra = nullptr, double bulk_modulus = 50.0) {
    DirichletConstraints c;
    for (int n : mesh.node_sets.at("axis")) c.fix(2 * n);
    for (int n : mesh.node_sets.at("bottom")) c.fix(2 * n + 1);
    for (int n : mesh.node_sets.at("top")) c.fix(2 * n + 1, final_height - 1.0);
    problem = std::make_unique<EnergyProblem>(flattened_positions(mesh), c);
    problem->add_form(make_elastic_form(mesh, {test::neo_hookean(1.0, bulk_modulus)}));
    if (extra) problem->add_form(extra);
    problem->finalize();
  }
};

PathCallbacks no_callbacks() {
  return {[](double) {}, [](double, const Vector&, bool, const NewtonReport&) {}};
}

/// A round-off floor: a gradient term of fixed size whose direction is a hash of x's bits, so
/// that no Newton step removes it (as the rounding of large cancelling ABS forces), with no
/// energy and no Hessian.
class RoundoffFloor : public Form {
 public:
  double amplitude = 0;  // per dof
  std::string name() const override { return "round-off floor"; }
  void declare_pattern(SparsePattern&) override {}
  FormStatus add(const Vector& x, double*, Vector* gradient, HessianAccumulator*) const override {
    if (!gradient) return FormStatus::fine();
    std::uint64_t h = 1469598103934665603ull;  // FNV-1a over the bits of x, then an LCG
    for (int i = 0; i < x.size(); ++i) {
      std::uint64_t bits;
      std::memcpy(&bits, &x[i], sizeof bits);
      h = (h ^ bits) * 1099511628211ull;
    }
    for (int i = 0; i < x.size(); ++i) {
      h = h * 6364136223846793005ull + 1442695040888963407ull;
      (*gradient)[i] += amplitude * (static_cast<double>(h >> 11) / 9007199254740992.0 * 2 - 1);
    }
    return FormStatus::fine();
  }
};

/// One dof d on a double-well spring, energy k (s⁴/(4 s_w²) − s²/2) with s = x_d − x₀: a maximum at
/// s = 0, where its curvature is −k, and minima at s = ±s_w. Stiffer than what holds d elastically,
/// it makes the tangent indefinite while |s| < s_w/√3.
class DoubleWellSpring : public Form {
 public:
  DoubleWellSpring(int dof, double x0, double stiffness, double s_w) : dof_(dof), x0_(x0), k_(stiffness), s_w_(s_w) {}
  std::string name() const override { return "double-well spring"; }
  void declare_pattern(SparsePattern& pattern) override { block_ = pattern.declare_block(std::span<const int>(&dof_, 1)); }
  FormStatus add(const Vector& x, double* value, Vector* gradient, HessianAccumulator* hessian) const override {
    const double s = x[dof_] - x0_, q = s * s / (s_w_ * s_w_);
    if (value) *value += k_ * s * s * (q / 4 - 0.5);
    if (gradient) (*gradient)[dof_] += k_ * s * (q - 1);
    if (hessian) {
      const double h = k_ * (3 * q - 1);
      hessian->add_block(0, block_, &h);
    }
    return FormStatus::fine();
  }

 private:
  int dof_, block_ = -1;
  double x0_, k_, s_w_;
};
}  // namespace

TEST_CASE("Newton stops at a round-off floor instead of iterating on it", "[solver]") {
  // A start next to equilibrium (residual 1e-5 of the force scale) on a problem whose residual
  // cannot fall below ~3e-8 of it: the energy norm, relative to a first value that was already
  // tiny, never reaches 1e-12, so Newton used to spend all its iterations (the SPL pose: 20
  // iterations at 3e-8, twice). Now it stops once the residual no longer falls.
  auto floor = std::make_shared<RoundoffFloor>();
  Compression c(0.7, floor);
  Vector x = c.problem->reference_positions();
  LinearSolver solver;
  const PathCallbacks none = no_callbacks();
  REQUIRE(follow_load_path(*c.problem, x, solver, {1.0}, none, NewtonSettings{}, StepSettings{}).completed);  // no floor yet
  const Evaluation e = c.problem->evaluate(x, true, false);
  const double scale = e.force_scale();
  const int free_dofs = c.problem->num_dofs() - static_cast<int>(std::count(c.problem->is_prescribed().begin(),
                                                                             c.problem->is_prescribed().end(), 1));
  floor->amplitude = 3e-8 * scale / std::sqrt(static_cast<double>(free_dofs));
  Vector nudge = Vector::LinSpaced(x.size(), -1.0, 1.0);
  c.problem->zero_prescribed(nudge);
  const double stiffness = 1.0;  // the shear modulus: a nudge of 1e-5 moves the residual by ~1e-5 of the scale
  x += 1e-5 * scale / stiffness / nudge.norm() * nudge;
  const NewtonReport report = solve_newton(*c.problem, x, solver, NewtonSettings{});
  CAPTURE(report.iterations, report.message);
  REQUIRE(report.converged);
  CHECK(report.iterations <= 5);
  const double residual = c.problem->evaluate(x, true, false).gradient.norm() / scale;
  CHECK(residual > NewtonSettings{}.residual_tolerance);  // it did sit above the tolerance
  CHECK(residual < 100 * NewtonSettings{}.residual_tolerance);
}

namespace {
/// A linear spring of stiffness k from dof d to a fixed anchor: energy k (x_d − anchor)² / 2.
class AnchorSpring : public Form {
 public:
  AnchorSpring(int dof, double anchor, double stiffness) : dof_(dof), anchor_(anchor), k_(stiffness) {}
  std::string name() const override { return "anchor spring"; }
  void declare_pattern(SparsePattern& pattern) override { block_ = pattern.declare_block(std::span<const int>(&dof_, 1)); }
  FormStatus add(const Vector& x, double* value, Vector* gradient, HessianAccumulator* hessian) const override {
    const double s = x[dof_] - anchor_;
    if (value) *value += 0.5 * k_ * s * s;
    if (gradient) (*gradient)[dof_] += k_ * s;
    if (hessian) hessian->add_block(0, block_, &k_);
    return FormStatus::fine();
  }

 private:
  int dof_, block_ = -1;
  double anchor_, k_;
};
}  // namespace

TEST_CASE("Newton accepts a residual that only the rounding of the positions keeps above its tolerance, at the first settled iterate", "[solver]") {
  // A spring stiff enough (k = 1e9 of the body's force scale) that one ulp of its dof's position moves
  // the residual by ~1e-7 of that scale: no position rounds to equilibrium, the residual stops near
  // 1e-7 (the ABS rings next to silicone, whose floor is near 1e-8). residual_beyond_roundoff takes
  // 10 ε |K||x| off each entry: nothing is left, and Newton stops at the first iterate whose update
  // has settled, not one iteration later where the residual shows that it stopped falling.
  const Mesh grid = Compression::grid();
  int node = 0;
  (grid.X.rowwise() - Eigen::RowVector2d(0.5, 0.5)).rowwise().norm().minCoeff(&node);
  const double scale = [] {
    Compression plain(0.7);
    Vector x = plain.problem->reference_positions();
    LinearSolver s;
    REQUIRE(follow_load_path(*plain.problem, x, s, {1.0}, no_callbacks(), NewtonSettings{}, StepSettings{}).completed);
    return plain.problem->evaluate(x, true, false).force_scale();
  }();
  const double k = 1e9 * scale;
  Compression c(0.7, std::make_shared<AnchorSpring>(2 * node, 0.5 + 1.0 / 3.0, k));
  Vector x = c.problem->reference_positions();
  LinearSolver solver;
  const NewtonSettings settings;
  REQUIRE(follow_load_path(*c.problem, x, solver, {1.0}, no_callbacks(), settings, StepSettings{}).completed);
  // From there, the body's other dofs nudged by 3e-4 (the spring's dof left where it is, so that the
  // first residual is the body's): Newton again.
  Vector nudge = Vector::LinSpaced(x.size(), -1.0, 1.0);
  c.problem->zero_prescribed(nudge);
  nudge[2 * node] = 0;
  x += 3e-4 / nudge.norm() * nudge;
  const NewtonReport report = solve_newton(*c.problem, x, solver, settings);
  CAPTURE(report.iterations, report.message);
  REQUIRE(report.converged);
  const Evaluation e = c.problem->evaluate(x, true, true);
  const double reference = std::max(e.force_scale(), scale);
  INFO("residual " << e.gradient.norm() / reference << ", beyond the floor "
                   << residual_beyond_roundoff(e.hessian, x, e.gradient) / reference);
  CHECK(e.gradient.norm() > settings.residual_tolerance * reference);  // above the tolerance: the floor
  CHECK(residual_beyond_roundoff(e.hessian, x, e.gradient) <= settings.residual_tolerance * reference);
  // Stopped where the residual was still falling (by more than half from the iterate before): no
  // iteration spent on showing the floor.
  REQUIRE(report.rows.size() >= 2);
  CHECK(report.rows.back().residual < 0.5 * report.rows[report.rows.size() - 2].residual);
  // And the state is converged: one more Newton step moves it by less than the update tolerance.
  REQUIRE(solver.factorize(e.hessian) == LinearSolver::Status::positive_definite);
  Vector dx = -solver.solve(e.gradient);
  c.problem->zero_prescribed(dx);
  CHECK(dx.norm() / (x - c.problem->reference_positions()).norm() < settings.update_tolerance);
}

namespace {
// The cylinder compressed to 70 % in one Newton solve, from the affine squash (no bulge), with a
// double-well spring on the axial dof of the node at (r, z) = (0.5, 0.5), whose maximum is the
// mid-plane, z = 0.35 after the squash; the spring's dof starts s0 above it. At s0 = 0 the start and
// the residual are symmetric about the mid-plane and Newton's steps leave the dof there, on the maximum.
NewtonReport compress_with_double_well(double k, double s_w, double s0, double& s_end) {
  const Mesh grid = Compression::grid();
  int node = 0;
  (grid.X.rowwise() - Eigen::RowVector2d(0.5, 0.5)).rowwise().norm().minCoeff(&node);
  const int dof = 2 * node + 1;
  Compression c(0.7, std::make_shared<DoubleWellSpring>(dof, 0.35, k, s_w));
  Vector x = c.problem->reference_positions();
  for (int n = 0; n < grid.num_nodes(); ++n) x[2 * n + 1] *= 0.7;
  c.problem->apply_constraints(x, 1.0);
  x[dof] += s0;
  LinearSolver solver;
  NewtonSettings newton;
  newton.shift_indefinite_tangent = true;
  newton.max_indefinite_iterations = 4;
  const NewtonReport report = solve_newton(*c.problem, x, solver, newton);
  s_end = x[dof] - 0.35;
  return report;
}

int longest_indefinite_run(const NewtonReport& r) {
  int longest = 0, run = 0;
  for (const NewtonRow& row : r.rows) longest = std::max(longest, run = row.positive_definite ? 0 : run + 1);
  return longest;
}
}  // namespace

TEST_CASE("Newton goes on through indefinite tangents while it halves the residual but not onto a maximum",
          "[solver]") {
  // The unstable-branch guard (max_indefinite_iterations = 4) counts only indefinite iterations
  // that fail to halve the best residual so far. Started on the spring's concave side
  // (s0 = 0.3 s_w), six iterations in a row meet an indefinite tangent while the compression's
  // residual halves; the old count, every indefinite iteration, gave up after five. Newton now
  // reaches the well.
  const double s_w = 1e-2;
  double s_end = 0;
  const NewtonReport well = compress_with_double_well(30, s_w, 0.3 * s_w, s_end);
  CAPTURE(well.message, s_end / s_w);
  REQUIRE(well.converged);
  CHECK(longest_indefinite_run(well) > 5);
  CHECK(well.tangent_positive_definite);
  CHECK(s_end > s_w / std::sqrt(3.0));  // past the spring's inflection: a stable minimum
  // Started on the maximum (s0 = 0, a symmetric start), a spring a little stiffer than what holds
  // its dof elastically: the shifted steps leave the symmetric negative mode alone and converge,
  // halving the residual, onto the maximum. That is an unstable equilibrium, reported as such.
  const NewtonReport top = compress_with_double_well(20, s_w, 0.0, s_end);
  CAPTURE(top.message, s_end / s_w);
  CHECK_FALSE(top.converged);
  CHECK(top.failure == Failure::unstable_branch);
  CHECK(longest_indefinite_run(top) > 5);
  CHECK(std::abs(s_end) < 1e-9 * s_w);
}

TEST_CASE("the unstable-branch count: only an iteration that halves the best residual clears it", "[solver]") {
  // The thesis 3CA's free end past its limit point: indefinite iterations stalled, one positive
  // definite iteration that threw the residual up, more indefinite ones. The guard (4) must give up
  // at the fifth indefinite iteration without progress, the positive definite one notwithstanding.
  int count = indefinite_without_progress_after(0, false, true, false);  // the first iteration, indefinite
  CHECK(count == 1);
  count = indefinite_without_progress_after(count, false, false, true);  // indefinite, halved the best
  CHECK(count == 1);
  for (int k = 0; k < 3; ++k) count = indefinite_without_progress_after(count, false, false, false);
  CHECK(count == 4);
  count = indefinite_without_progress_after(count, true, false, false);  // positive definite, no progress
  CHECK(count == 4);
  count = indefinite_without_progress_after(count, false, false, false);
  CHECK(count == 5);  // > 4: unstable_branch
  CHECK(indefinite_without_progress_after(5, true, false, true) == 0);  // positive definite and halved: cleared
  CHECK(indefinite_without_progress_after(3, true, true, false) == 0);  // a positive definite first iteration
}

TEST_CASE("load stepper lands exactly on the requested levels", "[solver]") {
  Compression c(0.7);
  Vector x = c.problem->reference_positions();
  LinearSolver solver;
  std::vector<double> landed;
  PathCallbacks cb{[](double) {}, [&](double level, const Vector&, bool is_output, const NewtonReport&) {
                     if (is_output) landed.push_back(level);
                   }};
  const std::vector<double> requested{0.1, 0.37, 0.5, 0.8123, 1.0};
  const auto r = follow_load_path(*c.problem, x, solver, requested, cb, NewtonSettings{}, StepSettings{});
  REQUIRE(r.completed);
  REQUIRE(landed.size() == requested.size());
  for (std::size_t k = 0; k < requested.size(); ++k) CHECK(landed[k] == requested[k]);  // bit-exact
}

TEST_CASE("the step controller leaves no sliver step before an output level", "[solver]") {
  // Increment 0.1 from level 0.2: an output within 1.3 increments is landed on, one within two is
  // approached half way (the plain rule took 0.1 and then a 0.02 sliver), a farther one gets a full step.
  CHECK(next_step_level(0.2, 0.1, 0.3) == 0.3);
  CHECK(next_step_level(0.2, 0.1, 0.33) == 0.33);
  CHECK(next_step_level(0.2, 0.1, 0.38) == Approx(0.29));
  CHECK(next_step_level(0.2, 0.1, 0.4) == Approx(0.3));
  CHECK(next_step_level(0.2, 0.1, 0.9) == Approx(0.3));
  CHECK(next_step_level(0.2, 0.1, 0.25) == 0.25);
}

TEST_CASE("the predictor's parabola reproduces a quadratic path and the secant a linear one", "[solver]") {
  // x(λ) = a + bλ + cλ² at three unequal levels, extrapolated to a fourth: exact for the parabola;
  // the secant through the last two is exact only for c = 0 and off by c(λ − λ1)(λ − λ2) otherwise.
  const Vector a = Vector::LinSpaced(5, 1.0, 2.0), b = Vector::LinSpaced(5, -3.0, 4.0), c = Vector::LinSpaced(5, 0.5, 9.0);
  const auto path = [&](double l) -> Vector { return a + l * b + l * l * c; };
  const Vector x0 = path(0.2), x1 = path(0.35), x2 = path(0.4);
  const Vector parabola = extrapolate_state({0.2, 0.35, 0.4}, {&x0, &x1, &x2}, 0.55);
  CHECK((parabola - path(0.55)).norm() < 1e-12 * path(0.55).norm());
  const Vector secant = extrapolate_state({0.35, 0.4}, {&x1, &x2}, 0.55);
  CHECK((secant - path(0.55) + (0.55 - 0.35) * (0.55 - 0.4) * c).norm() < 1e-12 * path(0.55).norm());
}

TEST_CASE("the predictor's cubic with the path's slope reproduces a cubic path, and beats the parabola on a smooth one", "[solver]") {
  // x(λ) = a + bλ + cλ² + dλ³ at three unequal levels with its slope at the last: exact for the cubic.
  const Vector a = Vector::LinSpaced(5, 1.0, 2.0), b = Vector::LinSpaced(5, -3.0, 4.0), c = Vector::LinSpaced(5, 0.5, 9.0),
               d = Vector::LinSpaced(5, -7.0, 2.5);
  const auto path = [&](double l) -> Vector { return a + l * b + l * l * c + l * l * l * d; };
  const auto slope = [&](double l) -> Vector { return b + 2 * l * c + 3 * l * l * d; };
  const Vector x0 = path(0.2), x1 = path(0.35), x2 = path(0.4);
  const Vector cubic = extrapolate_with_slope({0.2, 0.35, 0.4}, {&x0, &x1, &x2}, slope(0.4), 0.55);
  CHECK((cubic - path(0.55)).norm() < 1e-12 * path(0.55).norm());
  // On x(λ) = exp(kλ) (componentwise k), a smooth path no polynomial matches, with steps h: the
  // parabola's error falls as h³, the cubic's as h⁴, and the cubic is the closer at every h here.
  const Vector k = Vector::LinSpaced(5, 0.5, 3.0);
  const auto smooth = [&](double l) -> Vector { return (k * l).array().exp().matrix(); };
  const auto smooth_slope = [&](double l) -> Vector { return k.cwiseProduct(smooth(l)); };
  double last_parabola = 0, last_cubic = 0;
  for (const double h : {0.1, 0.05}) {
    const Vector y0 = smooth(0.5 - 2 * h), y1 = smooth(0.5 - h), y2 = smooth(0.5), exact = smooth(0.5 + h);
    const double parabola_error = (extrapolate_state({0.5 - 2 * h, 0.5 - h, 0.5}, {&y0, &y1, &y2}, 0.5 + h) - exact).norm();
    const double cubic_error = (extrapolate_with_slope({0.5 - 2 * h, 0.5 - h, 0.5}, {&y0, &y1, &y2}, smooth_slope(0.5), 0.5 + h) - exact).norm();
    INFO("h = " << h << ": parabola " << parabola_error << ", cubic " << cubic_error);
    CHECK(cubic_error < 0.5 * parabola_error);
    if (last_parabola > 0) {
      CHECK(last_parabola / parabola_error == Approx(8).epsilon(0.15));  // h³
      CHECK(last_cubic / cubic_error == Approx(16).epsilon(0.15));       // h⁴
    }
    last_parabola = parabola_error, last_cubic = cubic_error;
  }
}

TEST_CASE("the predictor takes the cubic only where it agrees with the parabola", "[solver]") {
  // The same cubic path: the cubic and the parabola's predictions differ by d(λ−l0)(λ−l1)(λ−l2)-ish
  // terms, small against the step from x2 for a small d. A slope far from the path's (as where K is
  // nearly singular, next to a limit point) makes the cubic disagree by more than 10 % of the
  // parabola's step: the parabola is returned, bit for bit.
  const Vector a = Vector::LinSpaced(5, 1.0, 2.0), b = Vector::LinSpaced(5, -3.0, 4.0), c = Vector::LinSpaced(5, 0.5, 9.0),
               d = Vector::Constant(5, 0.01);
  const auto path = [&](double l) -> Vector { return a + l * b + l * l * c + l * l * l * d; };
  const Vector x0 = path(0.2), x1 = path(0.35), x2 = path(0.4);
  const Vector true_slope = b + 0.8 * c + 0.48 * d;
  const Vector parabola = extrapolate_state({0.2, 0.35, 0.4}, {&x0, &x1, &x2}, 0.55);
  const Vector taken = predict_with_slope({0.2, 0.35, 0.4}, {&x0, &x1, &x2}, true_slope, 0.55);
  CHECK((taken - path(0.55)).norm() < 1e-12 * path(0.55).norm());  // the cubic, exact
  CHECK((taken - parabola).norm() > 0);
  const Vector refused = predict_with_slope({0.2, 0.35, 0.4}, {&x0, &x1, &x2}, 50 * true_slope, 0.55);
  CHECK(refused == parabola);
  Vector not_finite = true_slope;
  not_finite[2] = std::nan("");
  CHECK(predict_with_slope({0.2, 0.35, 0.4}, {&x0, &x1, &x2}, not_finite, 0.55) == parabola);
}

TEST_CASE("the second step's parabola with the path's slope reproduces a parabolic path, and is refused where it disagrees with the secant", "[solver]") {
  // x(λ) = a + bλ + cλ² at two levels with its slope at the second: exact; the secant is off by
  // c(λ − l0)(λ − l1). A slope far from the path's (next to a limit point) puts the parabola more
  // than kSecondStepAgreement of the secant's step away: the secant is returned, bit for bit, and so
  // where the slope is not finite.
  const Vector a = Vector::LinSpaced(5, 1.0, 2.0), b = Vector::LinSpaced(5, -3.0, 4.0), c = Vector::LinSpaced(5, 0.5, 9.0);
  const auto path = [&](double l) -> Vector { return a + l * b + l * l * c; };
  const Vector true_slope = b + 2 * 0.35 * c;
  const Vector x0 = path(0.2), x1 = path(0.35), exact = path(0.5);
  CHECK((extrapolate_second_step({0.2, 0.35}, {&x0, &x1}, true_slope, 0.5) - exact).norm() < 1e-12 * exact.norm());
  const Vector secant = extrapolate_state({0.2, 0.35}, {&x0, &x1}, 0.5);
  CHECK((secant - exact + (0.5 - 0.2) * (0.5 - 0.35) * c).norm() < 1e-12 * exact.norm());
  const Vector taken = predict_second_step({0.2, 0.35}, {&x0, &x1}, true_slope, 0.5);
  CHECK((taken - exact).norm() < 1e-12 * exact.norm());
  CHECK(predict_second_step({0.2, 0.35}, {&x0, &x1}, 20 * true_slope, 0.5) == secant);
  Vector not_finite = true_slope;
  not_finite[1] = std::nan("");
  CHECK(predict_second_step({0.2, 0.35}, {&x0, &x1}, not_finite, 0.5) == secant);
}

TEST_CASE("load stepper cuts back after a failure and still reaches the end", "[solver]") {
  Compression c(0.4);
  Vector x = c.problem->reference_positions();
  LinearSolver solver;
  StepSettings steps;
  steps.initial_increment = 1.0;  // the whole compression at once: Newton cannot converge
  steps.max_increment = 1.0;
  PathCallbacks cb{[](double) {}, {}};
  const auto r = follow_load_path(*c.problem, x, solver, {1.0}, cb, NewtonSettings{}, steps);
  INFO(r.message);
  CHECK(r.completed);
  CHECK(r.stats.cutbacks >= 1);
  const int top = c.mesh.node_sets.at("top").front();
  CHECK(x[2 * top + 1] == Approx(0.4));
}

TEST_CASE("a path that cannot be finished returns what it reached and why", "[solver]") {
  Compression c(-0.5);  // the top pushed through the bottom: no admissible state exists past height 0
  Vector x = c.problem->reference_positions();
  LinearSolver solver;
  PathCallbacks cb{[](double) {}, {}};
  StepSettings steps;
  steps.min_increment = 1e-3;
  const auto r = follow_load_path(*c.problem, x, solver, {1.0}, cb, NewtonSettings{}, steps);
  CHECK_FALSE(r.completed);
  CHECK(r.failure != Failure::none);
  CHECK(r.reached_level > 0.3);
  CHECK(r.reached_level < 2.0 / 3.0);  // height 0 is reached at level 2/3
  CHECK(x.allFinite());
}

TEST_CASE("a singular matrix is reported and its solve is NaN instead of a crash", "[solver]") {
  // Rank 1: neither Cholesky nor LU can factorise it.
  softarm::fem::SparseMatrix k(2, 2);
  k.insert(0, 0) = 1.0;
  k.insert(0, 1) = 1.0;
  k.insert(1, 0) = 1.0;
  k.insert(1, 1) = 1.0;
  k.makeCompressed();
  softarm::fem::LinearSolver solver;
  CHECK(solver.factorize(k) == softarm::fem::LinearSolver::Status::singular);
  const Eigen::VectorXd x = solver.solve(Eigen::VectorXd::Ones(2));
  CHECK(x.size() == 2);
  CHECK(std::isnan(x[0]));
}

TEST_CASE("subspace iteration finds the lowest eigenpairs of the free dofs, as a dense solver does", "[solver]") {
  // A spring chain with varying stiffness (a soft spot in the middle: a localised lowest mode),
  // dofs 0 and 40 prescribed with identity rows, as the assembly leaves them.
  const int n = 41;
  std::vector<Eigen::Triplet<double>> t;
  std::vector<char> prescribed(n, 0);
  prescribed[0] = prescribed[n - 1] = 1;
  for (int i = 0; i + 1 < n; ++i) {
    const double k = (i == 20 || i == 21) ? 0.05 : 10.0 + i;  // node 21 hangs between two soft springs
    for (auto [a, b, v] : {std::tuple{i, i, k}, {i + 1, i + 1, k}, {i, i + 1, -k}, {i + 1, i, -k}})
      if (!prescribed[a] && !prescribed[b]) t.emplace_back(a, b, v);
  }
  t.emplace_back(0, 0, 1.0);
  t.emplace_back(n - 1, n - 1, 1.0);
  Eigen::SparseMatrix<double> K(n, n);
  K.setFromTriplets(t.begin(), t.end());
  LinearSolver solver;
  REQUIRE(solver.factorize(K) == LinearSolver::Status::positive_definite);
  const LowestModes m = lowest_modes(solver, K, prescribed, 2, 200, 1e-12);
  REQUIRE(m.converged);
  const Eigen::MatrixXd free = Eigen::MatrixXd(K).block(1, 1, n - 2, n - 2);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> dense(free);
  for (int j = 0; j < 2; ++j) {
    CHECK(m.eigenvalues[j] == Approx(dense.eigenvalues()[j]).epsilon(1e-9));
    CHECK(std::abs(m.modes[j].segment(1, n - 2).dot(dense.eigenvectors().col(j))) == Approx(1.0).epsilon(1e-6));
    CHECK(m.modes[j][0] == 0.0);  // exactly: prescribed dofs stay out of the modes
  }
  // The lowest mode moves node 21 and little else.
  const ModeExtent e = mode_extent(m.modes[0], 1);
  CHECK(e.peak_node == 21);
  CHECK(e.participation < 0.25);  // a chain-wide mode would have ~0.6
  Eigen::VectorXd uniform = Eigen::VectorXd::Ones(n);
  CHECK(mode_extent(uniform, 1).participation == Approx(1.0));
}

TEST_CASE("an LU solve does not depend on the matrix it was factorised from living on", "[solver]") {
  // UMFPACK's solve reads the matrix again (iterative refinement) and Eigen keeps only a reference
  // to it. Newton's tangent is replaced before dp/dV is solved for; a dangling reference crashed
  // the main job inside umfdi_solve. Here the caller's matrix is changed after factorising: the
  // solve must still be that of the factorised one.
  Eigen::SparseMatrix<double> K(3, 3);
  K.insert(0, 0) = 2.0;
  K.insert(1, 1) = -1.0;  // indefinite: the LU route
  K.insert(2, 2) = 3.0;
  K.insert(0, 1) = K.insert(1, 0) = 0.5;
  K.makeCompressed();
  const Eigen::VectorXd b = Eigen::Vector3d(1.0, 2.0, 3.0);
  const Eigen::VectorXd expected = Eigen::MatrixXd(K).lu().solve(b);
  LinearSolver solver;
  REQUIRE(solver.factorize(K) == LinearSolver::Status::indefinite);
  // Same arrays, values 1 % larger: a solve that still read them would refine towards (1.01 K)⁻¹ b.
  for (int k = 0; k < K.nonZeros(); ++k) K.valuePtr()[k] *= 1.01;
  const Eigen::VectorXd x = solver.solve(b);
  CHECK((x - expected).norm() < 1e-12 * expected.norm());
}

namespace {
// The 1D Laplacian with diagonal `d` (SPD for d ≥ 2), n = 40.
SparseMatrix laplacian(double d, double first_diagonal) {
  const int n = 40;
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, i == 0 ? first_diagonal : d);
    if (i + 1 < n) t.emplace_back(i, i + 1, -1.0), t.emplace_back(i + 1, i, -1.0);
  }
  SparseMatrix K(n, n);
  K.setFromTriplets(t.begin(), t.end());
  return K;
}
}  // namespace

TEST_CASE("preconditioned CG solves an SPD system exactly in n steps and stops on negative curvature", "[solver]") {
  const SparseMatrix K = laplacian(2.5, 2.5);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(K.rows(), -1.0, 2.0);
  const auto identity = [](const Eigen::VectorXd& r) { return r; };
  Eigen::VectorXd d;
  const CgResult cg = preconditioned_cg(K, b, identity, 1e-12, 100, d);
  CHECK(cg.converged);
  CHECK(cg.iterations <= K.rows());
  CHECK((K * d - b).norm() <= 1e-12 * b.norm() * 1.0001);
  CHECK((d - Eigen::MatrixXd(K).llt().solve(b)).norm() < 1e-10 * d.norm());
  // The exact inverse as preconditioner: one iteration.
  const Eigen::MatrixXd Kinv = Eigen::MatrixXd(K).inverse();
  const CgResult exact = preconditioned_cg(K, b, [&](const Eigen::VectorXd& r) { return Eigen::VectorXd(Kinv * r); },
                                           1e-10, 100, d);
  CHECK(exact.converged);
  CHECK(exact.iterations == 1);
  // Indefinite: the first diagonal entry −3 makes e₀ a direction of negative curvature.
  const SparseMatrix indefinite = laplacian(2.5, -3.0);
  const CgResult stop = preconditioned_cg(indefinite, Eigen::VectorXd::Unit(K.rows(), 0), identity, 1e-12, 100, d);
  CHECK_FALSE(stop.converged);
  CHECK(stop.negative_curvature);
}

TEST_CASE("CG gives up early only where its residuals put the tolerance well beyond its budget", "[solver]") {
  // The rule: k + log(tol/r)/log ρ > 1.5·max, ρ = (r/r₁)^(1/(k−1)), from the fourth iteration on.
  CHECK_FALSE(cg_out_of_reach(3, 1.0, 0.5, 1e-10, 10));   // too soon to tell
  CHECK(cg_out_of_reach(4, 1.0, 0.1, 1e-10, 10));         // 0.46 an iteration: 27 more
  CHECK_FALSE(cg_out_of_reach(4, 1.0, 1e-4, 1e-10, 10));  // 0.05 an iteration: 5 more
  CHECK(cg_out_of_reach(5, 1.0, 1.0, 1e-10, 10));         // no progress at all
  CHECK_FALSE(cg_out_of_reach(10, 1.0, 0.5, 1e-10, 10));  // the budget is spent: CG stops on its own
  // A first step that overshoots ‖b‖ sevenfold, then 0.64 an iteration: 58 more, within 1.5 × 60
  // (the single-precision factor's test, whose CG converges in about 30).
  CHECK_FALSE(cg_out_of_reach(4, 6.8, 1.8, 1e-11, 60));
  const auto identity = [](const Eigen::VectorXd& r) { return r; };
  Eigen::VectorXd plain, early;
  // Ill-conditioned (κ ≈ 700) without a preconditioner: 10 iterations are far from 10⁻¹², and the
  // residuals say so early.
  const SparseMatrix slow = laplacian(2.0, 2.0);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(slow.rows(), -1.0, 2.0);
  const CgResult spent = preconditioned_cg(slow, b, identity, 1e-12, 10, plain);
  const CgResult gave_up = preconditioned_cg(slow, b, identity, 1e-12, 10, early, true);
  CHECK_FALSE(spent.converged);
  CHECK(spent.iterations == 10);
  CHECK_FALSE(gave_up.converged);
  CHECK(gave_up.gave_up);
  CHECK(gave_up.iterations < 10);
  // Well conditioned (κ ≈ 9): it converges within the budget, the same iterates either way.
  const SparseMatrix fast = laplacian(2.5, 2.5);
  const CgResult a = preconditioned_cg(fast, b, identity, 1e-8, 40, plain);
  const CgResult c = preconditioned_cg(fast, b, identity, 1e-8, 40, early, true);
  REQUIRE(a.converged);
  CHECK(c.converged);
  CHECK_FALSE(c.gave_up);
  CHECK(c.iterations == a.iterations);
  CHECK(early == plain);
}

TEST_CASE("a changed SPD tangent is solved by CG on the earlier factor, an indefinite one is refused", "[solver]") {
  LinearSolver::Options options;
  options.reuse_cg_iterations = 4;
  LinearSolver solver(options);
  const SparseMatrix K0 = laplacian(2.0, 2.0);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(K0.rows(), 1.0, 2.0);
  Eigen::VectorXd d;
  CHECK_FALSE(solver.solve_reusing_factor(K0, b, 1e-10, d));  // nothing factorised yet
  REQUIRE(solver.factorize(K0) == LinearSolver::Status::positive_definite);
  // K1 = 1.3 K0 + u uᵀ: K0⁻¹K1 has two distinct eigenvalues besides 1.3's cluster, so CG on
  // the factor of K0 converges in two iterations.
  const Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(K0.rows(), 0.0, 1.0);
  const SparseMatrix K1 = 1.3 * K0 + SparseMatrix((u * u.transpose()).sparseView());
  REQUIRE(solver.solve_reusing_factor(K1, b, 1e-10, d));
  CHECK((K1 * d - b).norm() <= 1e-10 * b.norm());
  CHECK(solver.factorizations == 1);
  CHECK(solver.reused_solves == 1);
  CHECK(solver.cg_iterations <= 3);
  // An indefinite tangent: CG meets negative curvature and says no; the caller factorises.
  CHECK_FALSE(solver.solve_reusing_factor(laplacian(2.0, -3.0), Eigen::VectorXd::Unit(K0.rows(), 0), 1e-10, d));
  // A factor that is an LU (of an indefinite matrix) is no preconditioner for CG.
  REQUIRE(solver.factorize(laplacian(2.0, -3.0)) == LinearSolver::Status::indefinite);
  CHECK_FALSE(solver.solve_reusing_factor(K0, b, 1e-10, d));
  CHECK(solver.reused_solves == 1);
}

TEST_CASE("CG on a held factor gives up early unless its caller's fallback is dearer than its budget", "[solver]") {
  // Volume control's CG (volume_control.cpp) falls back on an LU of an indefinite K: it asks for
  // the whole budget. The factor of a near-diagonal matrix preconditions the 1D Laplacian (κ ≈ 700)
  // hardly at all: 10 iterations are far from 10⁻¹², and the residuals say so early.
  LinearSolver::Options options;
  options.reuse_cg_iterations = 10;
  LinearSolver solver(options);
  REQUIRE(solver.factorize(laplacian(50.0, 50.0)) == LinearSolver::Status::positive_definite);
  const SparseMatrix slow = laplacian(2.0, 2.0);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(slow.rows(), -1.0, 2.0);
  Eigen::VectorXd d;
  CHECK_FALSE(solver.solve_reusing_factor(slow, b, 1e-12, d));
  const int early = solver.cg_iterations;
  CHECK(early >= 4);
  CHECK(early < 10);
  const LinearOperator apply = [&](const Eigen::VectorXd& p) { return Eigen::VectorXd(slow * p); };
  CHECK_FALSE(solver.solve_reusing_factor(apply, b, 1e-12, 10, /*give_up_early=*/false, d));
  CHECK(solver.cg_iterations - early == 10);
  CHECK_FALSE(solver.solve_reusing_factor(apply, b, 1e-12, 10, /*give_up_early=*/true, d));
  CHECK(solver.cg_iterations - early - 10 == early);
  CHECK(solver.factorizations == 1);
}

TEST_CASE("Newton reusing factors reaches the same path with fewer factorisations", "[solver]") {
  // The compression path of the stepper tests, solved twice: every iteration factorised, and by
  // CG on the last factor (inexact Newton, forcing min(1e-2, relative residual)).
  auto run = [](bool reuse, LinearSolver& solver) {
    Compression c(0.6);
    Vector x = c.problem->reference_positions();
    NewtonSettings newton;
    newton.reuse_factor = reuse;
    PathCallbacks cb{[](double) {}, {}};
    const auto r = follow_load_path(*c.problem, x, solver, {0.25, 0.5, 0.75, 1.0}, cb, newton, StepSettings{});
    REQUIRE(r.completed);
    return x;
  };
  LinearSolver exact;
  LinearSolver::Options options;
  options.reuse_cg_iterations = 30;
  LinearSolver reusing(options);
  const Vector x_exact = run(false, exact), x_reused = run(true, reusing);
  CHECK((x_reused - x_exact).norm() < 1e-6 * x_exact.norm());
  CHECK(reusing.reused_solves > 0);
  CHECK(reusing.factorizations < exact.factorizations);
}

TEST_CASE("a plain first step that fails on indefinite tangents does not make the steps creep up to it",
          "[solver]") {
  // Compressing to 40 % in one step from rest meets indefinite tangents (elements near inversion)
  // and gives up as an unstable branch. That says nothing of the path: the steps after the cut-back
  // grow as usual instead of halving their distance to the failed level (before: 6 halved steps
  // and 11 in all; now 7).
  Compression c(0.4);
  Vector x = c.problem->reference_positions();
  LinearSolver solver;
  NewtonSettings newton;
  newton.shift_indefinite_tangent = true;
  newton.max_indefinite_iterations = 1;
  StepSettings steps;
  steps.initial_increment = 1.0;
  const PathCallbacks none = no_callbacks();
  const auto r = follow_load_path(*c.problem, x, solver, {1.0}, none, newton, steps);
  CAPTURE(r.stats.failed_levels, r.stats.halved_steps, r.stats.steps, r.message);
  REQUIRE(!r.stats.failed_levels.empty());
  CHECK(r.stats.failed_levels.front() == 1.0);
  CHECK(r.stats.halved_steps == 0);
}

TEST_CASE("parallel_tasks runs every task once, one thread each, and hands back the first failure", "[solver]") {
  const int saved = thread_count();
  set_thread_count(2);
  std::vector<int> runs(7, 0), threads_seen(7, 0);
  parallel_tasks(7, [&](int i) {
    ++runs[i];
    threads_seen[i] = thread_count();
  });
  for (int i = 0; i < 7; ++i) {
    CHECK(runs[i] == 1);
    CHECK(threads_seen[i] == 1);  // the tasks' own assembly and BLAS stay serial
  }
  CHECK(thread_count() == 2);  // restored
  CHECK_THROWS_WITH(parallel_tasks(3, [](int i) { if (i == 1) throw std::runtime_error("task 1"); }), "task 1");
  CHECK(thread_count() == 2);
  set_thread_count(saved);
}

namespace {
/// The 7-point Laplacian of an m×m×m grid plus the identity: SPD, with a graph that METIS orders
/// by random matchings and bisections.
SparseMatrix grid_laplacian_3d(int m) {
  const auto at = [m](int i, int j, int k) { return (k * m + j) * m + i; };
  std::vector<Eigen::Triplet<double>> t;
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        const int r = at(i, j, k);
        t.emplace_back(r, r, 7.0);
        if (i + 1 < m) t.emplace_back(r, at(i + 1, j, k), -1.0), t.emplace_back(at(i + 1, j, k), r, -1.0);
        if (j + 1 < m) t.emplace_back(r, at(i, j + 1, k), -1.0), t.emplace_back(at(i, j + 1, k), r, -1.0);
        if (k + 1 < m) t.emplace_back(r, at(i, j, k + 1), -1.0), t.emplace_back(at(i, j, k + 1), r, -1.0);
      }
  SparseMatrix K(m * m * m, m * m * m);
  K.setFromTriplets(t.begin(), t.end());
  return K;
}
}  // namespace

TEST_CASE("two solvers factorising side by side give the bits each gives alone (METIS ordering)", "[solver]") {
  // The cells run side by side, one thread each; a design's answer must not depend on which
  // cell's analysis came first. METIS keeps one random generator for the whole process.
  const SparseMatrix K = grid_laplacian_3d(22);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(K.rows(), 1.0, 2.0);
  LinearSolver::Options options;
  options.ordering = LinearSolver::Options::Ordering::metis;
  options.mode = LinearSolver::Options::Mode::supernodal;
  options.share_analysis = false;  // each solver calls METIS (the kept analyses: the next test)
  const auto solve_alone = [&] {  // no Catch assertion inside: the tasks run it on two threads
    LinearSolver solver(options);
    return solver.factorize(K) == LinearSolver::Status::positive_definite ? Eigen::VectorXd(solver.solve(b))
                                                                          : Eigen::VectorXd();
  };
  const int saved = thread_count();
  set_thread_count(1);  // as each task runs: the BLAS's thread count changes its rounding too
  const Eigen::VectorXd alone = solve_alone();
  REQUIRE((K * alone - b).norm() <= 1e-10 * b.norm());
  set_thread_count(2);
  for (int round = 0; round < 4; ++round) {
    std::vector<Eigen::VectorXd> side_by_side(2);
    parallel_tasks(2, [&](int i) { side_by_side[i] = solve_alone(); }, {});
    for (const auto& x : side_by_side) {
      REQUIRE(x.size() == alone.size());
      CHECK(std::memcmp(x.data(), alone.data(), sizeof(double) * alone.size()) == 0);
    }
  }
  set_thread_count(saved);
}

TEST_CASE("a solver of a pattern analysed before takes the kept analysis: the same factor to the bit, no METIS", "[solver]") {
  // A cell rod runs many solvers on few patterns (symbolic_analysis_cache.hpp). A pattern no other
  // test makes: the grid Laplacian with its first and last unknowns coupled.
  SparseMatrix K = grid_laplacian_3d(17);
  const Eigen::Index n = K.rows();
  K.coeffRef(0, n - 1) = -0.1;
  K.coeffRef(n - 1, 0) = -0.1;
  K.makeCompressed();
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, 1.0, 2.0);
  const auto solved = [&](const SparseMatrix& A, const LinearSolver::Options& options, double* flops = nullptr) {
    LinearSolver solver(options);
    REQUIRE(solver.factorize(A) == LinearSolver::Status::positive_definite);
    if (flops) *flops = solver.factor_flops;
    return Eigen::VectorXd(solver.solve(b));
  };
  LinearSolver::Options fresh;
  fresh.share_analysis = false;
  double flops_fresh = 0, flops_made = 0, flops_served = 0;
  const Eigen::VectorXd reference = solved(K, fresh, &flops_fresh);
  const AnalysisCounts before = analysis_counts();
  const Eigen::VectorXd made = solved(K, {}, &flops_made);
  const AnalysisCounts after_first = analysis_counts();
  CHECK(after_first.made == before.made + 1);  // the first of its pattern: analysed, and kept
  CHECK(after_first.served == before.served);
  const Eigen::VectorXd served = solved(K, {}, &flops_served);
  const AnalysisCounts after_second = analysis_counts();
  CHECK(after_second.served == after_first.served + 1);  // the second: served, METIS not called
  CHECK(after_second.made == after_first.made);
  for (const Eigen::VectorXd* x : {&made, &served}) {
    REQUIRE(x->size() == reference.size());
    CHECK(std::memcmp(x->data(), reference.data(), sizeof(double) * n) == 0);
  }
  CHECK(flops_served == flops_fresh);
  CHECK(flops_made == flops_fresh);
  // Other values on the same pattern: served, and solved right.
  SparseMatrix scaled = K;
  scaled.diagonal() *= 2.0;
  const Eigen::VectorXd x_scaled = solved(scaled, {});
  CHECK(analysis_counts().served == after_second.served + 1);
  CHECK((scaled * x_scaled - b).norm() <= 1e-10 * b.norm());
  // Another pattern, or other settings: analysed anew.
  SparseMatrix other = K;
  other.coeffRef(1, n - 2) = -0.1;
  other.coeffRef(n - 2, 1) = -0.1;
  other.makeCompressed();
  const Eigen::VectorXd x_other = solved(other, {});
  CHECK(analysis_counts().made == after_second.made + 1);
  CHECK((other * x_other - b).norm() <= 1e-10 * b.norm());
  LinearSolver::Options amd;
  amd.ordering = LinearSolver::Options::Ordering::amd;
  solved(K, amd);
  CHECK(analysis_counts().made == after_second.made + 2);
}

TEST_CASE("The triangle of PKPᵀ CHOLMOD factorises is gathered from K's columns, entry for entry", "[solver]") {
  // Against Eigen's own permutation of K (twistedBy), for a scrambled ordering, both triangles.
  SparseMatrix K = grid_laplacian_3d(5);
  for (int j = 0; j < K.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(K, j); it; ++it)
      it.valueRef() *= 1.0 + 0.1 * std::sin(0.37 * it.row() + 0.11 * it.col());  // distinct, not symmetric
  const int n = static_cast<int>(K.rows());
  std::vector<int> perm(n);
  for (int i = 0; i < n; ++i) perm[i] = (37 * i + 11) % n;  // 37 is prime to n = 125
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> P(n);
  for (int i = 0; i < n; ++i) P.indices()[perm[i]] = i;  // P maps K's row perm[i] to row i
  const SparseMatrix PKP = SparseMatrix(P * K * P.transpose());
  for (const bool lower : {true, false}) {
    PermutedTriangle triangle(K, perm.data(), lower);
    REQUIRE(triangle.fits(K));
    const cholmod_sparse A = triangle.gather(K);
    CHECK(A.stype == (lower ? -1 : 1));
    const int* p = static_cast<const int*>(A.p);
    const int* i = static_cast<const int*>(A.i);
    const double* x = static_cast<const double*>(A.x);
    int entries = 0;
    for (int j = 0; j < n; ++j)
      for (int k = p[j]; k < p[j + 1]; ++k, ++entries) {
        CAPTURE(lower, i[k], j);
        CHECK((lower ? i[k] >= j : i[k] <= j));
        if (k > p[j]) CHECK(i[k] > i[k - 1]);  // sorted, as CHOLMOD's transposition leaves them
        CHECK(x[k] == PKP.coeff(i[k], j));     // the very entry, not a sum or a mirror
      }
    CHECK(entries == (PKP.nonZeros() + n) / 2);
  }
  CHECK(!PermutedTriangle(K, perm.data(), true).fits(SparseMatrix(n + 1, n + 1)));
  CHECK(!PermutedTriangle().fits(K));  // a solver's first factorisation makes the positions
}

TEST_CASE("CHOLMOD on the gathered triangle solves K as a separate factorisation does, shifted or not", "[solver]") {
  SparseMatrix K = grid_laplacian_3d(14);
  for (int j = 0; j < K.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(K, j); it; ++it)
      if (it.row() != it.col()) {
        const int lo = std::min<int>(it.row(), it.col()), hi = std::max<int>(it.row(), it.col());
        it.valueRef() *= 1.0 + 0.1 * std::sin(0.37 * lo + 0.11 * hi);  // distinct values, still symmetric
      }
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(K.rows(), 1.0, 2.0);
  const Eigen::VectorXd reference = Eigen::SimplicialLLT<SparseMatrix>(K).solve(b);  // Eigen's own Cholesky
  using Options = LinearSolver::Options;
  for (const auto mode : {Options::Mode::simplicial, Options::Mode::supernodal}) {
    CAPTURE(mode == Options::Mode::supernodal);
    Options options;
    options.mode = mode;
    LinearSolver solver(options);
    for (int round = 0; round < 2; ++round) {  // the second factorisation reuses the gather's positions
      REQUIRE(solver.factorize(K) == LinearSolver::Status::positive_definite);
      const Eigen::VectorXd x = solver.solve(b);
      CHECK((x - reference).norm() <= 1e-12 * reference.norm());
      SparseMatrix indefinite = K;
      indefinite.diagonal().array() -= 6.5;  // a few negative eigenvalues: factorize_shifted's ladder
      REQUIRE(solver.factorize_shifted(indefinite) == LinearSolver::Status::indefinite);
      SparseMatrix with_shift = indefinite;
      with_shift.diagonal().array() += solver.last_shift;
      const Eigen::VectorXd shifted_reference = Eigen::SimplicialLLT<SparseMatrix>(with_shift).solve(b);
      CHECK((solver.solve(b) - shifted_reference).norm() <= 1e-10 * shifted_reference.norm());
    }
  }
}

TEST_CASE("Newton stops where its last two steps' contraction bounds the error left by the update tolerance",
          "[solver]") {
  // The bound (remaining_error.hpp) on its own: θ/(1−θ)·‖δ_k‖ for θ = ‖δ_k‖/‖δ_{k−1}‖ up to ½, none past.
  CHECK(remaining_error_bound(1.0, 0.5) == Approx(0.5));
  CHECK(remaining_error_bound(7.155e-4, 1.135e-5) == Approx(1.135e-5 * 1.135e-5 / (7.155e-4 - 1.135e-5)));
  CHECK(std::isinf(remaining_error_bound(1.0, 0.6)));
  CHECK(std::isinf(remaining_error_bound(0.0, 0.0)));
  // The cylinder squashed in steps of 2 % of its height, each Newton solve from the last state: those
  // that converged where the residual met its tolerance and the last two steps bounded the error
  // left by the update tolerance, one iteration before the update itself fell below it, are as close
  // to equilibrium as the bound says (against the same step solved to round-off).
  Compression c(0.8, nullptr, 200.0);  // ν = 0.4975: residual and update fall at different rates
  Vector x = c.problem->reference_positions();
  LinearSolver solver;
  const NewtonSettings newton;
  NewtonSettings strict;
  strict.residual_tolerance = 1e-14;
  strict.update_tolerance = 1e-13;
  int stopped_by_bound = 0;
  for (int step = 1; step <= 10; ++step) {
    c.problem->apply_constraints(x, 0.1 * step);
    Vector tight = x;
    const NewtonReport report = solve_newton(*c.problem, x, solver, newton);
    REQUIRE(report.converged);
    REQUIRE(report.rows.size() >= 2);
    const NewtonRow &last = report.rows.back(), &before = report.rows[report.rows.size() - 2];
    CAPTURE(step, report.iterations, before.update, last.update);
    if (last.update <= newton.update_tolerance) continue;
    ++stopped_by_bound;
    const double bound = remaining_error_bound(before.update, last.update);
    CHECK(bound <= newton.update_tolerance);
    LinearSolver solver2;
    REQUIRE(solve_newton(*c.problem, tight, solver2, strict).converged);
    const double displacement = (tight - c.problem->reference_positions()).norm();
    // Measured: errors of 4e-11 to 1.2e-8 of the displacement, against bounds of 3e-9 to 8e-7.
    CHECK((x - tight).norm() <= bound * displacement);
    x = tight;
  }
  CHECK(stopped_by_bound >= 3);
}

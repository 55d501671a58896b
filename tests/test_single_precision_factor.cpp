// The single-precision copy of a supernodal Cholesky factor (fem/solver/single_precision_factor.hpp):
// its solves against the double factor's on a tangent-like matrix with a 10⁴ stiffness contrast (the
// rings' against the silicone's), CG preconditioned with it against the exact solution, and the
// factors it declines.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include <Eigen/CholmodSupport>

#include "fem/solver/linear_solver.hpp"
#include "fem/solver/preconditioned_cg.hpp"
#include "fem/solver/single_precision_factor.hpp"

using namespace softarm::fem;

namespace {
/// The 7-point Laplacian of an m×m×m grid plus a small multiple of the identity, its couplings 10⁴
/// times stiffer in the slab of layers k = m/2 … m/2 + 1: SPD, with the contrast of an ABS ring in
/// silicone and a condition number near 10⁶.
SparseMatrix stiff_slab_laplacian(int m) {
  const auto at = [m](int i, int j, int k) { return (k * m + j) * m + i; };
  const auto stiffness = [m](int k0, int k1) { return k0 >= m / 2 && k1 <= m / 2 + 1 ? 1e4 : 1.0; };
  std::vector<Eigen::Triplet<double>> t;
  const auto couple = [&](int a, int b, double c) {
    t.emplace_back(a, a, c), t.emplace_back(b, b, c), t.emplace_back(a, b, -c), t.emplace_back(b, a, -c);
  };
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        const int r = at(i, j, k);
        t.emplace_back(r, r, 0.1);
        if (i + 1 < m) couple(r, at(i + 1, j, k), stiffness(k, k));
        if (j + 1 < m) couple(r, at(i, j + 1, k), stiffness(k, k));
        if (k + 1 < m) couple(r, at(i, j, k + 1), stiffness(k, k + 1));
      }
  SparseMatrix K(m * m * m, m * m * m);
  K.setFromTriplets(t.begin(), t.end());
  return K;
}

/// CHOLMOD's factor through Eigen, with the factor itself in reach.
struct Factor : Eigen::CholmodDecomposition<SparseMatrix, Eigen::Lower> {
  explicit Factor(bool supernodal) {
    cholmod().supernodal = supernodal ? CHOLMOD_SUPERNODAL : CHOLMOD_SIMPLICIAL;
    if (!supernodal) cholmod().final_ll = 0;  // LDLᵀ
  }
  const cholmod_factor& factor() const { return *m_cholmodFactor; }
};
}  // namespace

TEST_CASE("A supernodal factor copied to single precision solves as it does to single precision, and CG on it to double",
          "[solver]") {
  const SparseMatrix K = stiff_slab_laplacian(14);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(K.rows(), -1.0, 2.0);
  Factor L(true);
  L.compute(K);
  REQUIRE(L.info() == Eigen::Success);
  REQUIRE(L.factor().is_super);
  SinglePrecisionFactor single;
  REQUIRE(single.assign(L.factor()));
  const Eigen::VectorXd exact = L.solve(b);
  REQUIRE((K * exact - b).norm() <= 1e-9 * b.norm());

  SECTION("Its solve is the double factor's to single precision, times the factor's condition") {
    const Eigen::VectorXd x = single.solve(b);
    const double off = (x - exact).norm() / exact.norm();
    INFO("relative difference " << off);
    CHECK(off < 1e-3);   // u·κ(L) with u = 6e-8 and κ(L) = √κ(K) ≈ 1e3
    CHECK(off > 1e-12);  // and not the double factor's: single precision it is
    // Any scale: b is brought to unit norm first, so 10⁻⁴⁰ (below single precision's normal range)
    // and 10³⁰ give the same digits.
    for (const double scale : {1e-40, 1e30}) {
      const Eigen::VectorXd scaled = single.solve(scale * b);
      CHECK((scaled / scale - x).norm() <= 1e-12 * x.norm());
    }
    CHECK(single.solve(Eigen::VectorXd::Zero(K.rows())).isZero(0));
  }
  SECTION("CG preconditioned with it reaches double precision in a few iterations") {
    Eigen::VectorXd d;
    const CgResult cg = preconditioned_cg(K, b, [&](const Eigen::VectorXd& r) { return single.solve(r); }, 1e-12, 20, d);
    INFO(cg.iterations << " iterations, relative residual " << cg.relative_residual);
    CHECK(cg.converged);
    CHECK(cg.iterations <= 5);
    CHECK((d - exact).norm() <= 1e-9 * exact.norm());
  }
  SECTION("The linear solver's CG on an earlier factor uses it, and finds what the double factor finds") {
    // K1 = 1.3 K, every 97th unknown stiffer, solved by CG on the factor of K: with the double
    // factor and with its copy.
    const Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(K.rows(), 0.0, 1.0);
    SparseMatrix uu(K.rows(), K.rows());
    std::vector<Eigen::Triplet<double>> t;
    for (int i = 0; i < K.rows(); i += 97) t.emplace_back(i, i, 50.0 * u[i] * u[i] + 1.0);
    uu.setFromTriplets(t.begin(), t.end());
    const SparseMatrix K1 = 1.3 * K + uu;
    std::vector<Eigen::VectorXd> d(2);
    std::vector<int> iterations(2);
    for (int single_precision = 0; single_precision < 2; ++single_precision) {
      LinearSolver::Options options;
      options.mode = LinearSolver::Options::Mode::supernodal;
      options.reuse_cg_iterations = 60;
      options.single_precision_preconditioner = single_precision == 1;
      LinearSolver solver(options);
      REQUIRE(solver.factorize(K) == LinearSolver::Status::positive_definite);
      REQUIRE(solver.supernodal);
      REQUIRE(solver.solve_reusing_factor(K1, b, 1e-11, d[single_precision]));
      iterations[single_precision] = solver.cg_iterations;
    }
    INFO("CG iterations: " << iterations[0] << " on the double factor, " << iterations[1] << " on its copy; true relative residuals "
                           << (K1 * d[0] - b).norm() / b.norm() << " and " << (K1 * d[1] - b).norm() / b.norm());
    // CG's own residual reaches 1e-11; the true one drifts from it by rounding over ~30 iterations at
    // this conditioning, the same on either factor (measured: 1.9e-11 and 2.0e-11, in 28 and 33
    // iterations). The copy costs iterations only where CG is asked for more than single precision.
    CHECK((K1 * d[1] - b).norm() <= 1e-10 * b.norm());
    CHECK((d[1] - d[0]).norm() <= 1e-9 * d[0].norm());
    CHECK(iterations[1] <= iterations[0] + 6);
  }
}

TEST_CASE("A simplicial factor is not copied to single precision", "[solver]") {
  const SparseMatrix K = stiff_slab_laplacian(6);
  Factor L(false);
  L.compute(K);
  REQUIRE(L.info() == Eigen::Success);
  REQUIRE_FALSE(L.factor().is_super);
  SinglePrecisionFactor single;
  CHECK_FALSE(single.assign(L.factor()));
  CHECK(single.empty());
}

// The tangent's sparsity pattern (fem/sparse/sparse_pattern.hpp) against one built the plain way,
// from a std::set of (row, column) pairs: the same columns, and every block entry's position names
// its own row in its own column; scattered blocks sum to the dense sum of the same blocks.
#include <catch2/catch.hpp>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "fem/sparse/sparse_pattern.hpp"

using namespace softarm::fem;

TEST_CASE("The sparsity pattern holds each coupled pair once and each block entry's position is its own", "[assembly]") {
  std::mt19937 rng(5);
  const int n = 300;
  std::uniform_int_distribution<int> dof(0, n - 1), size(1, 12);
  SparsePattern pattern(n);
  std::vector<std::vector<int>> blocks;
  for (int b = 0; b < 200; ++b) {
    std::vector<int> d(size(rng));
    for (int& x : d) x = dof(rng);  // a dof may repeat within a block, as it may in a form's list
    blocks.push_back(d);
    REQUIRE(pattern.declare_block(d) == b);
  }
  pattern.finalize();
  const SparseMatrix& m = pattern.zero_matrix();

  std::set<std::pair<int, int>> expected;  // (column, row)
  for (int c = 0; c < n; ++c) expected.insert({c, c});
  for (const auto& d : blocks)
    for (int j : d)
      for (int i : d) expected.insert({j, i});
  std::set<std::pair<int, int>> got;
  for (int c = 0; c < n; ++c)
    for (SparseMatrix::InnerIterator it(m, c); it; ++it) {
      CHECK(it.value() == 0.0);
      got.insert({c, static_cast<int>(it.row())});
    }
  REQUIRE(m.isCompressed());
  REQUIRE(static_cast<std::size_t>(m.nonZeros()) == expected.size());  // no entry twice
  REQUIRE(got == expected);

  for (std::size_t b = 0; b < blocks.size(); ++b) {
    const auto& d = blocks[b];
    const int s = static_cast<int>(d.size());
    REQUIRE(pattern.block_size(static_cast<int>(b)) == s);
    const int* pos = pattern.positions(static_cast<int>(b));
    for (int j = 0; j < s; ++j)
      for (int i = 0; i < s; ++i) {
        const int k = pos[j * s + i];
        INFO("block " << b << ", entry (" << i << ", " << j << ")");
        REQUIRE(k >= m.outerIndexPtr()[d[j]]);
        REQUIRE(k < m.outerIndexPtr()[d[j] + 1]);
        REQUIRE(m.innerIndexPtr()[k] == d[i]);
      }
  }

  // Scattered through two threads' accumulators, the blocks sum to their dense sum.
  std::uniform_real_distribution<double> value(-1, 1);
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(n, n);
  HessianAccumulator acc(pattern, 2);
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    const auto& d = blocks[b];
    const int s = static_cast<int>(d.size());
    std::vector<double> v(static_cast<std::size_t>(s * s));
    for (double& x : v) x = value(rng);
    for (int j = 0; j < s; ++j)
      for (int i = 0; i < s; ++i) dense(d[i], d[j]) += v[j * s + i];
    acc.add_block(static_cast<int>(b % 2), static_cast<int>(b), v.data());
  }
  SparseMatrix sum;
  acc.finish(sum);
  CHECK((Eigen::MatrixXd(sum) - dense).cwiseAbs().maxCoeff() < 1e-12);
}

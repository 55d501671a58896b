// The tangent's sparsity pattern (fem/sparse/sparse_pattern.hpp) against one built the plain way,
// from a std::set of (row, column) pairs: the same columns, and every block entry's position names
// its own row in its own column, also in blocks kept by runs of consecutive dofs (a node's x, y, z);
// scattered blocks sum to the dense sum of the same blocks.
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
  std::uniform_int_distribution<int> node3(0, n / 3 - 1), node2(0, n / 2 - 1);
  for (int b = 0; b < 300; ++b) {
    std::vector<int> d(size(rng));
    if (b % 3 == 0) {
      for (int& x : d) x = dof(rng);  // a dof may repeat within a block, as it may in a form's list
    } else {  // nodes of three or two dofs each, a node possibly twice
      const int w = b % 3 == 1 ? 3 : 2;
      d.resize(w * d.size());
      for (std::size_t a = 0; a < d.size(); a += w) {
        const int first = w * (w == 3 ? node3(rng) : node2(rng));
        for (int k = 0; k < w; ++k) d[a + k] = first + k;
      }
    }
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
    // Kept by runs where the dofs come as nodes: the table a third (a half) of the plain one.
    if (b % 3 != 0) CHECK(pattern.run_length(static_cast<int>(b)) >= (b % 3 == 1 ? 3 : 2));
    for (int j = 0; j < s; ++j)
      for (int i = 0; i < s; ++i) {
        const int k = pattern.position(static_cast<int>(b), i, j);
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

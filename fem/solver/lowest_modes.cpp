#include "fem/solver/lowest_modes.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace softarm::fem {

LowestModes lowest_modes(LinearSolver& solver, const Eigen::SparseMatrix<double>& K, const std::vector<char>& prescribed,
                         int count, int max_iterations, double tolerance) {
  const Eigen::Index n = K.rows();
  // Bathe's subspace size: min(2p, p + 8) vectors converge the lowest p faster than p alone.
  const int q = std::min<int>(static_cast<int>(n), std::min(2 * count, count + 8));
  const auto free_only = [&](Eigen::VectorXd& v) {
    for (Eigen::Index i = 0; i < n; ++i)
      if (prescribed[i]) v[i] = 0.0;
  };
  // Start: the diagonal's inverse (a vector that weights the soft dofs) and deterministic pseudo-random vectors.
  Eigen::MatrixXd X(n, q);
  std::uint64_t seed = 0x9E3779B97F4A7C15ull;
  for (int j = 0; j < q; ++j)
    for (Eigen::Index i = 0; i < n; ++i) {
      seed = seed * 6364136223846793005ull + 1442695040888963407ull;
      X(i, j) = j == 0 ? 1.0 / std::max(std::abs(K.coeff(i, i)), 1e-300)
                       : static_cast<double>(seed >> 11) / 9007199254740992.0 - 0.5;
    }
  LowestModes out;
  std::vector<double> previous(q, 0.0);
  Eigen::VectorXd v;
  for (int it = 1; it <= max_iterations; ++it) {
    // Inverse iteration on the block, then Rayleigh–Ritz on its span.
    for (int j = 0; j < q; ++j) {
      v = X.col(j);
      free_only(v);
      v = solver.solve(v);
      free_only(v);
      X.col(j) = v;
    }
    Eigen::HouseholderQR<Eigen::MatrixXd> qr(X);
    const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(n, q);
    const Eigen::MatrixXd reduced = Q.transpose() * (K * Q);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (reduced + reduced.transpose()));
    X = Q * eig.eigenvectors();
    out.iterations = it;
    bool settled = true;
    for (int j = 0; j < count; ++j) {
      const double l = eig.eigenvalues()[j];
      settled = settled && std::abs(l - previous[j]) <= tolerance * std::abs(l);
      previous[j] = l;
    }
    if (settled && it > 1) {
      out.converged = true;
      break;
    }
  }
  for (int j = 0; j < count && j < q; ++j) {
    out.eigenvalues.push_back(previous[j]);
    v = X.col(j);
    free_only(v);  // exactly zero there, not round-off from the Ritz step
    out.modes.push_back(v.normalized());
  }
  return out;
}

ModeExtent mode_extent(const Eigen::VectorXd& mode, int dofs_per_node) {
  const Eigen::Index nodes = mode.size() / dofs_per_node;
  double sum = 0, sum_sq = 0, peak = -1;
  ModeExtent out;
  for (Eigen::Index a = 0; a < nodes; ++a) {
    const double amplitude = mode.segment(a * dofs_per_node, dofs_per_node).squaredNorm();
    sum += amplitude;
    sum_sq += amplitude * amplitude;
    if (amplitude > peak) peak = amplitude, out.peak_node = static_cast<int>(a);
  }
  out.participation = sum_sq > 0 ? sum * sum / (static_cast<double>(nodes) * sum_sq) : 0.0;
  return out;
}

}  // namespace softarm::fem

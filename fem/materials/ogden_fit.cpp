#include "fem/materials/ogden_fit.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include "fem/materials/least_squares.hpp"
#include "fem/materials/uniaxial_closed_form.hpp"

namespace softarm::fem {
namespace {

constexpr double alpha_floor = 1e-3;
const std::vector<double> start_grid{-4.0, -2.0, -1.0, 0.5, 1.0, 2.0, 3.0, 5.0, 8.0};
constexpr int max_iterations = 400;

bool admissible(const Eigen::VectorXd& alpha, double max_abs_alpha) {
  return alpha.allFinite() && (alpha.array().abs() >= alpha_floor).all() &&
         (alpha.array().abs() <= max_abs_alpha).all();
}

/// The variable-projection state at α: μ(α), r(α) = P − Bμ and the SSE.
struct Projection {
  Eigen::MatrixXd B;
  Eigen::VectorXd mu, residual;
  double sse = std::numeric_limits<double>::infinity();
};

Projection project(const Eigen::VectorXd& stretch, const Eigen::VectorXd& stress, const Eigen::VectorXd& alpha) {
  Projection p;
  p.B = ogden_basis(stretch, alpha);
  p.mu = linear_least_squares(p.B, stress);
  p.residual = stress - p.B * p.mu;
  p.sse = p.residual.allFinite() ? p.residual.squaredNorm() : std::numeric_limits<double>::infinity();
  return p;
}

/// Kaufman's Jacobian of r(α): column i = −(I − B B⁺)(∂φ_i/∂α_i μ_i).
Eigen::MatrixXd kaufman_jacobian(const Eigen::VectorXd& stretch, const Eigen::VectorXd& alpha, const Projection& p) {
  Eigen::MatrixXd J(stretch.size(), alpha.size());
  for (Eigen::Index i = 0; i < alpha.size(); ++i) {
    Eigen::VectorXd v(stretch.size());
    for (Eigen::Index r = 0; r < stretch.size(); ++r) v[r] = ogden_basis_dalpha(stretch[r], alpha[i]) * p.mu[i];
    J.col(i) = -(v - p.B * linear_least_squares(p.B, v));
  }
  return J;
}

/// Levenberg–Marquardt (Marquardt's diagonal scaling) on the projected residual from alpha0.
OgdenFit levenberg_marquardt(const Eigen::VectorXd& stretch, const Eigen::VectorXd& stress, Eigen::VectorXd alpha,
                             double max_abs_alpha) {
  Projection p = project(stretch, stress, alpha);
  double damping = 1e-3;
  for (int it = 0; it < max_iterations && damping < 1e12; ++it) {
    const Eigen::MatrixXd J = kaufman_jacobian(stretch, alpha, p);
    const Eigen::MatrixXd A = J.transpose() * J;
    const Eigen::VectorXd g = J.transpose() * p.residual;
    const double diagonal_floor = 1e-12 * std::max(A.diagonal().maxCoeff(), 1e-300);
    bool accepted = false;
    while (!accepted && damping < 1e12) {
      Eigen::MatrixXd M = A;
      M.diagonal() += damping * A.diagonal().cwiseMax(diagonal_floor);
      const Eigen::VectorXd step = -M.ldlt().solve(g);
      const Eigen::VectorXd trial = alpha + step;
      if (admissible(trial, max_abs_alpha)) {
        Projection q = project(stretch, stress, trial);
        if (q.sse < p.sse) {
          const double decrease = p.sse - q.sse;
          const bool converged = decrease <= 1e-14 * p.sse || step.norm() <= 1e-12 * (1.0 + alpha.norm());
          alpha = trial;
          p = std::move(q);
          damping = std::max(damping / 3.0, 1e-12);
          accepted = true;
          if (converged) damping = 1e12;  // ends the outer loop
          continue;
        }
      }
      damping *= 4.0;
    }
  }
  OgdenFit fit;
  fit.alpha = alpha;
  fit.mu = p.mu;
  fit.sse = p.sse;
  return fit;
}

/// Every `terms`-subset of the start grid values within the bound, as exponent vectors.
std::vector<Eigen::VectorXd> starting_points(int terms, double max_abs_alpha) {
  std::vector<double> grid;
  for (double a : start_grid)
    if (std::abs(a) <= max_abs_alpha) grid.push_back(a);
  std::vector<Eigen::VectorXd> starts;
  std::vector<int> pick(terms);
  std::iota(pick.begin(), pick.end(), 0);
  const int n = static_cast<int>(grid.size());
  while (true) {
    Eigen::VectorXd a(terms);
    for (int i = 0; i < terms; ++i) a[i] = grid[pick[i]];
    starts.push_back(a);
    int i = terms - 1;  // next combination in lexicographic order
    while (i >= 0 && pick[i] == n - terms + i) --i;
    if (i < 0) break;
    ++pick[i];
    for (int k = i + 1; k < terms; ++k) pick[k] = pick[k - 1] + 1;
  }
  return starts;
}

OgdenFit sorted_by_alpha(const OgdenFit& fit) {
  std::vector<Eigen::Index> order(fit.alpha.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) { return fit.alpha[a] < fit.alpha[b]; });
  OgdenFit out = fit;
  for (std::size_t k = 0; k < order.size(); ++k) {
    out.alpha[k] = fit.alpha[order[k]];
    out.mu[k] = fit.mu[order[k]];
  }
  return out;
}

}  // namespace

OgdenFit fit_ogden(const Eigen::VectorXd& stretch, const Eigen::VectorXd& stress, int terms, double max_abs_alpha) {
  max_abs_alpha = std::max(max_abs_alpha, 1.0);  // the start grid needs at least {-1, 0.5, 1}
  OgdenFit best, best_valid;
  best.sse = best_valid.sse = std::numeric_limits<double>::infinity();
  int runs = 0;
  for (const auto& start : starting_points(terms, max_abs_alpha)) {
    const OgdenFit fit = levenberg_marquardt(stretch, stress, start, max_abs_alpha);
    ++runs;
    if (fit.sse < best.sse) best = fit;
    if (fit.mu.sum() > 0.0 && fit.sse < best_valid.sse) best_valid = fit;
  }
  OgdenFit out = sorted_by_alpha(std::isfinite(best_valid.sse) ? best_valid : best);
  out.starts = runs;
  return out;
}

}  // namespace softarm::fem

#include "fem/materials/drucker_stability.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

#include "fem/core/input_error.hpp"

namespace softarm::fem {
namespace {

constexpr int grid_steps_per_unit_log = 1000;  // Δ(ln λ) = 1e-3
constexpr double bisection_relative_tolerance = 1e-7;

bool positive_definite(const Eigen::Matrix2d& H) {
  // Sylvester's criterion; NaN compares false and so reads as unstable.
  return H(0, 0) > 0.0 && H(0, 0) * H(1, 1) - H(0, 1) * H(1, 0) > 0.0;
}

/// Walks from ln λ = 0 towards ln λ = end; returns the last stable ln λ
/// (refined by bisection) and whether an unstable point was met.
std::pair<double, bool> stable_extent(const HyperelasticLaw& law, LoadingMode mode, double end) {
  const int steps = std::max(1, static_cast<int>(std::ceil(std::abs(end) * grid_steps_per_unit_log)));
  const double step = end / steps;
  auto stable = [&](double log_lambda) { return drucker_stable(law, mode, std::exp(log_lambda)); };
  for (int k = 1; k <= steps; ++k) {
    const double x = k * step;
    if (stable(x)) continue;
    double good = (k - 1) * step, bad = x;  // stable at good, unstable at bad
    while (std::abs(bad - good) > bisection_relative_tolerance) {  // in ln λ: relative in λ
      const double mid = 0.5 * (good + bad);
      (stable(mid) ? good : bad) = mid;
    }
    return {good, true};
  }
  return {end, false};
}

}  // namespace

std::string mode_name(LoadingMode mode) {
  switch (mode) {
    case LoadingMode::uniaxial: return "uniaxial";
    case LoadingMode::equibiaxial: return "equibiaxial";
    case LoadingMode::planar: return "planar";
  }
  return "?";
}

Eigen::Vector2d path_log_strains(LoadingMode mode, double lambda) {
  const double e = std::log(lambda);
  switch (mode) {
    case LoadingMode::uniaxial: return {e, -0.5 * e};
    case LoadingMode::equibiaxial: return {e, e};
    case LoadingMode::planar: return {e, 0.0};
  }
  return {0.0, 0.0};
}

Jet3 incompressible_energy(const HyperelasticLaw& law, double eps1, double eps2) {
  const Jet3 e1 = Jet3::variable(eps1, 0), e2 = Jet3::variable(eps2, 1);
  // c_a = λ_a² = e^{2ε_a}; J = 1, so the split laws' W̄ is the whole energy.
  return law.principal_energy(exp(2.0 * e1), exp(2.0 * e2), exp(-2.0 * (e1 + e2)));
}

Eigen::Matrix2d drucker_matrix(const HyperelasticLaw& law, double eps1, double eps2) {
  return incompressible_energy(law, eps1, eps2).h.topLeftCorner<2, 2>();
}

bool drucker_stable_at(const HyperelasticLaw& law, double eps1, double eps2) {
  return positive_definite(drucker_matrix(law, eps1, eps2));
}

bool drucker_stable(const HyperelasticLaw& law, LoadingMode mode, double lambda) {
  const Eigen::Vector2d e = path_log_strains(mode, lambda);
  return drucker_stable_at(law, e[0], e[1]);
}

double nominal_stress(const HyperelasticLaw& law, LoadingMode mode, double lambda) {
  // τ_a = λ_a ∂W/∂λ_a − p. Direction 3 is traction free on every path
  // (uniaxial: τ2 = τ3 = 0; equibiaxial: τ1 = τ2, τ3 = 0; planar: λ2 = 1 held
  // by τ2, τ3 = 0), so σ1 = τ1 − τ3 = ∂w/∂ε1 and P1 = σ1 λ2 λ3 = σ1 / λ1.
  const Eigen::Vector2d e = path_log_strains(mode, lambda);
  return incompressible_energy(law, e[0], e[1]).g[0] / lambda;
}

std::vector<ModeStability> drucker_stability(const HyperelasticLaw& law, double lambda_lo, double lambda_hi) {
  if (!(lambda_lo > 0.0 && lambda_lo < 1.0)) {
    std::ostringstream m;
    m << "value " << lambda_lo << " is out of range; valid: (0, 1)";
    throw InputError("lambda_lo", m.str());
  }
  if (!(lambda_hi > 1.0 && std::isfinite(lambda_hi))) {
    std::ostringstream m;
    m << "value " << lambda_hi << " is out of range; valid: > 1";
    throw InputError("lambda_hi", m.str());
  }
  std::vector<ModeStability> out;
  const bool at_rest = positive_definite(drucker_matrix(law, 0.0, 0.0));
  for (LoadingMode mode : all_loading_modes) {
    ModeStability s;
    s.mode = mode_name(mode);
    s.stable_at_rest = at_rest;
    if (!at_rest) {
      s.lambda_min = s.lambda_max = std::numeric_limits<double>::quiet_NaN();
      s.bounded_below = s.bounded_above = true;
    } else {
      const auto [up, bounded_up] = stable_extent(law, mode, std::log(lambda_hi));
      const auto [down, bounded_down] = stable_extent(law, mode, std::log(lambda_lo));
      s.lambda_max = bounded_up ? std::exp(up) : lambda_hi;
      s.lambda_min = bounded_down ? std::exp(down) : lambda_lo;
      s.bounded_above = bounded_up;
      s.bounded_below = bounded_down;
    }
    out.push_back(s);
  }
  return out;
}

}  // namespace softarm::fem

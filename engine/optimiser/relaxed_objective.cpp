// Relaxed objective in normalised space with integer interpolation (see relaxed_objective.hpp).
#include "engine/optimiser/relaxed_objective.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

namespace softarm::optimise::detail {

RelaxedObjective::RelaxedObjective(const DesignSpace& space, EvaluationCache& cache,
                                   std::vector<double> base, std::vector<std::size_t> searched)
    : space_(space),
      cache_(cache),
      base_(std::move(base)),
      searched_(std::move(searched)),
      constraint_count_(cache.constraint_count()) {}

std::vector<double> RelaxedObjective::physical(const std::vector<double>& u) const {
  std::vector<double> x = base_;
  for (std::size_t j = 0; j < searched_.size(); ++j) x[searched_[j]] = space_.to_physical(searched_[j], u[j]);
  return x;
}

std::vector<double> RelaxedObjective::unit(const std::vector<double>& x) const {
  std::vector<double> u(searched_.size());
  for (std::size_t j = 0; j < searched_.size(); ++j) u[j] = space_.to_unit(searched_[j], x[searched_[j]]);
  return u;
}

std::vector<RelaxedObjective::Corner> RelaxedObjective::corners(const std::vector<double>& u) const {
  std::vector<double> x = physical(u);
  // Fractional searched integers: (index, fraction), x set to the floor.
  std::vector<std::pair<std::size_t, double>> fractional;
  for (std::size_t i : searched_) {
    if (space_.variable(i).kind != VariableKind::integer) continue;
    const double fl = std::floor(x[i]);
    double f = x[i] - fl;
    if (f < 1e-9) {
      x[i] = fl;
    } else if (f > 1 - 1e-9) {
      x[i] = fl + 1;
    } else {
      x[i] = fl;
      fractional.emplace_back(i, f);
    }
  }
  std::stable_sort(fractional.begin(), fractional.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  std::vector<Corner> out;
  double previous = 1;
  for (std::size_t j = 0; j <= fractional.size(); ++j) {
    const double next = j < fractional.size() ? fractional[j].second : 0.0;
    if (previous - next > 0) out.push_back({x, previous - next});
    if (j < fractional.size()) x[fractional[j].first] += 1;
    previous = next;
  }
  return out;
}

void RelaxedObjective::prefetch(const std::vector<std::vector<double>>& us) {
  std::vector<std::vector<double>> designs;
  for (const auto& u : us)
    for (Corner& c : corners(u)) designs.push_back(std::move(c.x));
  cache_.prefetch(designs);
}

Evaluation RelaxedObjective::operator()(const std::vector<double>& u) {
  const std::vector<Corner> lattice = corners(u);
  Evaluation result;
  result.objective = 0;
  result.constraints.assign(constraint_count_, 0.0);
  for (const Corner& corner : lattice) {
    Evaluation e = cache_.evaluate(corner.x);  // every corner, even after a failed one: each is cached
    if (!result.ok) continue;
    if (!e.ok) {
      result.ok = false;
      result.failure_reason = e.failure_reason;
      continue;
    }
    result.objective += corner.weight * e.objective;
    for (std::size_t c = 0; c < e.constraints.size(); ++c) result.constraints[c] += corner.weight * e.constraints[c];
  }
  if (!result.ok) {
    result.objective = 0;
    result.constraints.clear();
    if (lattice.size() > 1) result.failure_reason = "integer-lattice corner failed: " + result.failure_reason;
    return result;
  }

  // Statistics for penalties and the relaxed best.
  if (!seen_ok_) {
    f_min_ = f_max_ = result.objective;
    g_max_ = result.constraints;
    seen_ok_ = true;
  } else {
    f_min_ = std::min(f_min_, result.objective);
    f_max_ = std::max(f_max_, result.objective);
    for (std::size_t c = 0; c < g_max_.size() && c < result.constraints.size(); ++c)
      g_max_[c] = std::max(g_max_[c], result.constraints[c]);
  }
  if (!has_best_ || better(result, best_value_, cache_.constraint_tolerance())) {
    has_best_ = true;
    best_u_ = u;
    for (double& v : best_u_) v = std::clamp(v, 0.0, 1.0);
    best_value_ = result;
  }
  return result;
}

double RelaxedObjective::penalty_objective() const {
  if (!seen_ok_) return 1e6;
  return f_max_ + std::max(1.0, f_max_ - f_min_);
}

double RelaxedObjective::penalty_constraint(std::size_t i) const {
  const double worst = i < g_max_.size() ? g_max_[i] : 0.0;
  return std::max(0.0, worst) + 1.0;
}

}  // namespace softarm::optimise::detail

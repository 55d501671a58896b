// Forward/backward finite differences in normalised space (see finite_difference.hpp).
#include "engine/optimiser/finite_difference.hpp"

#include <algorithm>

namespace softarm::optimise::detail {

Linearisation linearise(RelaxedObjective& f, const std::vector<double>& u_in, double step) {
  const std::size_t n = f.dimension(), m = f.constraint_count();
  std::vector<double> u = u_in;
  for (double& v : u) v = std::clamp(v, 0.0, 1.0);
  Linearisation lin;
  lin.value = f(u);
  lin.objective_gradient.assign(n, 0.0);
  lin.constraint_jacobian.assign(m * n, 0.0);
  if (!lin.value.ok) {
    lin.failure_reason = lin.value.failure_reason;
    return lin;
  }
  lin.gradient_ok = true;
  // Forward unless that leaves the box (the other side if the first fails, below). The first
  // choices run side by side, before the loop asks for them one by one.
  std::vector<double> forward(n);
  std::vector<std::vector<double>> neighbours;
  for (std::size_t j = 0; j < n; ++j) {
    forward[j] = u[j] + step <= 1.0 ? step : -step;
    neighbours.push_back(u);
    neighbours.back()[j] += forward[j];
  }
  f.prefetch(neighbours);
  for (std::size_t j = 0; j < n; ++j) {
    Evaluation neighbour;
    double h = 0;
    for (double trial : {forward[j], -forward[j]}) {
      if (u[j] + trial < 0.0 || u[j] + trial > 1.0) continue;
      std::vector<double> v = u;
      v[j] += trial;
      neighbour = f(v);
      if (neighbour.ok) {
        h = trial;
        break;
      }
    }
    if (h == 0) {
      lin.gradient_ok = false;
      lin.failure_reason = "no successful finite-difference neighbour in direction " + std::to_string(j) +
                           ": " + neighbour.failure_reason;
      continue;
    }
    lin.objective_gradient[j] = (neighbour.objective - lin.value.objective) / h;
    for (std::size_t i = 0; i < m; ++i)
      lin.constraint_jacobian[i * n + j] = (neighbour.constraints[i] - lin.value.constraints[i]) / h;
  }
  return lin;
}

}  // namespace softarm::optimise::detail

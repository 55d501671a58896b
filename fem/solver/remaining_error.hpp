#pragma once
// How far a Newton iterate may still be from the solution, from how its last two steps contracted.
#include <limits>

namespace softarm::fem {

/// A bound on ‖x_k − x*‖ from the last two steps δ_{k−1} and δ_k (their norms, in any common scale):
/// where they contract, θ = ‖δ_k‖/‖δ_{k−1}‖ ≤ ½, and the steps to come contract at least as fast, those
/// steps sum to at most θ/(1−θ)·‖δ_k‖ (the a-posteriori bound of the contraction-mapping theorem).
/// Newton's contraction only tightens near the solution, its rate being quadratic, so the bound is
/// pessimistic there: the thesis RRA's step to 186 kPa made steps of 7.2e-4 and 1.1e-5 of the
/// displacement, a bound of 1.8e-7, and its next step was 1.2e-10. +∞ where the steps do not contract
/// by half.
inline double remaining_error_bound(double previous_step, double last_step) {
  const double theta = last_step / previous_step;
  if (!(theta <= 0.5)) return std::numeric_limits<double>::infinity();
  return theta / (1 - theta) * last_step;
}

}  // namespace softarm::fem

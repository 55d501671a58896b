#pragma once
// Load following shared by the reduced rods (arm_rod.hpp, spatial_rod.hpp):
// gravity and tip mass first (4 steps, at zero pressure), then the pressures in
// `steps` equal increments, each step halved on failure down to 1/64 of its
// size, and grown back after success. `solve(gravity_fraction,
// pressure_fraction, start)` returns an equilibrium (State has `converged` and
// `diagnosis`); `on_step(pressure_fraction, state)` sees every converged
// pressure step. The returned state is the last converged one; converged=false
// says the path stopped, and why.
#include <functional>
#include <string>
#include <utility>

#include "fem/core/number_text.hpp"

namespace softarm::fem {

template <class State, class Solve>
State follow_rod_load(bool has_weight, int steps, const Solve& solve,
                      const std::function<void(double, const State&)>& on_step) {
  State state;
  bool have = false;
  const auto march = [&](bool gravity_stage, int count) -> bool {
    double done = 0, step = 1.0 / count;
    while (done < 1.0 - 1e-12) {
      const double next = std::min(1.0, done + step);
      State trial = gravity_stage ? solve(next, 0.0, have ? &state : nullptr) : solve(1.0, next, have ? &state : nullptr);
      if (trial.converged) {
        state = std::move(trial);
        have = true;
        done = next;
        if (!gravity_stage && on_step) on_step(done, state);
        step = std::min(step * 1.5, 1.0 / count);
      } else if ((step *= 0.5) < 1.0 / (64.0 * count)) {
        if (!have) state = trial;
        state.converged = false;
        state.diagnosis = (gravity_stage ? "under gravity alone: "
                                         : "beyond " + number_text(100 * done, 3) + " % of the pressures: ") +
                          trial.diagnosis;
        return false;
      }
    }
    return true;
  };
  if (!has_weight || march(true, 4)) march(false, steps);
  return state;
}

}  // namespace softarm::fem

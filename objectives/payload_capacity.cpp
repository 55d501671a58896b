#include "objectives/payload_capacity.hpp"

#include <algorithm>
#include <cmath>
#include "fem/core/angles.hpp"

namespace softarm::objectives {
namespace {
using fem::kDeg;

// One lift state: the tip at the lift angle at pressure p for tip mass m.
struct LiftState {
  double mass = 0, pressure = 0;
  fem::RodState shape;
  bool ok = false;           // an equilibrium at the lift angle exists near the start, at p ≤ p_w
  std::string failure;       // why not
  double reach_margin = 0, sheath_margin = 0;
  bool lifts() const { return ok && reach_margin >= 0 && sheath_margin >= 0; }
};

class PayloadSearch {
 public:
  PayloadSearch(const fem::ArmRod& arm, const PayloadSettings& s) : arm_(arm), s_(s) {
    load_.chamber_pressure_kPa.assign(6, {0.0, 0.0, 0.0});
    load_.gravity_m_s2 = {0.0, -s.gravity_m_s2};
    load_.clamp_angle_rad = -1.5707963267948966;  // hanging
  }

  fem::RodLoad load(double m, double p) const {
    fem::RodLoad l = load_;
    for (int piece : {1, 3, 5}) l.chamber_pressure_kPa[piece] = {0.0, p, p};
    l.tip_mass_kg = m;
    return l;
  }
  double angle(const fem::RodState& st) const { return arm_.tip_rotation(st, load_) * kDeg; }
  fem::RodState solve(double m, double p, const fem::RodState& from) {
    ++solves_;
    return arm_.solve(load(m, p), &from);
  }

  void judge(LiftState& st) const {
    st.reach_margin = std::abs(st.shape.x.back()) / (s_.reach_fraction * arm_.length_mm()) - 1;
    double stretch = 1;
    for (int piece : {1, 3, 5})
      stretch = std::max(stretch, arm_.extremes(st.shape, load(st.mass, st.pressure), piece).sheath_max_stretch);
    st.sheath_margin = 1 - stretch / s_.sheath_allowable_stretch;
  }

  // From a lift state at another mass: the lift state at mass m (secant on the pressure).
  LiftState track(const LiftState& from, double m, bool check_continuity = true) {
    LiftState out;
    out.mass = m;
    const double target = s_.lift_angle_deg, p_max = s_.working_pressure_kPa;
    double p0 = from.pressure;
    fem::RodState st0 = solve(m, p0, from.shape);
    if (!st0.converged || (check_continuity && std::abs(angle(st0) - angle(from.shape)) > 10.0)) {
      out.failure = st0.converged ? "step too large" : "no equilibrium near the last state: " + st0.diagnosis;
      return out;
    }
    // Secant on p; a step that turns the tip by more than 20° jumped across a fold of the pressure
    // path (the arm snaps through): it is halved, and if even a small step jumps, the lift angle
    // cannot be reached quasi-statically.
    double a0 = angle(st0), p1 = std::min(p_max, p0 + 0.02 * p_max);
    fem::RodState st1 = solve(m, p1, st0);
    for (int it = 0; it < 30 && st1.converged; ++it) {
      const double a1 = angle(st1);
      if (std::abs(a1 - a0) > 20.0) {
        if (std::abs(p1 - p0) < 1e-3 * p_max) {
          out.failure = "snap-through: the pressure path folds before the tip reaches the lift angle";
          return out;
        }
        p1 = 0.5 * (p0 + p1);
        st1 = solve(m, p1, st0);
        continue;
      }
      if (std::abs(a1 - target) < 1e-6) break;
      if (p1 >= p_max && a1 < target) {
        out.failure = "the lift angle needs more than the working pressure";
        out.pressure = p1;
        out.shape = st1;
        return out;
      }
      double p2 = a1 == a0 ? p1 + 0.01 * p_max : p1 + (target - a1) * (p1 - p0) / (a1 - a0);
      p2 = std::clamp(p2, std::max(0.0, p1 - 0.05 * p_max), std::min(p_max, p1 + 0.05 * p_max));
      fem::RodState st2 = solve(m, p2, st1);
      // A correction the rod cannot reach from st1 is shortened before it is called a fold: a fold
      // is where even a step of 1e-4 p_w finds no equilibrium, not where the secant's step did.
      for (int halving = 0; halving < 8 && !st2.converged && std::abs(p2 - p1) > 1e-4 * p_max; ++halving) {
        p2 = 0.5 * (p1 + p2);
        st2 = solve(m, p2, st1);
      }
      p0 = p1, a0 = a1, st0 = std::move(st1);
      p1 = p2, st1 = std::move(st2);
    }
    if (!st1.converged || std::abs(angle(st1) - target) > 1e-3) {
      out.failure = st1.converged ? "the pressure correction did not converge (angle " + std::to_string(angle(st1)) +
                                        " deg at " + std::to_string(p1) + " kPa)"
                                  : "fold: " + st1.diagnosis;
      return out;
    }
    out.ok = true;
    out.pressure = p1;
    out.shape = std::move(st1);
    judge(out);
    return out;
  }

  int solves() const { return solves_; }

 private:
  const fem::ArmRod& arm_;
  PayloadSettings s_;
  fem::RodLoad load_;
  int solves_ = 0;
};
}  // namespace

PayloadResult payload_capacity(const fem::ArmRod& arm, const PayloadSettings& s) {
  PayloadResult out;
  PayloadSearch search(arm, s);
  // The unloaded arm: ramp the pressure until the tip reaches the lift angle.
  LiftState low;
  double last_angle = 0, last_p = 0;
  fem::RodState last;
  bool crossed = false;
  const fem::RodState end = arm.follow(search.load(0.0, s.working_pressure_kPa), s.pressure_steps,
                                       [&](double fraction, const fem::RodState& st) {
                                         if (crossed) return;
                                         const double a = search.angle(st), p = fraction * s.working_pressure_kPa;
                                         if (a >= s.lift_angle_deg) {
                                           crossed = true;
                                           low.pressure = last_p + (s.lift_angle_deg - last_angle) * (p - last_p) /
                                                                       (a - last_angle);
                                           low.shape = st;
                                         }
                                         last_angle = a, last_p = p, last = st;
                                       });
  if (!crossed) {
    // Cannot lift its own tip: a negative capacity, the angle deficit over dθ/dm, keeps the
    // constraint informative for the optimiser.
    const double deficit = s.lift_angle_deg - last_angle;
    out.limited_by = end.converged ? "the unloaded arm's tip reaches only " + std::to_string(last_angle) + " deg"
                                   : "the unloaded arm stops short of the working pressure: " + end.diagnosis;
    double slope = -1;
    if (end.converged) {
      const fem::RodState heavier = search.solve(0.05, s.working_pressure_kPa, end);
      if (heavier.converged) slope = std::min(-1e-3, (search.angle(heavier) - last_angle) / 0.05);
    }
    out.capacity_kg = deficit / slope;
    out.x_mm = last.x;
    out.z_mm = last.z;
    out.rod_solves = search.solves();
    return out;
  }
  low = search.track(low, 0.0, false);  // land exactly on the lift angle
  if (!low.lifts()) {
    out.capacity_kg = 0;
    out.limited_by = low.ok ? "even unloaded, the lift holds the tip within " + std::to_string(s.reach_fraction) +
                                  " of the arm's length of the shoulder axis"
                            : low.failure;
    out.rod_solves = search.solves();
    return out;
  }
  // March up in mass, then bisect.
  LiftState high;
  double step = 0.05;
  while (true) {
    LiftState next = search.track(low, low.mass + step);
    if (next.lifts()) {
      low = std::move(next);
      step *= 1.5;
    } else if (next.failure == "step too large" || (!next.ok && next.failure.rfind("no equilibrium", 0) == 0)) {
      step *= 0.5;
      if (step < 1e-4) {
        high = std::move(next);
        break;
      }
    } else {
      high = std::move(next);
      break;
    }
    if (low.mass > 1000) break;
  }
  for (int it = 0; it < 14 && high.mass - low.mass > 1e-3 * std::max(0.1, low.mass); ++it) {
    LiftState mid = search.track(low, 0.5 * (low.mass + high.mass));
    if (mid.lifts()) low = std::move(mid);
    else high = std::move(mid);
  }
  out.capacity_kg = low.mass;
  out.lift_pressure_kPa = low.pressure;
  out.limited_by = high.ok ? (high.reach_margin < 0 ? "the payload's reach falls below the minimum"
                                                    : "the sheath's stretch under the payload")
                           : high.failure;
  out.x_mm = low.shape.x;
  out.z_mm = low.shape.z;
  out.rod_solves = search.solves();
  return out;
}

}  // namespace softarm::objectives

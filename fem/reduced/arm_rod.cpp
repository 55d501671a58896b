#include "fem/reduced/arm_rod.hpp"

#include "fem/reduced/rod_continuation.hpp"
#include "fem/reduced/shooting_root.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <utility>

namespace softarm::fem {
namespace {
double cross(double ax, double az, double bx, double bz) { return ax * bz - az * bx; }
}  // namespace

ArmRod::ArmRod(ArmRodSpec spec)
    : spec_(std::move(spec)), tube_law_(*spec_.tube.law), sheath_law_(*spec_.sheath.law),
      same_law_(spec_.tube.law == spec_.sheath.law), layout_(rod_nodes(spec_)) {
  std::vector<double> tube_area, sheath_area;
  for (const RodLayout::Node& node : layout_.nodes) {
    const RodPiece& piece = spec_.pieces[node.piece];
    sections_.push_back(node.rigid                          ? RodSection{}
                        : piece.kind == RodPiece::Kind::tca ? tca_section(piece.design, node.z, spec_.bend_direction_rad, 48, 6,
                                                                          rings_confine() ? spec_.tube.law.get() : nullptr)
                                                            : rra_section(piece.design.actuator, node.z));
    tube_area.push_back(sections_.back().tube_area + sections_.back().confined_area);
    sheath_area.push_back(sections_.back().sheath_area);
  }
  distribute_masses(layout_, spec_, tube_area, sheath_area);
}

// Confinement needs rings that are rigid next to the tube: ABS is ~10^4 times as stiff as the
// silicones; rings of a silicone (a plain tube in effect) hold nothing.
bool ArmRod::rings_confine() const {
  return spec_.ring_confinement &&
         spec_.rings.law->initial_shear_modulus() > 100 * spec_.tube.law->initial_shear_modulus();
}

double ArmRod::mass_kg() const {
  const RodPartMasses& m = layout_.masses;
  return m.tube + m.rings + m.sheath + m.connectors;
}

std::vector<double> ArmRod::chamber_forces(int j, const RodLoad& load) const {
  const int piece = layout_.nodes[j].piece;
  return chamber_forces_N(spec_.pieces[piece], load.chamber_pressure_kPa.at(piece), sections_[j].chamber_force_area);
}

// One shot: integrates the rod from the clamp with the clamp-section moment m0
// (N·mm). The internal force at each section is the distal weight, known
// without the shape (no other supports); the moment follows m' = −r' × F with
// the implicit trapezoid rule, each interval's end state by fixed-point
// iteration. The tip's moment must vanish: shoot() returns it.
double ArmRod::shoot(double m0, const RodLoad& load, RodState& st, std::string& failure) const {
  const int n = node_count();
  const double gx = load.gravity_m_s2[0], gz = load.gravity_m_s2[1];
  // Distal resultant at each node (N).
  std::vector<double> fx(n), fz(n);
  fx[n - 1] = load.tip_mass_kg * gx;
  fz[n - 1] = load.tip_mass_kg * gz;
  for (int j = n - 2; j >= 0; --j) {
    fx[j] = fx[j + 1] + layout_.interval_mass[j] * gx;
    fz[j] = fz[j + 1] + layout_.interval_mass[j] * gz;
  }
  const double stretch_guess = st.stretch.size() == static_cast<std::size_t>(n) ? st.stretch[0] : 1.0;
  st.theta.resize(n);
  st.stretch.resize(n);
  st.curvature.resize(n);
  st.x.assign(n, 0.0);
  st.z.assign(n, 0.0);
  st.moment.resize(n);
  const auto section = [&](int j, double theta, double m, SectionState guess) -> SectionState {
    if (layout_.nodes[j].rigid) return {1.0, 0.0, true, {}};
    const double axial = fx[j] * std::cos(theta) + fz[j] * std::sin(theta);
    return solve_section(sections_[j], laws(), chamber_forces(j, load), axial, m, guess);
  };
  SectionState s = section(0, load.clamp_angle_rad, m0, {stretch_guess, 0.0, true, {}});
  if (!s.ok) return failure = s.failure, std::nan("");
  st.theta[0] = load.clamp_angle_rad;
  st.stretch[0] = s.stretch;
  st.curvature[0] = s.curvature;
  st.moment[0] = m0;
  for (int j = 0; j + 1 < n; ++j) {
    const double ds = layout_.s[j + 1] - layout_.s[j], w = layout_.interval_mass[j];
    double theta = st.theta[j] + st.curvature[j] * ds, stretch = st.stretch[j], m = st.moment[j];
    SectionState next{stretch, st.curvature[j], true, {}};
    for (int it = 0; it < 30; ++it) {
      const double dx = 0.5 * ds * (st.stretch[j] * std::cos(st.theta[j]) + stretch * std::cos(theta));
      const double dz = 0.5 * ds * (st.stretch[j] * std::sin(st.theta[j]) + stretch * std::sin(theta));
      m = st.moment[j] - cross(dx, dz, fx[j + 1], fz[j + 1]) - cross(0.5 * dx, 0.5 * dz, w * gx, w * gz);
      next = section(j + 1, theta, m, next);
      if (!next.ok) return failure = next.failure, std::nan("");
      const double theta_new = st.theta[j] + 0.5 * ds * (st.curvature[j] + next.curvature);
      const double change = std::abs(theta_new - theta) + std::abs(next.stretch - stretch);
      theta = theta_new;
      stretch = next.stretch;
      st.x[j + 1] = st.x[j] + dx;
      st.z[j + 1] = st.z[j] + dz;
      if (change < 1e-13) break;
    }
    st.theta[j + 1] = theta;
    st.stretch[j + 1] = stretch;
    st.curvature[j + 1] = next.curvature;
    st.moment[j + 1] = m;
  }
  return st.moment[n - 1];
}

RodState ArmRod::solve(const RodLoad& load, const RodState* start) const {
  RodState st;
  std::string failure;
  // Moment scale: the straight rod's weight moment plus the chambers' force couples.
  double scale = 1.0;
  for (int j = 0; j < node_count(); ++j) {
    const auto f = chamber_forces(j, load);
    for (std::size_t k = 0; k < f.size(); ++k) scale = std::max(scale, std::abs(f[k] * sections_[j].chamber_y[k]));
  }
  scale = std::max(scale, (load.tip_mass_kg + mass_kg()) * std::hypot(load.gravity_m_s2[0], load.gravity_m_s2[1]) *
                              length_mm());
  // Secant on the clamp moment, from the previous state's (else the straight rod's weight moment).
  double m0 = 0;
  if (start) {
    m0 = start->moment.front();
  } else {
    const double tx = std::cos(load.clamp_angle_rad), tz = std::sin(load.clamp_angle_rad);
    const double gx = load.gravity_m_s2[0], gz = load.gravity_m_s2[1];
    for (int j = 0; j + 1 < node_count(); ++j) {
      const double arm = 0.5 * (layout_.s[j] + layout_.s[j + 1]);
      m0 += cross(arm * tx, arm * tz, layout_.interval_mass[j] * gx, layout_.interval_mass[j] * gz);
    }
    m0 += cross(length_mm() * tx, length_mm() * tz, load.tip_mass_kg * gx, load.tip_mass_kg * gz);
  }
  if (start) {
    st = *start;  // its shape is the warm start; its verdict is not ours
    st.converged = false;
    st.diagnosis.clear();
  }
  // The tip moment as a function of the clamp moment; its root (shooting_root.hpp, which
  // explains why a bracket is kept) leaves its shape in st.
  std::string last_failure;
  const auto tip_moment = [&](double m) {
    const double f = shoot(m, load, st, failure);
    if (!std::isfinite(f)) last_failure = failure;
    return f;
  };
  ShootingSettings settings;
  settings.scale = scale;
  const ShootingRoot root = shooting_root(tip_moment, m0, settings);
  st.newton_iterations = root.evaluations;
  if (root.converged) {
    st.converged = true;
    return st;
  }
  st.diagnosis = std::isfinite(root.f) || last_failure.empty()
                     ? "no equilibrium found near the previous state (the tip moment does not vanish): limit point"
                     : "section failure: " + last_failure;
  return st;
}

RodState ArmRod::follow(const RodLoad& load, int steps,
                        const std::function<void(double, const RodState&)>& on_step) const {
  const auto solve_at = [&](double gravity_fraction, double pressure_fraction, const RodState* start) {
    RodLoad l = load;
    for (auto& p : l.chamber_pressure_kPa)
      for (double& v : p) v *= pressure_fraction;
    l.gravity_m_s2 = {load.gravity_m_s2[0] * gravity_fraction, load.gravity_m_s2[1] * gravity_fraction};
    return solve(l, start);
  };
  const bool loaded = std::abs(load.gravity_m_s2[0]) + std::abs(load.gravity_m_s2[1]) > 0 || load.tip_mass_kg > 0;
  return follow_rod_load<RodState>(loaded, steps, solve_at, on_step);
}

PieceExtremes ArmRod::extremes(const RodState& s, const RodLoad& load, int piece) const {
  PieceExtremes e;
  bool first = true;
  for (int j = 0; j < node_count(); ++j) {
    if (layout_.nodes[j].piece != piece || layout_.nodes[j].rigid) continue;
    const SectionState st{s.stretch[j], s.curvature[j], true, {}};
    e.widen(fibre_extremes(sections_[j], st), first);
    for (std::size_t k = 0; k < sections_[j].chamber_y.size(); ++k)
      if (load.chamber_pressure_kPa.at(piece)[k] > 0)
        e.chamber_max_stretch =
            std::max(e.chamber_max_stretch, s.stretch[j] - s.curvature[j] * sections_[j].chamber_y[k]);
    first = false;
  }
  return e;
}

}  // namespace softarm::fem

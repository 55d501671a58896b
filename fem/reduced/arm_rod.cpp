#include "fem/reduced/arm_rod.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <utility>

namespace softarm::fem {
namespace {
constexpr double kMm3ToKgPerGcm3 = 1e-6;  // mm³ × g/cm³ → kg

double cross(double ax, double az, double bx, double bz) { return ax * bz - az * bx; }

// Trapezoid integral of f over the nodes [a, b].
template <class F>
double trapezoid(const std::vector<double>& s, int a, int b, F f) {
  double sum = 0;
  for (int j = a; j < b; ++j) sum += 0.5 * (s[j + 1] - s[j]) * (f(j) + f(j + 1));
  return sum;
}
}  // namespace

double ForceFactor::at(double p) const {
  if (pressure_kPa.empty()) return 1.0;
  if (p <= pressure_kPa.front()) return factor.front();
  for (std::size_t i = 1; i < pressure_kPa.size(); ++i)
    if (p <= pressure_kPa[i]) {
      const double t = (p - pressure_kPa[i - 1]) / (pressure_kPa[i] - pressure_kPa[i - 1]);
      return (1 - t) * factor[i - 1] + t * factor[i];
    }
  return factor.back();
}

ArmRod::ArmRod(ArmRodSpec spec)
    : spec_(std::move(spec)), tube_law_(*spec_.tube.law), sheath_law_(*spec_.sheath.law),
      same_law_(spec_.tube.law == spec_.sheath.law) {
  double s0 = 0;
  for (int p = 0; p < static_cast<int>(spec_.pieces.size()); ++p) {
    const RodPiece& piece = spec_.pieces[p];
    const int first = static_cast<int>(nodes_.size());
    if (piece.kind == RodPiece::Kind::connector) {
      for (double s : {s0, s0 + piece.length_mm}) {
        nodes_.push_back({p, true, {}});
        s_.push_back(s);
      }
      interval_mass_.resize(nodes_.size() - 1, 0.0);
      interval_mass_.back() = piece.mass_kg;
      masses_.connectors += piece.mass_kg;
      s0 += piece.length_mm;
      continue;
    }
    const RraDesign& a = piece.design.actuator;
    // Three zones (top cap, chamber, bottom cap) meshed separately, with a node on each side of
    // the zone boundaries (ΔS = 0 between them): the section jumps there (solid cap vs hollow
    // chamber), and the trapezoid rule keeps its second order only on smooth zones.
    const double l = a.length_mm, tc = a.end_cap_thickness_mm;
    const int n = std::max(5, spec_.nodes_per_segment);
    const int cap_nodes = std::max(2, static_cast<int>(std::lround(n * tc / l)) + 1);
    const std::array<std::array<double, 2>, 3> zones{{{0.0, tc}, {tc, l - tc}, {l - tc, l}}};  // in local s = l − z
    for (int k = 0; k < 3; ++k) {
      const int count = k == 1 ? std::max(3, n - 2 * cap_nodes) : cap_nodes;
      const double eps = 1e-9 * l;  // evaluate the section just inside the zone
      for (int i = 0; i < count; ++i) {
        const double local = zones[k][0] + (zones[k][1] - zones[k][0]) * i / (count - 1);
        const double z = std::clamp(l - local, l - zones[k][1] + eps, l - zones[k][0] - eps);
        nodes_.push_back({p, false,
                          piece.kind == RodPiece::Kind::tca ? tca_section(piece.design, z, spec_.bend_direction_rad)
                                                            : rra_section(a, z)});
        s_.push_back(s0 + local);
      }
    }
    // Exact part masses (rra_design.hpp), distributed along the piece as its section areas are.
    const double count = piece.kind == RodPiece::Kind::tca ? 3.0 : 1.0;
    const double tube = count * tube_volume_mm3(a) * spec_.tube.density_g_cm3 * kMm3ToKgPerGcm3;
    const double rings = count * ring_volume_mm3(a) * spec_.rings.density_g_cm3 * kMm3ToKgPerGcm3;
    const int last = static_cast<int>(nodes_.size()) - 1;
    const auto tube_area = [&](int j) { return nodes_[j].section.tube_area; };
    const auto sheath_area = [&](int j) { return nodes_[j].section.sheath_area; };
    // The rings sit half in the tube's grooves, half in the core: the core loses that half.
    const double sheath_volume =
        std::max(0.0, trapezoid(s_, first, last, sheath_area) - 0.5 * count * ring_volume_mm3(a));
    const double sheath = sheath_volume * spec_.sheath.density_g_cm3 * kMm3ToKgPerGcm3;
    const double tube_total = trapezoid(s_, first, last, tube_area);
    const double sheath_total = trapezoid(s_, first, last, sheath_area);
    interval_mass_.resize(nodes_.size() - 1, 0.0);
    for (int j = first; j < last; ++j) {
      const double ds = s_[j + 1] - s_[j];
      double m = tube * 0.5 * ds * (tube_area(j) + tube_area(j + 1)) / tube_total + rings * ds / a.length_mm;
      if (sheath_total > 0) m += sheath * 0.5 * ds * (sheath_area(j) + sheath_area(j + 1)) / sheath_total;
      interval_mass_[j] = m;
    }
    masses_.tube += tube;
    masses_.rings += rings;
    masses_.sheath += sheath;
    s0 += a.length_mm;
  }
  interval_mass_.resize(std::max<std::size_t>(1, nodes_.size()) - 1, 0.0);
}

double ArmRod::mass_kg() const { return masses_.tube + masses_.rings + masses_.sheath + masses_.connectors; }

std::vector<double> ArmRod::chamber_forces(int j, const RodLoad& load) const {
  const Node& node = nodes_[j];
  const RodPiece& piece = spec_.pieces[node.piece];
  std::vector<double> f(node.section.chamber_force_area.size(), 0.0);
  for (std::size_t k = 0; k < f.size(); ++k) {
    const double p = load.chamber_pressure_kPa.at(node.piece)[k];
    f[k] = piece.force_factor.at(p) * p * 1e-3 * node.section.chamber_force_area[k];  // kPa → MPa; MPa·mm² = N
  }
  return f;
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
    fx[j] = fx[j + 1] + interval_mass_[j] * gx;
    fz[j] = fz[j + 1] + interval_mass_[j] * gz;
  }
  const double stretch_guess = st.stretch.size() == static_cast<std::size_t>(n) ? st.stretch[0] : 1.0;
  st.theta.resize(n);
  st.stretch.resize(n);
  st.curvature.resize(n);
  st.x.assign(n, 0.0);
  st.z.assign(n, 0.0);
  st.moment.resize(n);
  const auto section = [&](int j, double theta, double m, SectionState guess) -> SectionState {
    if (nodes_[j].rigid) return {1.0, 0.0, true, {}};
    const double axial = fx[j] * std::cos(theta) + fz[j] * std::sin(theta);
    return solve_section(nodes_[j].section, laws(), chamber_forces(j, load), axial, m, guess);
  };
  SectionState s = section(0, load.clamp_angle_rad, m0, {stretch_guess, 0.0, true, {}});
  if (!s.ok) return failure = s.failure, std::nan("");
  st.theta[0] = load.clamp_angle_rad;
  st.stretch[0] = s.stretch;
  st.curvature[0] = s.curvature;
  st.moment[0] = m0;
  for (int j = 0; j + 1 < n; ++j) {
    const double ds = s_[j + 1] - s_[j], w = interval_mass_[j];
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
    for (std::size_t k = 0; k < f.size(); ++k) scale = std::max(scale, std::abs(f[k] * nodes_[j].section.chamber_y[k]));
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
      const double arm = 0.5 * (s_[j] + s_[j + 1]);
      m0 += cross(arm * tx, arm * tz, interval_mass_[j] * gx, interval_mass_[j] * gz);
    }
    m0 += cross(length_mm() * tx, length_mm() * tz, load.tip_mass_kg * gx, load.tip_mass_kg * gz);
  }
  if (start) st = *start;
  double f0 = shoot(m0, load, st, failure);
  if (!std::isfinite(f0)) {
    st.diagnosis = "section failure: " + failure;
    return st;
  }
  double m1 = m0 + 1e-4 * scale, f1 = shoot(m1, load, st, failure);
  for (int it = 0; it < 80; ++it) {
    st.newton_iterations = it + 1;
    // A trial moment that breaks a section (a fibre outside its table, a section past its
    // limit point) is an overshoot: back off towards the last good one.
    for (int k = 0; k < 40 && !std::isfinite(f1); ++k) {
      m1 = 0.5 * (m0 + m1);
      f1 = shoot(m1, load, st, failure);
    }
    if (!std::isfinite(f1)) {
      st.diagnosis = "section failure: " + failure;
      return st;
    }
    if (std::abs(f1) < 1e-10 * scale) {
      st.converged = true;
      return st;
    }
    if (f1 == f0) break;
    double m2 = m1 - f1 * (m1 - m0) / (f1 - f0);
    const double limit = 0.5 * scale;  // no jump larger than half the moment scale per iteration
    m2 = std::clamp(m2, m1 - limit, m1 + limit);
    m0 = m1, f0 = f1, m1 = m2;
    f1 = shoot(m1, load, st, failure);
  }
  st.diagnosis = "no equilibrium found near the previous state (the tip moment does not vanish): limit point";
  return st;
}

RodState ArmRod::follow(const RodLoad& load, int steps,
                        const std::function<void(double, const RodState&)>& on_step) const {
  // Stage 1: gravity and tip mass at zero pressure (4 steps); stage 2: the pressures.
  const auto at = [&](double gravity_fraction, double pressure_fraction) {
    RodLoad l = load;
    for (auto& p : l.chamber_pressure_kPa)
      for (double& v : p) v *= pressure_fraction;
    l.gravity_m_s2 = {load.gravity_m_s2[0] * gravity_fraction, load.gravity_m_s2[1] * gravity_fraction};
    l.tip_mass_kg = load.tip_mass_kg;
    return l;
  };
  RodState state;
  bool have = false;
  const auto march = [&](bool gravity_stage, int count) -> bool {
    double done = 0, step = 1.0 / count;
    while (done < 1.0 - 1e-12) {
      const double next = std::min(1.0, done + step);
      const RodLoad l = gravity_stage ? at(next, 0.0) : at(1.0, next);
      RodState trial = solve(l, have ? &state : nullptr);
      if (trial.converged) {
        state = std::move(trial);
        have = true;
        done = next;
        if (!gravity_stage && on_step) on_step(done, state);
        step = std::min(step * 1.5, 1.0 / count);
      } else if ((step *= 0.5) < 1.0 / (64.0 * count)) {
        if (!have) state = trial;
        state.converged = false;
        state.diagnosis = (gravity_stage ? "under gravity alone: " : "at " + std::to_string(done) + " of the pressure: ") +
                          trial.diagnosis;
        return false;
      }
    }
    return true;
  };
  const bool loaded = std::abs(load.gravity_m_s2[0]) + std::abs(load.gravity_m_s2[1]) > 0 || load.tip_mass_kg > 0;
  if (!loaded || march(true, 4)) march(false, steps);
  return state;
}

PieceExtremes ArmRod::extremes(const RodState& s, const RodLoad& load, int piece) const {
  PieceExtremes e;
  bool first = true;
  for (int j = 0; j < node_count(); ++j) {
    if (nodes_[j].piece != piece || nodes_[j].rigid) continue;
    const SectionState st{s.stretch[j], s.curvature[j], true, {}};
    const FibreExtremes f = fibre_extremes(nodes_[j].section, st);
    e.tube_max_stretch = first ? f.tube_max : std::max(e.tube_max_stretch, f.tube_max);
    e.tube_min_stretch = first ? f.tube_min : std::min(e.tube_min_stretch, f.tube_min);
    e.sheath_max_stretch = first ? f.sheath_max : std::max(e.sheath_max_stretch, f.sheath_max);
    e.sheath_min_stretch = first ? f.sheath_min : std::min(e.sheath_min_stretch, f.sheath_min);
    for (std::size_t k = 0; k < nodes_[j].section.chamber_y.size(); ++k)
      if (load.chamber_pressure_kPa.at(piece)[k] > 0)
        e.chamber_max_stretch =
            std::max(e.chamber_max_stretch, s.stretch[j] - s.curvature[j] * nodes_[j].section.chamber_y[k]);
    first = false;
  }
  return e;
}

}  // namespace softarm::fem

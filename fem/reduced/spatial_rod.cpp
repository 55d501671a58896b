#include "fem/reduced/spatial_rod.hpp"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <utility>

#include "fem/reduced/rod_continuation.hpp"
#include "fem/reduced/rotation_vector.hpp"
#include "fem/reduced/rod_section.hpp"
#include "fem/core/angles.hpp"

namespace softarm::fem {
namespace {
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
}  // namespace

Mat3 hanging_rod_frame() {
  Mat3 r;
  r.col(0) = Vec3::UnitX();
  r.col(1) = -Vec3::UnitY();
  r.col(2) = -Vec3::UnitZ();
  return r;
}

SpatialRod::SpatialRod(ArmRodSpec spec, int cells)
    : spec_(std::move(spec)), tube_law_(*spec_.tube.law), sheath_law_(*spec_.sheath.law),
      same_law_(spec_.tube.law == spec_.sheath.law), layout_(rod_nodes(spec_)) {
  std::vector<double> tube_area, sheath_area;
  for (const RodLayout::Node& node : layout_.nodes) {
    const RodPiece& piece = spec_.pieces[node.piece];
    if (piece.kind == RodPiece::Kind::rra)
      throw std::invalid_argument("SpatialRod: a lone RRA does not bend; use the planar rod (arm_rod.hpp)");
    sections_.push_back(node.rigid ? CellSection{} : tca_cell_section(piece.design, node.z, cells));
    const CellSection& s = sections_.back();
    double gj = 0;
    for (const FibreCell& c : s.cells)
      gj += (c.tube_area * tube_law_.initial_modulus() + c.sheath_area * sheath_law_.initial_modulus()) *
            c.xi.squaredNorm() / 3;
    torsion_Nmm2_.push_back(gj);
    // Masses from the exact strip areas, so that both rods weigh the same.
    const RodSection exact = node.rigid ? RodSection{} : tca_section(piece.design, node.z, 0.0);
    tube_area.push_back(exact.tube_area);
    sheath_area.push_back(exact.sheath_area);
  }
  distribute_masses(layout_, spec_, tube_area, sheath_area);
}

double SpatialRod::mass_kg() const {
  const RodPartMasses& m = layout_.masses;
  return m.tube + m.rings + m.sheath + m.connectors;
}

// One shot from the clamp moment m0 (N·mm, scene frame); returns the moment left at the free tip.
Vec3 SpatialRod::shoot(const Vec3& m0, const SpatialRodLoad& load, SpatialRodState& st, std::string& failure) const {
  const int n = node_count();
  const Vec3 g = load.gravity_m_s2;  // kg · m/s² = N
  std::vector<Vec3> weight_beyond(n);  // n(S) at each node: the distal weight, N
  weight_beyond[n - 1] = load.tip_mass_kg * g;
  for (int j = n - 2; j >= 0; --j) weight_beyond[j] = weight_beyond[j + 1] + layout_.interval_mass[j] * g;
  std::vector<double> start_stretch = st.stretch;
  std::vector<Vec3> start_curvature = st.curvature;
  const bool warm = static_cast<int>(start_stretch.size()) == n;
  st.position.assign(n, load.clamp_position_mm);
  st.frame.assign(n, load.clamp_frame);
  st.stretch.assign(n, 1.0);
  st.curvature.assign(n, Vec3::Zero());
  st.moment.assign(n, m0);

  // Section j's stretch and curvature under the moment m (scene frame), with frame R.
  const auto section = [&](int j, const Mat3& r, const Vec3& m, double& stretch, Vec3& curvature) -> bool {
    if (layout_.nodes[j].rigid) {
      stretch = 1.0;
      curvature.setZero();
      return true;
    }
    const int piece = layout_.nodes[j].piece;
    const Vec3 local = r.transpose() * m;
    BiaxialSectionState guess{stretch, Eigen::Vector2d(-curvature.y(), curvature.x()), true, {}};
    const BiaxialSectionState s = solve_biaxial_section(
        sections_[j], laws(), chamber_forces_N(spec_.pieces[piece], load.chamber_pressure_kPa.at(piece), sections_[j].chamber_force_area),
        weight_beyond[j].dot(r.col(2)), Eigen::Vector2d(-local.y(), local.x()), guess);
    if (!s.ok) {
      failure = s.failure;
      return false;
    }
    stretch = s.stretch;
    curvature = Vec3(s.gradient.y(), -s.gradient.x(), local.z() / torsion_Nmm2_[j]);
    return true;
  };
  const auto fail = [&] { return Vec3::Constant(std::nan("")); };
  if (warm) st.stretch[0] = start_stretch[0], st.curvature[0] = start_curvature[0];
  if (!section(0, st.frame[0], m0, st.stretch[0], st.curvature[0])) return fail();
  for (int j = 0; j + 1 < n; ++j) {
    const double ds = layout_.s[j + 1] - layout_.s[j];
    const Vec3 w = layout_.interval_mass[j] * g;
    double stretch = warm ? start_stretch[j + 1] : st.stretch[j];
    Vec3 curvature = warm ? start_curvature[j + 1] : st.curvature[j];
    for (int it = 0; it < 30; ++it) {
      const Mat3 r = st.frame[j] * rotation_exp(0.5 * ds * (st.curvature[j] + curvature));
      const Vec3 dr = 0.5 * ds * (st.stretch[j] * st.frame[j].col(2) + stretch * r.col(2));
      const Vec3 m = st.moment[j] - dr.cross(weight_beyond[j + 1]) - (0.5 * dr).cross(w);
      const double old_stretch = stretch;
      const Vec3 old_curvature = curvature;
      if (!section(j + 1, r, m, stretch, curvature)) return fail();
      st.frame[j + 1] = r;
      st.position[j + 1] = st.position[j] + dr;
      st.moment[j + 1] = m;
      const double change = std::abs(stretch - old_stretch) + ds * (curvature - old_curvature).norm();
      if (change < 1e-13) break;
    }
    // The frame, position and moment stored above belong to the last curvature but one: redo them once converged.
    st.stretch[j + 1] = stretch;
    st.curvature[j + 1] = curvature;
    st.frame[j + 1] = st.frame[j] * rotation_exp(0.5 * ds * (st.curvature[j] + curvature));
    const Vec3 dr = 0.5 * ds * (st.stretch[j] * st.frame[j].col(2) + stretch * st.frame[j + 1].col(2));
    st.position[j + 1] = st.position[j] + dr;
    st.moment[j + 1] = st.moment[j] - dr.cross(weight_beyond[j + 1]) - (0.5 * dr).cross(w);
  }
  return st.moment[n - 1];
}

SpatialRodState SpatialRod::solve(const SpatialRodLoad& load, const SpatialRodState* start) const {
  const int n = node_count();
  // Moment scale: the chambers' force couples and the straight rod's weight moment.
  double scale = 1.0;
  for (int j = 0; j < n; ++j) {
    const int piece = layout_.nodes[j].piece;
    if (layout_.nodes[j].rigid) continue;
    const auto f = chamber_forces_N(spec_.pieces[piece], load.chamber_pressure_kPa.at(piece), sections_[j].chamber_force_area);
    for (std::size_t k = 0; k < f.size(); ++k) scale = std::max(scale, std::abs(f[k]) * sections_[j].chamber_xi[k].norm());
  }
  scale = std::max(scale, (load.tip_mass_kg + mass_kg()) * load.gravity_m_s2.norm() * layout_.s.back());
  Vec3 m0 = Vec3::Zero();
  if (start && !start->moment.empty()) {
    m0 = start->moment.front();
  } else {  // the straight rod's weight moment about the clamp
    const Vec3 axis = load.clamp_frame.col(2);
    for (int j = 0; j + 1 < n; ++j)
      m0 += (0.5 * (layout_.s[j] + layout_.s[j + 1]) * axis).cross(layout_.interval_mass[j] * load.gravity_m_s2);
    m0 += (layout_.s.back() * axis).cross(load.tip_mass_kg * load.gravity_m_s2);
  }
  SpatialRodState st;
  if (start) {
    st = *start;  // its shape is the warm start; its verdict is not ours
    st.converged = false;
    st.diagnosis.clear();
  }
  std::string failure;
  Vec3 f0 = shoot(m0, load, st, failure);
  if (!f0.allFinite()) {
    st.diagnosis = "section failure: " + failure;
    return st;
  }
  const double h = 1e-6 * scale;
  for (int it = 0; it < 60; ++it) {
    st.newton_iterations = it + 1;
    if (f0.norm() < 1e-10 * scale) {
      st.converged = true;
      return st;
    }
    // Finite-difference Jacobian of the tip moment with respect to the clamp moment.
    Mat3 jac;
    for (int c = 0; c < 3; ++c) {
      SpatialRodState probe = st;
      const Vec3 fc = shoot(m0 + h * Vec3::Unit(c), load, probe, failure);
      if (!fc.allFinite()) {
        st.diagnosis = "section failure next to the equilibrium: " + failure + " (limit point)";
        return st;
      }
      jac.col(c) = (fc - f0) / h;
    }
    Vec3 step = jac.fullPivLu().solve(-f0);
    if (!step.allFinite()) break;
    if (step.norm() > 0.5 * scale) step *= 0.5 * scale / step.norm();  // no jump beyond half the moment scale
    // Halve a step whose shot breaks a section or does not lower the tip moment.
    bool accepted = false;
    for (int k = 0; k < 30 && !accepted; ++k, step *= 0.5) {
      SpatialRodState trial = st;
      const Vec3 f1 = shoot(m0 + step, load, trial, failure);
      if (f1.allFinite() && f1.norm() < f0.norm()) {
        m0 += step;
        f0 = f1;
        st = std::move(trial);
        accepted = true;
      }
    }
    if (!accepted) break;
  }
  st.diagnosis = "no equilibrium found near the previous state (the tip moment does not vanish): limit point";
  return st;
}

SpatialRodState SpatialRod::follow(const SpatialRodLoad& load, int steps,
                                   const std::function<void(double, const SpatialRodState&)>& on_step) const {
  const auto solve_at = [&](double gravity_fraction, double pressure_fraction, const SpatialRodState* start) {
    SpatialRodLoad l = load;
    for (auto& p : l.chamber_pressure_kPa)
      for (double& v : p) v *= pressure_fraction;
    l.gravity_m_s2 = load.gravity_m_s2 * gravity_fraction;
    return solve(l, start);
  };
  const bool loaded = load.gravity_m_s2.norm() > 0 || load.tip_mass_kg > 0;
  return follow_rod_load<SpatialRodState>(loaded, steps, solve_at, on_step);
}

double SpatialRod::tilt_deg(const SpatialRodState& s, const SpatialRodLoad& load, int node) const {
  const double c = std::clamp(s.frame[node].col(2).dot(load.clamp_frame.col(2)), -1.0, 1.0);
  return std::acos(c) * kDeg;
}

PieceExtremes SpatialRod::extremes(const SpatialRodState& s, const SpatialRodLoad& load, int piece) const {
  PieceExtremes e;
  bool first = true;
  for (int j = 0; j < node_count(); ++j) {
    if (layout_.nodes[j].piece != piece || layout_.nodes[j].rigid) continue;
    const BiaxialSectionState st{s.stretch[j], Eigen::Vector2d(-s.curvature[j].y(), s.curvature[j].x()), true, {}};
    e.widen(fibre_extremes(sections_[j], st), first);
    for (std::size_t k = 0; k < sections_[j].chamber_xi.size(); ++k)
      if (load.chamber_pressure_kPa.at(piece)[k] > 0)
        e.chamber_max_stretch = std::max(e.chamber_max_stretch, st.stretch + st.gradient.dot(sections_[j].chamber_xi[k]));
    first = false;
  }
  return e;
}

}  // namespace softarm::fem

#include "fem/reduced/spatial_cell_rod.hpp"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "fem/core/number_text.hpp"
#include "fem/reduced/cell_interpolation.hpp"
#include "fem/reduced/rotation_vector.hpp"

namespace softarm::fem {
namespace {
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

/// One interval's section at the load level: free response and compliances.
struct IntervalSection {
  Vec3 free_curvature = Vec3::Zero();  // material frame
  double free_stretch = 1;
  Eigen::Matrix2d bending = Eigen::Matrix2d::Zero();
  double axial = 0, torsion = 0;       // compliances: 1/N, 1/(N·mm²)
  double length = 0, mass = 0;
};

/// A piece's intervals: their count and length (at most the spec's interval).
int interval_count(const SpatialCellRodSpec& spec, const SpatialCellPiece& piece) {
  return std::max(1, static_cast<int>(std::ceil(piece.length_mm / spec.interval_mm - 1e-9)));
}

/// The mass of each interval of a piece (kg): a connector's spread evenly, a segment's from its
/// cells' mass per length (Lagrange in height), whatever their tables reached.
std::vector<double> interval_masses(const SpatialCellRodSpec& spec, const SpatialCellPiece& piece) {
  const int n = interval_count(spec, piece);
  const double dz = piece.length_mm / n;
  if (piece.cells.empty()) return std::vector<double>(n, piece.mass_kg / n);
  std::vector<double> z, mass, out;
  for (const SpatialCellTable& c : piece.cells) z.push_back(c.z_mm), mass.push_back(c.mass_per_length_kg_per_mm);
  for (int i = 0; i < n; ++i) out.push_back(lagrange(z, mass, piece.length_mm - (i + 0.5) * dz) * dz);
  return out;
}

/// The pieces' intervals at level t; an empty string when every cell's table covers t.
std::string sections_at(const SpatialCellRodSpec& spec, double t, std::vector<IntervalSection>& out,
                        std::vector<int>& first_interval) {
  out.clear();
  first_interval.clear();
  for (const SpatialCellPiece& piece : spec.pieces) {
    first_interval.push_back(static_cast<int>(out.size()));
    const int n = interval_count(spec, piece);
    const double dz = piece.length_mm / n;
    const std::vector<double> masses = interval_masses(spec, piece);
    if (piece.cells.empty()) {
      for (int i = 0; i < n; ++i) out.push_back({Vec3::Zero(), 1, Eigen::Matrix2d::Zero(), 0, 0, dz, masses[i]});
      continue;
    }
    std::vector<double> z, stretch, axial, torsion;
    std::vector<Eigen::Vector2d> curvature;
    std::vector<Eigen::Matrix2d> bending;
    for (const SpatialCellTable& c : piece.cells) {
      const auto l = along_ramp(c.level, c.stretch, t);
      const auto k = along_ramp(c.level, c.curvature_per_mm, t);
      const auto b = along_ramp(c.level, c.bending_compliance_per_Nmm2, t);
      const auto a = along_ramp(c.level, c.axial_compliance_per_N, t);
      if (!l || !k || !b || !a)
        return "the cell at z = " + number_text(c.z_mm) + " mm reached " +
               number_text(c.level.empty() ? 0.0 : c.level.back()) + " of its pressures only";
      z.push_back(c.z_mm), stretch.push_back(*l), curvature.push_back(*k), bending.push_back(*b);
      axial.push_back(*a), torsion.push_back(c.torsion_compliance_per_Nmm2);
    }
    // The ends' own turn and stretch per unit length, over their lengths from z = 0 and z = length.
    struct EndRate {
      double z0, z1;
      Eigen::Vector2d curvature;
      double stretch, torsion;  // torsion: 1/GJ over the end, 0 where the cells' holds
    };
    std::vector<EndRate> ends;
    for (const SpatialEndTable& e : piece.ends) {
      const auto turn = along_ramp(e.level, e.rotation_rad, t);
      const auto longer = along_ramp(e.level, e.elongation_mm, t);
      if (!turn || !longer)
        return std::string("the end cell at the segment's ") + (e.at_top ? "top" : "bottom") + " reached " +
               number_text(e.level.empty() ? 0.0 : e.level.back()) + " of its pressures only";
      const double z0 = e.at_top ? piece.length_mm - e.length_mm : 0.0;
      ends.push_back({z0, z0 + e.length_mm, *turn / e.length_mm, 1 + *longer / e.length_mm,
                      e.twist_compliance_per_Nmm / e.length_mm});
    }
    // From the piece's top (its z = length) down.
    for (int i = 0; i < n; ++i) {
      const double zi = piece.length_mm - (i + 0.5) * dz;
      const bool cap = zi < piece.cap_mm || zi > piece.length_mm - piece.cap_mm;
      IntervalSection s;
      Eigen::Vector2d k = Eigen::Vector2d::Zero();
      if (!cap) {
        k = lagrange(z, curvature, zi);
        s.free_stretch = lagrange(z, stretch, zi);
      }
      s.torsion = lagrange(z, torsion, zi);
      for (const EndRate& e : ends) {  // the share of the interval inside an end takes the end's rates
        const double share = overlap_share(zi, dz, e.z0, e.z1);
        k = share * e.curvature + (1 - share) * k;
        s.free_stretch = share * e.stretch + (1 - share) * s.free_stretch;
        if (e.torsion > 0) s.torsion = share * e.torsion + (1 - share) * s.torsion;
      }
      s.free_curvature = Vec3(k.x(), k.y(), 0);
      s.bending = lagrange(z, bending, zi);
      s.axial = lagrange(z, axial, zi);
      s.length = dz;
      s.mass = masses[i];
      out.push_back(s);
    }
  }
  return {};
}
}  // namespace

double spatial_cell_rod_length_mm(const SpatialCellRodSpec& spec) {
  double l = 0;
  for (const auto& p : spec.pieces) l += p.length_mm;
  return l;
}

double spatial_cell_rod_twist_compliance(const SpatialCellRodSpec& spec, std::size_t piece) {
  if (piece >= spec.pieces.size()) return std::nan("");
  std::vector<IntervalSection> sec;
  std::vector<int> first;
  if (std::string why = sections_at(spec, 0.0, sec, first); !why.empty()) return std::nan("");
  const int end = piece + 1 < spec.pieces.size() ? first[piece + 1] : static_cast<int>(sec.size());
  double c = 0;
  for (int i = first[piece]; i < end; ++i) c += sec[i].torsion * sec[i].length;
  return c;
}

double spatial_cell_rod_mass_kg(const SpatialCellRodSpec& spec) {
  double m = 0;
  for (const auto& piece : spec.pieces)
    for (double interval : interval_masses(spec, piece)) m += interval;
  return m;
}

namespace {
/// The shape under the intervals' moments and tensions, integrated from the clamp (at height
/// `length_mm`) down: each interval's curvature and stretch, and the nodes' positions and frames.
void shape_under(const std::vector<IntervalSection>& sec, const std::vector<Vec3>& moment,
                 const std::vector<double>& tension, double length_mm, std::vector<Vec3>& r, std::vector<Mat3>& R,
                 std::vector<Vec3>& curvature, std::vector<double>& stretches) {
  const int n = static_cast<int>(sec.size());
  r[0] = Vec3(0, 0, length_mm);
  R[0] = Mat3::Identity();
  for (int i = 0; i < n; ++i) {
    const IntervalSection& s = sec[i];
    const Vec3 local = R[i].transpose() * moment[i];
    Vec3 k = s.free_curvature;
    k.head<2>() += s.bending * local.head<2>();
    k.z() += s.torsion * local.z();
    const double stretch = s.free_stretch + s.axial * tension[i];
    curvature[i] = k, stretches[i] = stretch;
    const Mat3 half = R[i] * rotation_exp(-0.5 * s.length * k);
    R[i + 1] = R[i] * rotation_exp(-s.length * k);
    r[i + 1] = r[i] - s.length * stretch * half.col(2);
  }
}

/// The weights' moments and tensions at each interval's midpoint (masses lumped there) on the shape
/// r, R: the tip's weight `tip_force` (N) and each interval's mass under gravity g (kg · m/s² = N).
void weights_moments(const std::vector<IntervalSection>& sec, const Vec3& tip_force, const Vec3& g,
                     const std::vector<Vec3>& r, const std::vector<Mat3>& R, std::vector<Vec3>& moment,
                     std::vector<double>& tension) {
  const int n = static_cast<int>(sec.size());
  Vec3 force = tip_force, about_origin = r[n].cross(force);
  for (int i = n - 1; i >= 0; --i) {
    const Vec3 at = 0.5 * (r[i] + r[i + 1]);
    moment[i] = at.cross(force) - about_origin;  // −Σ (r_j − at) × f_j over the weights below
    tension[i] = -force.dot(R[i].col(2));
    const Vec3 f = sec[i].mass * g;
    about_origin += at.cross(f);
    force += f;
  }
}

/// The shape–moment fixed point at the spec's full weights, from `start`'s moments (else none), within
/// `most_iterations`.
SpatialCellRodState settle(const SpatialCellRodSpec& spec, double level, const SpatialCellRodState* start,
                           int most_iterations = 400) {
  SpatialCellRodState out;
  out.level = level;
  std::vector<IntervalSection> sec;
  std::vector<int> first;
  if (std::string why = sections_at(spec, level, sec, first); !why.empty()) {
    out.diagnosis = why;
    out.beyond_tables = true;
    return out;
  }
  const int n = static_cast<int>(sec.size());
  for (std::size_t p = 0; p < spec.pieces.size(); ++p) {
    out.piece_first_node.push_back(first[p]);
    out.piece_last_node.push_back(p + 1 < spec.pieces.size() ? first[p + 1] : n);
  }
  std::vector<Vec3> moment(n, Vec3::Zero()), next(n);
  std::vector<double> tension(n, 0.0);
  if (start && static_cast<int>(start->moment_Nmm.size()) == n) moment = start->moment_Nmm;
  std::vector<Vec3> r(n + 1), curvature(n);
  std::vector<Mat3> R(n + 1);
  std::vector<double> stretches(n);
  // The iterate: every interval's moment and tension, which the shape they produce maps to new
  // ones. The map is a contraction only while the weight bends the rod little; Anderson mixing of
  // the last few iterates (Walker & Ni 2011) settles it where plain iteration oscillates or
  // creeps (a horizontal arm, a heavy tip mass). A residual that blows up restarts the history.
  constexpr int kMemory = 6;
  const auto pack = [&](const std::vector<Vec3>& m, const std::vector<double>& t) {
    Eigen::VectorXd v(4 * n);
    for (int i = 0; i < n; ++i) v.segment<3>(3 * i) = m[i], v[3 * n + i] = t[i];
    return v;
  };
  Eigen::VectorXd x = pack(moment, tension), x_previous, f_previous;
  std::vector<Eigen::VectorXd> dx, df;
  double best = std::numeric_limits<double>::infinity();
  Vec3 last_tip = Vec3::Constant(1e300);
  for (int it = 1; it <= most_iterations; ++it) {
    for (int i = 0; i < n; ++i) moment[i] = x.segment<3>(3 * i), tension[i] = x[3 * n + i];
    shape_under(sec, moment, tension, spatial_cell_rod_length_mm(spec), r, R, curvature, stretches);
    std::vector<double> next_tension(n);
    weights_moments(sec, spec.tip_mass_kg * spec.gravity_m_s2, spec.gravity_m_s2, r, R, next, next_tension);
    out.iterations = it;
    if ((r[n] - last_tip).norm() < 1e-9) {
      out.ok = true;
      break;
    }
    last_tip = r[n];
    const Eigen::VectorXd f = pack(next, next_tension) - x;
    if (!f.allFinite()) break;
    if (x_previous.size() > 0) {
      dx.push_back(x - x_previous), df.push_back(f - f_previous);
      if (static_cast<int>(dx.size()) > kMemory) dx.erase(dx.begin()), df.erase(df.begin());
    }
    if (f.norm() > 1e3 * best) dx.clear(), df.clear();
    best = std::min(best, f.norm());
    x_previous = x, f_previous = f;
    Eigen::VectorXd step = f;
    if (!df.empty()) {
      Eigen::MatrixXd F(4 * n, df.size()), X(4 * n, dx.size());
      for (std::size_t k = 0; k < df.size(); ++k) F.col(k) = df[k], X.col(k) = dx[k];
      const Eigen::VectorXd gamma = F.colPivHouseholderQr().solve(f);
      if (gamma.allFinite()) step = f - (X + F) * gamma;
    }
    x += step;
  }
  if (!out.ok) {
    out.diagnosis = "the shape under its weight did not settle in " + std::to_string(most_iterations) +
                    " iterations (the weight's moment may exceed what the sections hold: a limit point)";
    return out;
  }
  out.position.assign(r.begin(), r.end());
  out.frame.assign(R.begin(), R.end());
  out.moment_Nmm = moment;
  out.stretch = std::move(stretches);
  out.curvature_per_mm = std::move(curvature);
  return out;
}

/// The weights (gravity on the rod, its connectors and the tip mass) raised from none to the spec's,
/// each equilibrium starting the next: the step doubles after one that settles and halves after one
/// that does not, down to kSmallestWeightStep. Weightless, the rod takes its free shape at once, and a
/// nearby weight's moments start the iteration close to its fixed point. On the thesis arm at 9
/// pressures near its workspace's rim (0.2 kg at the tip) the direct iteration ran its 400 steps
/// without settling where 90 % of the weight, then the whole, settled in 41 and 16.
/// A step's iterations are capped at kStepIterations: from its neighbour's moments one settles in tens.
constexpr double kFirstWeightStep = 0.5, kSmallestWeightStep = 1.0 / 64;
constexpr int kMostWeightSteps = 40, kStepIterations = 100;

SpatialCellRodState ramp_weights(const SpatialCellRodSpec& spec, double level, SpatialCellRodState failed) {
  SpatialCellRodSpec ramped = spec;
  ramped.gravity_m_s2.setZero();
  SpatialCellRodState held = settle(ramped, level, nullptr);
  int iterations = failed.iterations + held.iterations;
  double fraction = 0, step = kFirstWeightStep;
  for (int k = 0; held.ok && fraction < 1 && step >= kSmallestWeightStep && k < kMostWeightSteps; ++k) {
    const double next = std::min(1.0, fraction + step);
    ramped.gravity_m_s2 = next * spec.gravity_m_s2;
    SpatialCellRodState s = settle(ramped, level, &held, kStepIterations);
    iterations += s.iterations;
    if (s.ok) held = std::move(s), fraction = next, step *= 2;
    else step *= 0.5;
  }
  if (held.ok && fraction == 1) {
    held.iterations = iterations;
    return held;
  }
  failed.diagnosis += "; nor with the weights raised from none, which held to " +
                      std::to_string(static_cast<int>(100 * fraction)) + " % of them";
  return failed;
}
}  // namespace

SpatialCellRodState solve_spatial_cell_rod(const SpatialCellRodSpec& spec, double level,
                                           const SpatialCellRodState* start) {
  SpatialCellRodState direct = settle(spec, level, start);
  // From no start, an iteration that did not settle (not a level past the tables) is tried again along
  // the weights; a given start is a path's last state, whose neighbour is wanted, not another branch.
  if (direct.ok || start || direct.iterations == 0 || spec.gravity_m_s2.isZero()) return direct;
  return ramp_weights(spec, level, std::move(direct));
}

}  // namespace softarm::fem

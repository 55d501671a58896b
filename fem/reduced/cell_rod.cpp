#include "fem/reduced/cell_rod.hpp"

#include "fem/core/number_text.hpp"
#include "fem/reduced/cell_interpolation.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include "fem/core/angles.hpp"

namespace softarm::fem {
namespace {

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }
}  // namespace

CellRodState solve_cell_rod(const CellRodSpec& spec, double pressure_kPa) {
  CellRodState out;
  out.pressure_kPa = pressure_kPa;
  // Every cell's response at this pressure.
  std::vector<double> z, stretch, curvature, compliance, mass;
  for (const CellTable& c : spec.cells) {
    const auto l = along_ramp(c.pressure_kPa, c.stretch, pressure_kPa);
    const auto k = along_ramp(c.pressure_kPa, c.curvature_per_mm, pressure_kPa);
    const auto m = along_ramp(c.pressure_kPa, c.bending_compliance_per_Nmm2, pressure_kPa);
    if (!l || !k || !m) {
      out.diagnosis = "the cell at z = " + number_text(c.z_mm) + " mm reached " +
                      number_text(c.pressure_kPa.empty() ? 0.0 : c.pressure_kPa.back()) + " kPa only";
      return out;
    }
    z.push_back(c.z_mm), stretch.push_back(*l), curvature.push_back(*k), compliance.push_back(*m);
    mass.push_back(c.mass_per_length_kg_per_mm);
  }
  // The ends' own turn and stretch per unit length, over their reference lengths from z = 0
  // (the free end) and from z = L (the clamp).
  struct EndRate {
    double z0, z1, curvature, stretch;
  };
  std::vector<EndRate> ends;
  for (const EndTable& e : spec.ends) {
    const auto turn = along_ramp(e.pressure_kPa, e.rotation_rad, pressure_kPa);
    const auto longer = along_ramp(e.pressure_kPa, e.elongation_mm, pressure_kPa);
    if (!turn || !longer) {
      out.diagnosis = std::string("the ") + (e.at_clamp ? "clamped" : "free") + " end reached " +
                      number_text(e.pressure_kPa.empty() ? 0.0 : e.pressure_kPa.back()) + " kPa only";
      return out;
    }
    const double z0 = e.at_clamp ? spec.length_mm - e.length_mm : 0.0;
    ends.push_back({z0, z0 + e.length_mm, *turn / e.length_mm, 1 + *longer / e.length_mm});
  }
  // Nodes along S from the clamp (z = L) to the free end (z = 0), values at interval midpoints.
  const int n = spec.intervals;
  const double L = spec.length_mm, dS = L / n;
  std::vector<double> k0(n), l0(n), c0(n), w(n);
  for (int i = 0; i < n; ++i) {
    const double zi = L - (i + 0.5) * dS;
    const bool cap = zi < spec.cap_mm || zi > L - spec.cap_mm;
    k0[i] = cap ? 0.0 : lagrange(z, curvature, zi);
    l0[i] = cap ? 1.0 : lagrange(z, stretch, zi);
    for (const EndRate& e : ends) {  // the share of the interval inside an end takes the end's rates
      const double share = overlap_share(zi, dS, e.z0, e.z1);
      k0[i] = share * e.curvature + (1 - share) * k0[i];
      l0[i] = share * e.stretch + (1 - share) * l0[i];
    }
    c0[i] = lagrange(z, compliance, zi);
    w[i] = lagrange(z, mass, zi) * dS;  // kg per interval
  }
  const Eigen::Vector2d g(spec.gravity_along_bend_m_s2, spec.gravity_along_axis_m_s2);  // N per kg
  std::vector<double> theta(n + 1, 0.0), moment(n, 0.0);
  std::vector<Eigen::Vector2d> r(n + 1);
  double last_tip = 1e300;
  for (int it = 1; it <= 100; ++it) {
    // Shape from the curvature under the last moments (midpoint rule per interval).
    r[0] = Eigen::Vector2d(0, L);
    for (int i = 0; i < n; ++i) {
      theta[i + 1] = theta[i] + (k0[i] + c0[i] * moment[i]) * dS;
      const double mid = 0.5 * (theta[i] + theta[i + 1]);
      r[i + 1] = r[i] + l0[i] * dS * Eigen::Vector2d(std::sin(mid), -std::cos(mid));
    }
    // Moments of the weight beyond each interval's midpoint, lumped at interval midpoints.
    Eigen::Vector2d force = Eigen::Vector2d::Zero();
    double about_origin = 0;  // Σ r_j × f_j beyond
    for (int i = n - 1; i >= 0; --i) {
      const Eigen::Vector2d at = 0.5 * (r[i] + r[i + 1]), f = w[i] * g;
      moment[i] = about_origin - cross(at, force);  // Σ (r_j − r) × f_j over the intervals beyond
      about_origin += cross(at, f);
      force += f;
    }
    out.iterations = it;
    if (std::abs(theta[n] - last_tip) < 1e-12) {
      out.ok = true;
      break;
    }
    last_tip = theta[n];
  }
  if (!out.ok) {
    out.diagnosis = "the shape under its weight did not settle in 100 iterations";
    return out;
  }
  out.bending_angle_deg = theta[n] * 180 / kPi;
  out.tip_along_bend_mm = r[n].x();
  out.tip_z_mm = r[n].y();
  for (const Eigen::Vector2d& node : r) out.centreline_mm.emplace_back(node.x(), 0.0, node.y());
  return out;
}

}  // namespace softarm::fem

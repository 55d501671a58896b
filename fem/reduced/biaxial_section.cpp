#include "fem/reduced/biaxial_section.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace softarm::fem {
namespace {
using Vector3 = Eigen::Vector3d;
using Matrix3 = Eigen::Matrix3d;

// Nominal stress and its slope of the cell's material mix at stretch λ, per unit of cell (N, N/mm²·mm²).
void cell_response(const FibreCell& c, const SectionLaws& laws, double l, double& p, double& dp) {
  double pt, dpt;
  laws.tube->evaluate(l, pt, dpt);
  p = c.tube_area * pt;
  dp = c.tube_area * dpt;
  if (!laws.sheath || c.sheath_area <= 0) return;
  if (laws.sheath != laws.tube) laws.sheath->evaluate(l, pt, dpt);
  p += c.sheath_area * pt;
  dp += c.sheath_area * dpt;
}
}  // namespace

BiaxialSectionState solve_biaxial_section(const CellSection& s, const SectionLaws& laws,
                                          const std::vector<double>& chamber_force_N, double axial_force_N,
                                          const Eigen::Vector2d& fibre_moment_Nmm, BiaxialSectionState guess) {
  Vector3 load(axial_force_N, fibre_moment_Nmm.x(), fibre_moment_Nmm.y());
  for (std::size_t k = 0; k < chamber_force_N.size(); ++k)
    load += chamber_force_N[k] * Vector3(1.0, s.chamber_xi[k].x(), s.chamber_xi[k].y());
  // Convergence as in solve_section: residuals as strains of the section, below 1e-11.
  double xi_max = 0, ea = 0;
  for (const auto& c : s.cells) {
    xi_max = std::max(xi_max, c.xi.norm());
    ea += c.tube_area * laws.tube->initial_modulus() + (laws.sheath ? c.sheath_area * laws.sheath->initial_modulus() : 0.0);
  }
  BiaxialSectionState st = guess;
  st.ok = true;
  st.failure.clear();
  for (int it = 0; it < 50; ++it) {
    Vector3 r = -load;
    Matrix3 k = Matrix3::Zero();
    for (const auto& c : s.cells) {
      double p, dp;
      cell_response(c, laws, st.stretch + st.gradient.dot(c.xi), p, dp);
      const Vector3 e(1.0, c.xi.x(), c.xi.y());
      r += p * e;
      k += dp * e * e.transpose();
    }
    if (!r.allFinite()) break;
    if (std::abs(r[0]) < 1e-11 * ea && r.tail<2>().norm() < 1e-11 * ea * xi_max) return st;
    const Eigen::LLT<Matrix3> llt(k);
    if (llt.info() != Eigen::Success) {
      st.ok = false;
      st.failure = "section tangent not positive definite (a fibre past its uniaxial Drucker limit): limit point";
      return st;
    }
    Vector3 d = llt.solve(-r);
    const double worst = std::abs(d[0]) + d.tail<2>().norm() * xi_max;  // largest stretch change in the section
    if (worst > 0.1) d *= 0.1 / worst;
    st.stretch += d[0];
    st.gradient += d.tail<2>();
    const double spread = st.gradient.norm() * xi_max;
    if (st.failure = fibre_range_failure(laws, st.stretch - spread, st.stretch + spread); !st.failure.empty()) {
      st.ok = false;
      return st;
    }
  }
  st.ok = false;
  st.failure = "section equilibrium did not converge in 50 Newton iterations";
  return st;
}

FibreExtremes fibre_extremes(const CellSection& s, const BiaxialSectionState& st) {
  FibreExtremes e;
  for (const auto& c : s.cells) e.include(st.stretch + st.gradient.dot(c.xi), c.tube_area > 0, c.sheath_area > 0);
  return e;
}

}  // namespace softarm::fem

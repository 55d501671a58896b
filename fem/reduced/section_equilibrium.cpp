#include "fem/reduced/section_equilibrium.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace softarm::fem {
namespace {
struct Residual {
  Eigen::Vector2d r;
  Eigen::Matrix2d k;  // ∂R/∂(λ0, κ)
};

Residual residual(const RodSection& s, const SectionLaws& laws, double f_sum, double f_moment, double n_ext,
                  double m_ext, double l0, double kappa) {
  Residual out;
  double n = 0, m = 0, a = 0, b = 0, c = 0;  // ∫P, ∫yP, ∫P', ∫yP', ∫y²P'
  for (const auto& f : s.strips) {
    const double l = l0 - kappa * f.y;
    double pt, dpt;
    laws.tube->evaluate(l, pt, dpt);
    double p = f.tube_area * pt, dp = f.tube_area * dpt;
    if (laws.sheath && f.sheath_area > 0) {
      if (laws.sheath == laws.tube) {
        p += f.sheath_area * pt;
        dp += f.sheath_area * dpt;
      } else {
        double ps, dps;
        laws.sheath->evaluate(l, ps, dps);
        p += f.sheath_area * ps;
        dp += f.sheath_area * dps;
      }
    }
    if (f.confined_area > 0) {
      double pc, dpc;
      s.confined_law->evaluate(l, pc, dpc);
      p += f.confined_area * pc;
      dp += f.confined_area * dpc;
    }
    n += p;
    m += f.y * p;
    a += dp;
    b += f.y * dp;
    c += f.y * f.y * dp;
  }
  out.r = {n - f_sum - n_ext, m - f_moment + m_ext};
  out.k << a, -b, b, -c;
  return out;
}
}  // namespace

std::string fibre_range_failure(const SectionLaws& laws, double lo, double hi) {
  if (lo >= laws.tube->lambda_min() && hi <= laws.tube->lambda_max()) return {};
  return "fibre stretch outside [" + std::to_string(laws.tube->lambda_min()) + ", " +
         std::to_string(laws.tube->lambda_max()) + "]";
}

SectionState solve_section(const RodSection& s, const SectionLaws& laws, const std::vector<double>& chamber_force_N,
                           double axial_force_N, double moment_Nmm, SectionState guess) {
  double f_sum = 0, f_moment = 0;
  for (std::size_t k = 0; k < chamber_force_N.size(); ++k) {
    f_sum += chamber_force_N[k];
    f_moment += chamber_force_N[k] * s.chamber_y[k];
  }
  // Convergence: the residuals as strains of the section, |R1|/EA and |R2|/(EA·y_max), below 1e-11
  // (EA: the small-strain axial stiffness; the tables' roundoff is ~1e-15 of it).
  double y_max = 0, ea = 0;
  for (const auto& f : s.strips) {
    y_max = std::max(y_max, std::abs(f.y));
    ea += f.tube_area * laws.tube->initial_modulus() + (laws.sheath ? f.sheath_area * laws.sheath->initial_modulus() : 0.0);
    if (f.confined_area > 0) ea += f.confined_area * s.confined_law->initial_modulus();
  }
  const double scale = std::abs(ea);
  SectionState st = guess;
  st.ok = true;
  st.failure.clear();
  for (int it = 0; it < 50; ++it) {
    const Residual r = residual(s, laws, f_sum, f_moment, axial_force_N, moment_Nmm, st.stretch, st.curvature);
    if (!r.r.allFinite()) break;
    if (std::abs(r.r[0]) < 1e-11 * scale && std::abs(r.r[1]) < 1e-11 * scale * y_max) return st;
    // The tangent, with the moment row sign-flipped, is [[A, −B], [−B, C]]: it must be positive definite.
    const double a = r.k(0, 0), b = r.k(1, 0), c = -r.k(1, 1);
    if (!(a > 0 && a * c - b * b > 0)) {
      st.ok = false;
      st.failure = "section tangent not positive definite (a fibre past its uniaxial Drucker limit): limit point";
      return st;
    }
    Eigen::Vector2d d = r.k.partialPivLu().solve(-r.r);
    // Limit the step to 0.1 in stretch anywhere in the section.
    const double worst = std::abs(d[0]) + std::abs(d[1]) * y_max;
    if (worst > 0.1) d *= 0.1 / worst;
    st.stretch += d[0];
    st.curvature += d[1];
    const double l_lo = st.stretch - std::abs(st.curvature) * y_max, l_hi = st.stretch + std::abs(st.curvature) * y_max;
    if (st.failure = fibre_range_failure(laws, l_lo, l_hi); !st.failure.empty()) {
      st.ok = false;
      return st;
    }
    if (s.confined_law)
      for (const auto& f : s.strips)
        if (f.confined_area > 0 && st.stretch - st.curvature * f.y < s.confined_law->lambda_min()) {
          st.ok = false;
          st.failure = "a ring-held wall compressed below stretch " + std::to_string(s.confined_law->lambda_min()) +
                       " (its chamber closes)";
          return st;
        }
  }
  st.ok = false;
  st.failure = "section equilibrium did not converge in 50 Newton iterations";
  return st;
}

void FibreExtremes::include(double l, bool tube, bool sheath) {
  if (tube) {
    tube_max = have_tube_ ? std::max(tube_max, l) : l;
    tube_min = have_tube_ ? std::min(tube_min, l) : l;
    have_tube_ = true;
  }
  if (sheath) {
    sheath_max = have_sheath_ ? std::max(sheath_max, l) : l;
    sheath_min = have_sheath_ ? std::min(sheath_min, l) : l;
    have_sheath_ = true;
  }
}

FibreExtremes fibre_extremes(const RodSection& s, const SectionState& st) {
  FibreExtremes e;
  for (const auto& f : s.strips) e.include(st.stretch - st.curvature * f.y, f.tube_area + f.confined_area > 0, f.sheath_area > 0);
  return e;
}

}  // namespace softarm::fem

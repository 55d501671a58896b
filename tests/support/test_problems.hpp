#pragma once
// Shared helpers for the FEM tests: materials with chosen coefficients and
// central finite-difference checks of a form's gradient and Hessian.
#include <memory>
#include <random>

#include "fem/assembly/energy_problem.hpp"
#include "fem/materials/material.hpp"
#include "fem/materials/neo_hookean.hpp"
#include "fem/materials/ogden.hpp"
#include "fem/materials/saint_venant_kirchhoff.hpp"

namespace softarm::test {

inline fem::Material material(std::shared_ptr<const fem::HyperelasticLaw> law, double density_g_cm3 = 1.0) {
  fem::Material m;
  m.name = law->kind();
  m.law = std::move(law);
  m.density_g_cm3 = density_g_cm3;
  return m;
}

/// Neo-Hookean with shear modulus mu and bulk modulus kappa (D1 = 2/kappa).
inline fem::Material neo_hookean(double mu, double kappa) {
  return material(std::make_shared<fem::NeoHookean>(mu / 2, fem::VolumetricPolynomial({2.0 / kappa})));
}

/// Dragon Skin 30's Ogden coefficients with a chosen bulk modulus.
inline fem::Material dragon_skin_30_ogden(double kappa) {
  return material(std::make_shared<fem::Ogden>(std::vector<double>{1.1806, 0.8743, -1.9396},
                                               std::vector<double>{1.0698, -1.2370, 0.1347},
                                               fem::VolumetricPolynomial({2.0 / kappa})));
}

inline fem::Material abs_plastic() { return material(std::make_shared<fem::SaintVenantKirchhoff>(2620.0, 0.35)); }

/// Random perturbation of every coordinate by up to ±amplitude (reproducible).
inline fem::Vector perturbed(const fem::Vector& x, double amplitude, unsigned seed = 7) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  fem::Vector y = x;
  for (int i = 0; i < y.size(); ++i) y[i] += u(gen);
  return y;
}

struct DerivativeErrors {
  double gradient = 0.0;  // max |g − g_fd| / max |g|
  double hessian = 0.0;   // max |H − H_fd| / max |H|
};

/// Central differences of the problem's energy (for the gradient) and of its
/// gradient (for the Hessian), over the free dofs, step h.
inline DerivativeErrors finite_difference_errors(const fem::EnergyProblem& problem, const fem::Vector& x, double h) {
  const auto at = problem.evaluate(x, true, true);
  const Eigen::MatrixXd H = Eigen::MatrixXd(at.hessian);
  DerivativeErrors err;
  double gmax = 0.0, hmax = 0.0, gerr = 0.0, herr = 0.0;
  const auto& fixed = problem.is_prescribed();
  for (int i = 0; i < x.size(); ++i) {
    if (fixed[i]) continue;
    fem::Vector xp = x, xm = x;
    xp[i] += h;
    xm[i] -= h;
    const auto ep = problem.evaluate(xp, true, false);
    const auto em = problem.evaluate(xm, true, false);
    const double g_fd = (ep.energy - em.energy) / (2 * h);
    gmax = std::max(gmax, std::abs(at.gradient[i]));
    gerr = std::max(gerr, std::abs(g_fd - at.gradient[i]));
    const fem::Vector col_fd = (ep.gradient - em.gradient) / (2 * h);
    for (int j = 0; j < x.size(); ++j) {
      if (fixed[j]) continue;
      hmax = std::max(hmax, std::abs(H(j, i)));
      herr = std::max(herr, std::abs(col_fd[j] - H(j, i)));
    }
  }
  err.gradient = gerr / gmax;
  err.hessian = herr / hmax;
  return err;
}

}  // namespace softarm::test

#include "fem/materials/material_fit.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "fem/core/input_error.hpp"
#include "fem/materials/least_squares.hpp"
#include "fem/materials/neo_hookean.hpp"
#include "fem/materials/ogden.hpp"
#include "fem/materials/ogden_fit.hpp"
#include "fem/materials/uniaxial_closed_form.hpp"
#include "fem/materials/yeoh.hpp"

namespace softarm::fem {
namespace {

int parameter_count(FitModel model) {
  switch (model) {
    case FitModel::neo_hookean: return 1;
    case FitModel::yeoh: return 3;
    case FitModel::ogden1: return 2;
    case FitModel::ogden2: return 4;
    case FitModel::ogden3: return 6;
  }
  return 0;
}

std::string shortest(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

/// prefix + (i + 1) + suffix: "C10_MPa", "mu2_MPa", "alpha3".
std::string numbered(const char* prefix, int i, const char* suffix) {
  std::string key = prefix;
  key += std::to_string(i + 1);
  key += suffix;
  return key;
}

int ogden_terms(FitModel model) { return parameter_count(model) / 2; }

/// D1 for initial shear modulus mu0 at Poisson's ratio nu: D1 = 2/K0, K0 = 2μ0(1 + ν)/(3(1 − 2ν)).
VolumetricPolynomial volumetric_for(double mu0, double nu) {
  if (nu >= 0.5 || !(mu0 > 0.0)) return VolumetricPolynomial();
  return VolumetricPolynomial({3.0 * (1.0 - 2.0 * nu) / (mu0 * (1.0 + nu))});
}

/// Coefficients, fitted stresses and the law for one model (law null when invalid).
FitResult fit_model(FitModel model, const Eigen::VectorXd& stretch, const Eigen::VectorXd& stress,
                    const FitOptions& options) {
  const double nu = options.poisson_ratio;
  FitResult r;
  r.model = model;
  r.parameters = parameter_count(model);
  Eigen::VectorXd fitted;
  auto make_law = [&]() -> std::shared_ptr<const HyperelasticLaw> {
    if (model == FitModel::neo_hookean || model == FitModel::yeoh) {
      const Eigen::VectorXd c = linear_least_squares(invariant_polynomial_basis(stretch, r.parameters), stress);
      fitted = invariant_polynomial_basis(stretch, r.parameters) * c;
      for (int i = 0; i < c.size(); ++i) r.coefficients.emplace_back(numbered("C", i, "0_MPa"), c[i]);
      const auto volumetric = volumetric_for(2.0 * c[0], nu);  // μ0 = 2 C10
      if (model == FitModel::neo_hookean) return std::make_shared<const NeoHookean>(c[0], volumetric);
      return std::make_shared<const Yeoh>(c[0], c[1], c[2], volumetric);
    }
    const OgdenFit f = fit_ogden(stretch, stress, ogden_terms(model), options.max_abs_alpha);
    fitted = ogden_basis(stretch, f.alpha) * f.mu;
    for (int i = 0; i < f.mu.size(); ++i) {
      r.coefficients.emplace_back(numbered("mu", i, "_MPa"), f.mu[i]);
      r.coefficients.emplace_back(numbered("alpha", i, ""), f.alpha[i]);
    }
    if ((f.alpha.array().abs() >= (1.0 - 1e-9) * options.max_abs_alpha).any())
      r.note = "an exponent is at the bound |alpha| <= " + shortest(options.max_abs_alpha);
    std::vector<double> mu(f.mu.data(), f.mu.data() + f.mu.size()), alpha(f.alpha.data(), f.alpha.data() + f.alpha.size());
    return std::make_shared<const Ogden>(mu, alpha, volumetric_for(f.mu.sum(), nu));
  };
  try {
    r.law = make_law();
  } catch (const InputError& e) {
    r.note = std::string("the fitted coefficients are not a valid law: ") + e.what();
  }
  r.fitted_stress_MPa.assign(fitted.data(), fitted.data() + fitted.size());
  r.r_squared = r_squared(stress, fitted);
  r.rms_error_MPa = std::sqrt((stress - fitted).squaredNorm() / static_cast<double>(stress.size()));
  return r;
}

bool covers(const ModeStability& s, double lo, double hi) {
  return s.stable_at_rest && s.lambda_min <= lo && s.lambda_max >= hi;
}

}  // namespace

std::vector<FitModel> all_fit_models() {
  return {FitModel::neo_hookean, FitModel::yeoh, FitModel::ogden1, FitModel::ogden2, FitModel::ogden3};
}

std::string fit_model_name(FitModel model) {
  switch (model) {
    case FitModel::neo_hookean: return "neo_hookean";
    case FitModel::yeoh: return "yeoh";
    case FitModel::ogden1: return "ogden1";
    case FitModel::ogden2: return "ogden2";
    case FitModel::ogden3: return "ogden3";
  }
  return "?";
}

std::vector<std::string> fit_model_names() {
  std::vector<std::string> names;
  for (FitModel m : all_fit_models()) names.push_back(fit_model_name(m));
  return names;
}

FitModel fit_model_from_name(const std::string& name, const std::string& field) {
  for (FitModel m : all_fit_models())
    if (fit_model_name(m) == name) return m;
  std::string valid;
  for (const auto& n : fit_model_names()) valid += (valid.empty() ? "" : ", ") + n;
  throw InputError(field, "unknown model \"" + name + "\"; valid: " + valid);
}

FitSummary fit_uniaxial(const UniaxialData& data, const FitOptions& options) {
  const auto m = static_cast<Eigen::Index>(data.stretch.size());
  const Eigen::VectorXd stretch = Eigen::Map<const Eigen::VectorXd>(data.stretch.data(), m);
  const Eigen::VectorXd stress = Eigen::Map<const Eigen::VectorXd>(data.nominal_stress_MPa.data(), m);
  FitSummary s;
  s.data_lambda_min = std::min(1.0, stretch.minCoeff());
  s.data_lambda_max = std::max(1.0, stretch.maxCoeff());
  s.scan_lambda_min = std::min(0.1, 0.5 * s.data_lambda_min);
  s.scan_lambda_max = std::max(10.0, 1.1 * s.data_lambda_max);
  for (FitModel model : options.models) {
    if (m <= parameter_count(model)) {
      FitResult skipped;
      skipped.model = model;
      skipped.parameters = parameter_count(model);
      skipped.note = "skipped: " + std::to_string(m) + " points do not over-determine " +
                     std::to_string(skipped.parameters) + " coefficients";
      s.fits.push_back(skipped);
      continue;
    }
    FitResult r = fit_model(model, stretch, stress, options);
    if (r.law) {
      r.stability = drucker_stability(*r.law, s.scan_lambda_min, s.scan_lambda_max);
      r.stable_over_data = covers(r.stability.front(), s.data_lambda_min, s.data_lambda_max);  // front: uniaxial
    }
    s.fits.push_back(std::move(r));
  }
  for (std::size_t i = 0; i < s.fits.size(); ++i)
    if (s.fits[i].stable_over_data && (s.best < 0 || s.fits[i].r_squared > s.fits[s.best].r_squared))
      s.best = static_cast<int>(i);
  return s;
}

}  // namespace softarm::fem

#pragma once
// Fitting hyperelastic laws to uniaxial tension data (thesis Ch. 3: Yeoh,
// Neo-Hookean and Ogden least-squares fits compared by R², spec §2).
//
// Each model is fitted to the nominal stress by ordinary least squares
// (absolute error, MPa) with the incompressible closed forms of
// uniaxial_closed_form.hpp: Neo-Hookean (C10) and Yeoh (C10, C20, C30) are
// linear least squares; Ogden N = 1..3 by variable projection (ogden_fit.hpp).
// Each fit's Drucker-stable stretch range (drucker_stability.hpp) is reported
// for the uniaxial, equibiaxial and planar paths, and the selected fit is the
// one with the highest R² among those Drucker stable in uniaxial tension
// over the whole stretch range of the data (the only states it measured).
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "fem/materials/drucker_stability.hpp"
#include "fem/materials/hyperelastic_law.hpp"
#include "fem/materials/uniaxial_data.hpp"

namespace softarm::fem {

enum class FitModel { neo_hookean, yeoh, ogden1, ogden2, ogden3 };

std::vector<FitModel> all_fit_models();
/// "neo_hookean", "yeoh", "ogden1", "ogden2", "ogden3".
std::string fit_model_name(FitModel model);
std::vector<std::string> fit_model_names();
/// Inverse of fit_model_name; an unknown name raises InputError(field) listing the valid ones.
FitModel fit_model_from_name(const std::string& name, const std::string& field);

struct FitOptions {
  std::vector<FitModel> models = all_fit_models();
  /// Sets D1 of the laws built (uniaxial data of an incompressible test cannot):
  /// K0 = 2μ0(1 + ν)/(3(1 − 2ν)), D1 = 2/K0; 0.5 = incompressible (D1 = 0).
  /// 0.48 is what the thesis' Dragon Skin fits imply (K0/μ0 ≈ 25, spec §2).
  double poisson_ratio = 0.48;
  /// Bound on the Ogden exponents |α_i| (ogden_fit.hpp says why one is needed): twice the
  /// largest of Ogden's (1972) rubber fit (5), above every thesis Dragon Skin fit (|α| < 1.9).
  double max_abs_alpha = 10.0;
};

struct FitResult {
  FitModel model{};
  int parameters = 0;                                         // fitted coefficients
  std::vector<std::pair<std::string, double>> coefficients;   // ("C10_MPa", ..), ("mu1_MPa", ..), ("alpha1", ..)
  std::vector<double> fitted_stress_MPa;                      // at the data's stretches
  double r_squared = 0, rms_error_MPa = 0;
  std::shared_ptr<const HyperelasticLaw> law;                 // null: skipped, or not a valid law
  std::string note;                                           // why law is null, or a caveat
  std::vector<ModeStability> stability;                       // uniaxial, equibiaxial, planar
  bool stable_over_data = false;                              // uniaxial, over [data_lambda_min, data_lambda_max]
};

struct FitSummary {
  double data_lambda_min = 1, data_lambda_max = 1;  // the data's stretch range, widened to include 1
  double scan_lambda_min = 0.1, scan_lambda_max = 10;  // the range the stability scan covered
  std::vector<FitResult> fits;                        // in the order of options.models
  int best = -1;  // index of the selected fit; -1: none is stable over the data range
};

/// Fits every model of `options` to `data` (as read by read_uniaxial_csv).
FitSummary fit_uniaxial(const UniaxialData& data, const FitOptions& options = {});

}  // namespace softarm::fem

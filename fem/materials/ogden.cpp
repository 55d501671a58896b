#include "fem/materials/ogden.hpp"

#include <cmath>
#include <numeric>

#include "fem/core/input_error.hpp"
#include "fem/materials/coefficient_check.hpp"

namespace softarm::fem {

Ogden::Ogden(std::vector<double> mu_MPa, std::vector<double> alpha, VolumetricPolynomial volumetric,
             const std::string& path)
    : IsochoricVolumetricLaw(std::move(volumetric)), mu_(std::move(mu_MPa)), alpha_(std::move(alpha)) {
  const std::string mu_field = coefficient_field(path, "mu_MPa"), alpha_field = coefficient_field(path, "alpha");
  if (mu_.empty() || mu_.size() > static_cast<std::size_t>(max_terms))
    throw InputError(mu_field, "has " + std::to_string(mu_.size()) + " terms; valid: 1 to " + std::to_string(max_terms));
  if (alpha_.size() != mu_.size())
    throw InputError(alpha_field, "has " + std::to_string(alpha_.size()) + " entries but mu_MPa has " +
                                      std::to_string(mu_.size()) + "; valid: one alpha per mu");
  for (std::size_t i = 0; i < mu_.size(); ++i) {
    require_coefficient(std::isfinite(mu_[i]), indexed_field(mu_field, i), mu_[i], "a finite number (MPa)");
    require_coefficient(std::isfinite(alpha_[i]) && alpha_[i] != 0.0, indexed_field(alpha_field, i), alpha_[i],
                        "a finite nonzero number (the energy divides by alpha^2)");
  }
  require_coefficient(initial_shear_modulus() > 0.0, mu_field, initial_shear_modulus(),
                      "sum of mu_i (initial shear modulus) > 0 MPa");
}

std::shared_ptr<const Ogden> Ogden::from_json(JsonReader& reader) {
  auto mu = reader.required_number_list("mu_MPa", Range(), "Ogden moduli mu_i, MPa (mu0 = sum mu_i > 0)",
                                        "1 to 3 moduli (MPa)");
  auto alpha = reader.required_number_list("alpha", Range(), "Ogden exponents alpha_i, nonzero, one per mu_i",
                                           "1 to 3 exponents, one per mu_i");
  return std::make_shared<const Ogden>(std::move(mu), std::move(alpha), read_volumetric(reader, 3), reader.path());
}

double Ogden::initial_shear_modulus() const { return std::accumulate(mu_.begin(), mu_.end(), 0.0); }

// Eq 3: W̄ = Σ 2μ_i/α_i² (Σ_a λ̄_a^α_i − 3), with λ̄_a^α = c̄_a^(α/2).
Jet3 Ogden::isochoric_energy(const IsochoricStretches& s) const {
  Jet3 W;
  for (std::size_t i = 0; i < mu_.size(); ++i) {
    const double a = alpha_[i];
    const Jet3 sum = pow(s.cbar[0], 0.5 * a) + pow(s.cbar[1], 0.5 * a) + pow(s.cbar[2], 0.5 * a);
    W += (2.0 * mu_[i] / (a * a)) * (sum - 3.0);
  }
  return W;
}

// Eq 3 in log eigenvalues ℓ_a = ln c_a: with ℓ̄ = (ℓ1 + ℓ2 + ℓ3)/3 (so that J^(2/3) = e^ℓ̄) each
// term is k (Σ_a e_a − 3), e_a = c̄_a^β = e^(β(ℓ_a − ℓ̄)), k = 2μ/α², β = α/2. As ∂(ℓ_a − ℓ̄)/∂ℓ_b =
// δ_ab − 1/3, with S = Σ_a e_a:
//   ∂W/∂ℓ_b = k β (e_b − S/3),
//   ∂²W/∂ℓ_b∂ℓ_c = k β² (δ_bc e_b − (e_b + e_c)/3 + S/9),
// and back to c by ∂/∂c_b = (1/c_b) ∂/∂ℓ_b:
//   f_b = (∂W/∂ℓ_b)/c_b,  f_bc = (∂²W/∂ℓ_b∂ℓ_c)/(c_b c_c) − δ_bc (∂W/∂ℓ_b)/c_b².
// Three logarithms and 3N exponentials instead of 3N + 1 powers and the jets' products.
Jet3 Ogden::principal_energy_at(double c1, double c2, double c3) const {
  const double c[3] = {c1, c2, c3};
  const double l[3] = {std::log(c1), std::log(c2), std::log(c3)};
  const double mean = (l[0] + l[1] + l[2]) / 3.0;
  Jet3 W;
  Eigen::Vector3d g_log = Eigen::Vector3d::Zero();  // ∂W/∂ℓ
  Eigen::Matrix3d h_log = Eigen::Matrix3d::Zero();  // ∂²W/∂ℓ∂ℓ
  for (std::size_t i = 0; i < mu_.size(); ++i) {
    const double beta = 0.5 * alpha_[i], k = 2.0 * mu_[i] / (alpha_[i] * alpha_[i]);
    const double e[3] = {std::exp(beta * (l[0] - mean)), std::exp(beta * (l[1] - mean)), std::exp(beta * (l[2] - mean))};
    const double S = e[0] + e[1] + e[2];
    W.v += k * (S - 3.0);
    for (int b = 0; b < 3; ++b) {
      g_log[b] += k * beta * (e[b] - S / 3.0);
      for (int d = 0; d < 3; ++d)
        h_log(b, d) += k * beta * beta * ((b == d ? e[b] : 0.0) - (e[b] + e[d]) / 3.0 + S / 9.0);
    }
  }
  for (int b = 0; b < 3; ++b) {
    W.g[b] = g_log[b] / c[b];
    for (int d = 0; d < 3; ++d) W.h(b, d) = h_log(b, d) / (c[b] * c[d]) - (b == d ? g_log[b] / (c[b] * c[b]) : 0.0);
  }
  return W;
}

nlohmann::json Ogden::coefficients_json() const { return {{"mu_MPa", mu_}, {"alpha", alpha_}}; }

}  // namespace softarm::fem

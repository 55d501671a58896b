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

nlohmann::json Ogden::coefficients_json() const { return {{"mu_MPa", mu_}, {"alpha", alpha_}}; }

}  // namespace softarm::fem

#include "fem/materials/saint_venant_kirchhoff.hpp"

#include <cmath>

#include "fem/materials/coefficient_check.hpp"

namespace softarm::fem {

SaintVenantKirchhoff::SaintVenantKirchhoff(double E_MPa, double poisson_ratio, const std::string& path)
    : E_(E_MPa), nu_(poisson_ratio) {
  require_coefficient(std::isfinite(E_) && E_ > 0.0, coefficient_field(path, "E_MPa"), E_, "> 0 MPa");
  require_coefficient(std::isfinite(nu_) && nu_ > -1.0 && nu_ < 0.5, coefficient_field(path, "poisson_ratio"), nu_,
                      "(-1, 0.5)");
  lambda_ = E_ * nu_ / ((1.0 + nu_) * (1.0 - 2.0 * nu_));
  mu_ = E_ / (2.0 * (1.0 + nu_));
}

std::shared_ptr<const SaintVenantKirchhoff> SaintVenantKirchhoff::from_json(JsonReader& reader) {
  const double E = reader.number("E_MPa", Range::positive(), "Young's modulus, MPa");
  const double nu = reader.number("poisson_ratio", Range::open(-1.0, 0.5), "Poisson's ratio");
  return std::make_shared<const SaintVenantKirchhoff>(E, nu, reader.path());
}

// W = λ/2 (Σ E_a)² + μ Σ E_a², E_a = (c_a − 1)/2.
Jet3 SaintVenantKirchhoff::principal_energy(const Jet3& c1, const Jet3& c2, const Jet3& c3) const {
  const Jet3 E1 = 0.5 * (c1 - 1.0), E2 = 0.5 * (c2 - 1.0), E3 = 0.5 * (c3 - 1.0);
  const Jet3 trace = E1 + E2 + E3;
  return (0.5 * lambda_) * trace * trace + mu_ * (E1 * E1 + E2 * E2 + E3 * E3);
}

// ∂W/∂c_a = ½ (λ tr E + 2μ E_a),  ∂²W/∂c_a∂c_b = ¼ (λ + 2μ δ_ab).
Jet3 SaintVenantKirchhoff::principal_energy_at(double c1, double c2, double c3) const {
  const Eigen::Vector3d E(0.5 * (c1 - 1.0), 0.5 * (c2 - 1.0), 0.5 * (c3 - 1.0));
  const double trace = E.sum();
  Jet3 W;
  W.v = 0.5 * lambda_ * trace * trace + mu_ * E.squaredNorm();
  W.g = 0.5 * (lambda_ * trace * Eigen::Vector3d::Ones() + 2.0 * mu_ * E);
  W.h = Eigen::Matrix3d::Constant(0.25 * lambda_) + Eigen::Matrix3d::Identity() * (0.5 * mu_);
  return W;
}

double SaintVenantKirchhoff::initial_bulk_modulus() const { return E_ / (3.0 * (1.0 - 2.0 * nu_)); }

nlohmann::json SaintVenantKirchhoff::to_json() const {
  return {{"law", kind()}, {"E_MPa", E_}, {"poisson_ratio", nu_}};
}

}  // namespace softarm::fem

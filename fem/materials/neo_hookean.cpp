#include "fem/materials/neo_hookean.hpp"

#include <cmath>

#include "fem/materials/coefficient_check.hpp"

namespace softarm::fem {

NeoHookean::NeoHookean(double C10_MPa, VolumetricPolynomial volumetric, const std::string& path)
    : IsochoricVolumetricLaw(std::move(volumetric)), C10_(C10_MPa) {
  require_coefficient(std::isfinite(C10_) && C10_ > 0.0, coefficient_field(path, "C10_MPa"), C10_, "> 0 MPa");
}

std::shared_ptr<const NeoHookean> NeoHookean::from_json(JsonReader& reader) {
  const double C10 = reader.number("C10_MPa", Range::positive(), "neo-Hookean C10, MPa (mu0 = 2 C10)");
  return std::make_shared<const NeoHookean>(C10, read_volumetric(reader, 1), reader.path());
}

// Eq 4: W̄ = C10 (Ī1 − 3).
Jet3 NeoHookean::isochoric_energy(const IsochoricStretches& s) const { return C10_ * (s.first_invariant() - 3.0); }

nlohmann::json NeoHookean::coefficients_json() const { return {{"C10_MPa", C10_}}; }

}  // namespace softarm::fem

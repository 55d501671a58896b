#include "fem/materials/yeoh.hpp"

#include <cmath>

#include "fem/materials/coefficient_check.hpp"

namespace softarm::fem {

Yeoh::Yeoh(double C10_MPa, double C20_MPa, double C30_MPa, VolumetricPolynomial volumetric, const std::string& path)
    : IsochoricVolumetricLaw(std::move(volumetric)), C_{C10_MPa, C20_MPa, C30_MPa} {
  require_coefficient(std::isfinite(C_[0]) && C_[0] > 0.0, coefficient_field(path, "C10_MPa"), C_[0],
                      "> 0 MPa (mu0 = 2 C10)");
  require_coefficient(std::isfinite(C_[1]), coefficient_field(path, "C20_MPa"), C_[1], "a finite number");
  require_coefficient(std::isfinite(C_[2]), coefficient_field(path, "C30_MPa"), C_[2], "a finite number");
}

std::shared_ptr<const Yeoh> Yeoh::from_json(JsonReader& reader) {
  const double C10 = reader.number("C10_MPa", Range::positive(), "Yeoh C10, MPa (mu0 = 2 C10)");
  const double C20 = reader.number("C20_MPa", 0.0, Range(), "Yeoh C20, MPa");
  const double C30 = reader.number("C30_MPa", 0.0, Range(), "Yeoh C30, MPa");
  return std::make_shared<const Yeoh>(C10, C20, C30, read_volumetric(reader, 3), reader.path());
}

// Eq 2: W̄ = Σ_{i=1..3} C_i0 (Ī1 − 3)^i; integer powers stay exact at Ī1 = 3.
Jet3 Yeoh::isochoric_energy(const IsochoricStretches& s) const {
  const Jet3 x = s.first_invariant() - 3.0;
  Jet3 W;
  for (int i = 1; i <= 3; ++i)
    if (C_[i - 1] != 0.0) W += C_[i - 1] * ipow(x, i);
  return W;
}

nlohmann::json Yeoh::coefficients_json() const {
  return {{"C10_MPa", C_[0]}, {"C20_MPa", C_[1]}, {"C30_MPa", C_[2]}};
}

}  // namespace softarm::fem

#include "fem/materials/mooney_rivlin.hpp"

#include <cmath>

#include "fem/materials/coefficient_check.hpp"

namespace softarm::fem {

MooneyRivlin::MooneyRivlin(double C10_MPa, double C01_MPa, VolumetricPolynomial volumetric, const std::string& path)
    : IsochoricVolumetricLaw(std::move(volumetric)), C10_(C10_MPa), C01_(C01_MPa) {
  require_coefficient(std::isfinite(C10_), coefficient_field(path, "C10_MPa"), C10_, "a finite number");
  require_coefficient(std::isfinite(C01_) && C10_ + C01_ > 0.0, coefficient_field(path, "C01_MPa"), C01_,
                      "C10 + C01 > 0 (initial shear modulus 2(C10 + C01) must be positive)");
}

std::shared_ptr<const MooneyRivlin> MooneyRivlin::from_json(JsonReader& reader) {
  const double C10 = reader.number("C10_MPa", Range(), "Mooney-Rivlin C10, MPa");
  const double C01 = reader.number("C01_MPa", Range(), "Mooney-Rivlin C01, MPa (C10 + C01 > 0)");
  return std::make_shared<const MooneyRivlin>(C10, C01, read_volumetric(reader, 1), reader.path());
}

// W̄ = C10 (Ī1 − 3) + C01 (Ī2 − 3).
Jet3 MooneyRivlin::isochoric_energy(const IsochoricStretches& s) const {
  return C10_ * (s.first_invariant() - 3.0) + C01_ * (s.second_invariant() - 3.0);
}

nlohmann::json MooneyRivlin::coefficients_json() const { return {{"C10_MPa", C10_}, {"C01_MPa", C01_}}; }

}  // namespace softarm::fem

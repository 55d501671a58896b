#pragma once
// Mooney-Rivlin law (the N = 1 polynomial model; Abaqus form):
//   W = C10 (Ī1 − 3) + C01 (Ī2 − 3) + (1/D1)(J − 1)²,   μ0 = 2 (C10 + C01),  K0 = 2/D1.
// It equals Ogden with μ = [2 C10, 2 C01], α = [2, −2] (a test checks this).
#include <memory>

#include "fem/materials/isochoric_law.hpp"

namespace softarm::fem {

class MooneyRivlin final : public IsochoricVolumetricLaw {
 public:
  /// C10 + C01 > 0 MPa (either may be negative); `path` prefixes field names in errors.
  MooneyRivlin(double C10_MPa, double C01_MPa, VolumetricPolynomial volumetric, const std::string& path = "");
  static std::shared_ptr<const MooneyRivlin> from_json(JsonReader& reader);

  std::string kind() const override { return "mooney_rivlin"; }
  double initial_shear_modulus() const override { return 2.0 * (C10_ + C01_); }

 protected:
  Jet3 isochoric_energy(const IsochoricStretches& s) const override;
  nlohmann::json coefficients_json() const override;

 private:
  double C10_, C01_;
};

}  // namespace softarm::fem

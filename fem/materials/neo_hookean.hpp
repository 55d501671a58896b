#pragma once
// Neo-Hookean law, thesis eq 4 (Abaqus form):
//   W = C10 (Ī1 − 3) + (1/D1)(J − 1)²,   μ0 = 2 C10,  K0 = 2/D1.
// (The thesis obtains it from Ogden with N = 1, α = 2: C10 = μ/2.)
#include <memory>

#include "fem/materials/isochoric_law.hpp"

namespace softarm::fem {

class NeoHookean final : public IsochoricVolumetricLaw {
 public:
  /// C10 > 0 MPa; `path` prefixes field names in error messages.
  NeoHookean(double C10_MPa, VolumetricPolynomial volumetric, const std::string& path = "");
  static std::shared_ptr<const NeoHookean> from_json(JsonReader& reader);

  std::string kind() const override { return "neo_hookean"; }
  double initial_shear_modulus() const override { return 2.0 * C10_; }
  double C10() const { return C10_; }

 protected:
  Jet3 isochoric_energy(const IsochoricStretches& s) const override;
  nlohmann::json coefficients_json() const override;

 private:
  double C10_;
};

}  // namespace softarm::fem

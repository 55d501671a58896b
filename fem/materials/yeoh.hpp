#pragma once
// Yeoh law, thesis eq 2: the reduced polynomial of eq 1,
//   W = Σ_{i=1..N} C_i0 (Ī1 − 3)^i + Σ_{i=1..N} (1/D_i)(J − 1)^(2i),
// limited to N = 3.  μ0 = 2 C10, K0 = 2/D1.
#include <array>
#include <memory>

#include "fem/materials/isochoric_law.hpp"

namespace softarm::fem {

class Yeoh final : public IsochoricVolumetricLaw {
 public:
  /// C10 > 0 MPa; C20, C30 of any sign; `path` prefixes field names in errors.
  Yeoh(double C10_MPa, double C20_MPa, double C30_MPa, VolumetricPolynomial volumetric, const std::string& path = "");
  static std::shared_ptr<const Yeoh> from_json(JsonReader& reader);

  std::string kind() const override { return "yeoh"; }
  double initial_shear_modulus() const override { return 2.0 * C_[0]; }

 protected:
  Jet3 isochoric_energy(const IsochoricStretches& s) const override;
  nlohmann::json coefficients_json() const override;

 private:
  std::array<double, 3> C_;  // C10, C20, C30
};

}  // namespace softarm::fem

#pragma once
// Ogden law, thesis eq 3 (Abaqus form):
//   W = Σ_{i=1..N} 2μ_i/α_i² (λ̄1^α_i + λ̄2^α_i + λ̄3^α_i − 3) + Σ_{i=1..3} (1/D_i)(J − 1)^(2i),
//   λ̄_a² = c̄_a = J^(-2/3) c_a,   μ0 = Σ μ_i,  K0 = 2/D1.
// Individual μ_i may be negative (the thesis' Dragon Skin fits are); only
// μ0 > 0 is required here — whether the fit is physical over a stretch range
// is what drucker_stability() reports.
#include <memory>
#include <vector>

#include "fem/materials/isochoric_law.hpp"

namespace softarm::fem {

class Ogden final : public IsochoricVolumetricLaw {
 public:
  static constexpr int max_terms = 3;
  /// 1..3 pairs (μ_i MPa, α_i ≠ 0) with Σ μ_i > 0; `path` prefixes field names in errors.
  Ogden(std::vector<double> mu_MPa, std::vector<double> alpha, VolumetricPolynomial volumetric,
        const std::string& path = "");
  static std::shared_ptr<const Ogden> from_json(JsonReader& reader);

  std::string kind() const override { return "ogden"; }
  double initial_shear_modulus() const override;
  const std::vector<double>& mu() const { return mu_; }
  const std::vector<double>& alpha() const { return alpha_; }
  /// Eq 3's W̄ with its derivatives in closed form (through the jets, its ten powers and their
  /// products were a third of a Gauss point's cost); equal to the jets' to round-off (test [materials]).
  Jet3 principal_energy_at(double c1, double c2, double c3) const override;

 protected:
  Jet3 isochoric_energy(const IsochoricStretches& s) const override;
  nlohmann::json coefficients_json() const override;

 private:
  std::vector<double> mu_, alpha_;
};

}  // namespace softarm::fem

#pragma once
// Saint Venant-Kirchhoff law for the stiff printed parts (digital ABS rings
// and connectors, thesis "linear" E, ν): Hooke's law in Green-Lagrange strain,
//   W = λ/2 (tr E)² + μ tr E²,   E = (C − I)/2  (principal: E_a = (c_a − 1)/2),
//   λ = Eν/((1+ν)(1−2ν)),  μ = E/(2(1+ν)),  K0 = E/(3(1−2ν)).
// No isochoric/volumetric split: the whole energy is principal_energy(), so
// volumetric() is zero. Fine for the small strains the rings see; SVK
// softens (and loses stability) in strong compression, which rings never reach.
#include <memory>

#include "fem/core/json_reader.hpp"
#include "fem/materials/hyperelastic_law.hpp"

namespace softarm::fem {

class SaintVenantKirchhoff final : public HyperelasticLaw {
 public:
  /// E > 0 MPa, −1 < ν < 0.5; `path` prefixes field names in errors.
  SaintVenantKirchhoff(double E_MPa, double poisson_ratio, const std::string& path = "");
  static std::shared_ptr<const SaintVenantKirchhoff> from_json(JsonReader& reader);

  std::string kind() const override { return "saint_venant_kirchhoff"; }
  Jet3 principal_energy(const Jet3& c1, const Jet3& c2, const Jet3& c3) const override;
  /// The same W with its derivatives in closed form (every ring's Gauss point asks for it).
  Jet3 principal_energy_at(double c1, double c2, double c3) const override;
  std::optional<GreenStrainHooke> green_strain_hooke() const override { return GreenStrainHooke{lambda_, mu_}; }
  double initial_shear_modulus() const override { return mu_; }
  double initial_bulk_modulus() const override;
  nlohmann::json to_json() const override;

 private:
  double E_, nu_, lambda_, mu_;
};

}  // namespace softarm::fem

#pragma once
// Shared machinery of the laws with the Abaqus isochoric/volumetric split
// (thesis eqs 1–4):  W(C) = W̄(C̄) + U(J),  C̄ = J^(-2/3) C,  J² = det C.
//
// principal_energy() is written once here: it forms the isochoric
// eigenvalues c̄_a = J^(-2/3) c_a (with J = sqrt(c1 c2 c3) inside the Jet, so
// the derivatives carry the deviatoric projection automatically) and hands
// them to the law's isochoric_energy(). U(J) is the Abaqus polynomial.
#include <nlohmann/json.hpp>
#include <string>

#include "fem/core/json_reader.hpp"
#include "fem/materials/hyperelastic_law.hpp"
#include "fem/materials/volumetric_polynomial.hpp"

namespace softarm::fem {

/// Eigenvalues of the isochoric right Cauchy-Green tensor C̄ (= λ̄_a²).
struct IsochoricStretches {
  Jet3 cbar[3];
  /// Ī1 = c̄1 + c̄2 + c̄3.
  Jet3 first_invariant() const;
  /// Ī2 = c̄1 c̄2 + c̄2 c̄3 + c̄3 c̄1.
  Jet3 second_invariant() const;
};

IsochoricStretches isochoric_stretches(const Jet3& c1, const Jet3& c2, const Jet3& c3);

class IsochoricVolumetricLaw : public HyperelasticLaw {
 public:
  explicit IsochoricVolumetricLaw(VolumetricPolynomial volumetric_part) : volumetric_(std::move(volumetric_part)) {}

  Jet3 principal_energy(const Jet3& c1, const Jet3& c2, const Jet3& c3) const final {
    return isochoric_energy(isochoric_stretches(c1, c2, c3));
  }
  VolumetricResponse volumetric(double J) const final { return volumetric_.evaluate(J); }
  bool has_volumetric_split() const final { return true; }
  double initial_bulk_modulus() const final { return volumetric_.bulk_modulus(); }
  /// {"law": kind(), <law coefficients>, "D_per_MPa": [...]}.
  nlohmann::json to_json() const final;

  const VolumetricPolynomial& volumetric_polynomial() const { return volumetric_; }

  /// Reads the required "D_per_MPa" list (at most `max_terms` entries; [] = incompressible).
  static VolumetricPolynomial read_volumetric(JsonReader& reader, int max_terms);

 protected:
  /// W̄ as a function of the isochoric eigenvalues c̄_a.
  virtual Jet3 isochoric_energy(const IsochoricStretches& s) const = 0;
  /// The law's own coefficients in JSON form (keys with units).
  virtual nlohmann::json coefficients_json() const = 0;

 private:
  VolumetricPolynomial volumetric_;
};

}  // namespace softarm::fem

#pragma once
// The strain-energy interface every material law implements.
//
// A law is an isotropic strain energy W(C) written as a symmetric function of
// the three eigenvalues c_a of the right Cauchy-Green tensor C = FᵀF (so that
// c_a = λ_a², the squared principal stretches). Laws with the Abaqus
// isochoric/volumetric split (thesis eqs 1–4) return the isochoric part
// W̄(C̄), C̄ = J^(-2/3) C, here and the volumetric part U(J) separately, so
// that elements can treat the volumetric part with a mean-dilatation
// (F-bar type) formulation that does not lock (FEBio's split, step-44).
//
// Units: stresses and moduli in MPa, energies in MPa = N·mm/mm³.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "fem/core/jet.hpp"

namespace softarm::fem {

using Jet3 = Jet<3>;

/// U(J) with its first two derivatives.
struct VolumetricResponse {
  double U = 0.0;
  double dU = 0.0;
  double d2U = 0.0;
};

/// Lamé constants of a law that is Hooke's law in the Green-Lagrange strain E = (C − I)/2,
/// W = λ/2 (tr E)² + μ tr E² (Saint Venant-Kirchhoff). Its stress and tangent need no eigenvalues
/// of C: evaluate_principal (principal_stress.hpp) takes them in tensor form.
struct GreenStrainHooke {
  double lambda_MPa = 0.0;
  double mu_MPa = 0.0;
};

class HyperelasticLaw {
 public:
  virtual ~HyperelasticLaw() = default;

  /// Short identifier of the law family: "neo_hookean", "ogden", ...
  virtual std::string kind() const = 0;

  /// Energy per reference volume as a function of the eigenvalues of C
  /// (for split laws: the isochoric part only; J = sqrt(c1 c2 c3) inside).
  virtual Jet3 principal_energy(const Jet3& c1, const Jet3& c2, const Jet3& c3) const = 0;

  /// The same energy with its gradient and Hessian in (c1, c2, c3) at given eigenvalues: what every
  /// Gauss point asks for. By default principal_energy() on three variables; a law may give a closed
  /// form that is cheaper than the jet arithmetic (Ogden, Saint Venant-Kirchhoff).
  virtual Jet3 principal_energy_at(double c1, double c2, double c3) const {
    return principal_energy(Jet3::variable(c1, 0), Jet3::variable(c2, 1), Jet3::variable(c3, 2));
  }

  /// The Lamé constants of a law that is Hooke's law in the Green-Lagrange strain; empty for every
  /// other law.
  virtual std::optional<GreenStrainHooke> green_strain_hooke() const { return std::nullopt; }

  /// Volumetric energy U(J); laws without the split return zeros.
  virtual VolumetricResponse volumetric(double J) const { return {}; }
  virtual bool has_volumetric_split() const { return false; }

  /// Small-strain shear and bulk moduli at C = I, MPa.
  virtual double initial_shear_modulus() const = 0;
  virtual double initial_bulk_modulus() const = 0;

  /// Coefficients in the library's JSON form (round-trips through the parser).
  virtual nlohmann::json to_json() const = 0;
};

}  // namespace softarm::fem

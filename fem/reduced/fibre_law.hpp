#pragma once
// The uniaxial response of a hyperelastic law, as the fibres of a reduced
// (rod) model see it: an incompressible fibre stretched to λ with its lateral
// faces traction free carries the nominal stress
//     P(λ) = (1/λ) ∂w/∂ε1 on the uniaxial path (λ, λ^-1/2, λ^-1/2),
// for Ogden P = Σ (2μ_i/α_i)(λ^(α_i−1) − λ^(−α_i/2−1)) (fem/materials/drucker_stability.hpp).
// Tabulated once on a uniform stretch grid (the rod model evaluates it ~10^6
// times per design), with the tangent dP/dλ from the same law by central
// differences of the exact P, interpolated by cubic Hermite
// polynomials (C1, consistent value and slope). A law that softens (dP/dλ ≤ 0, the Drucker limit
// in uniaxial tension, e.g. Dragon Skin 10) makes the rod's section tangent
// singular there: the rod reports a limit point instead of running on.
#include <functional>
#include <vector>

#include "fem/materials/hyperelastic_law.hpp"

namespace softarm::fem {

class FibreLaw {
 public:
  /// Tabulates P on [lambda_min, lambda_max] with `points` samples.
  explicit FibreLaw(const HyperelasticLaw& law, double lambda_min = 0.3, double lambda_max = 6.0, int points = 6001);
  /// Tabulates any nominal stress P(λ) (MPa) the same way (tangent by central differences of P).
  FibreLaw(const std::function<double(double)>& nominal_stress, double lambda_min, double lambda_max, int points);
  /// Nominal stress P(λ), MPa (cubic Hermite on the table; linear extrapolation outside it).
  double stress(double lambda) const;
  /// dP/dλ, MPa: the exact derivative of stress().
  double tangent(double lambda) const;
  /// Both at once (one table lookup): the rod's sections call this ~10^6 times per design.
  void evaluate(double lambda, double& stress, double& tangent) const;
  /// Small-strain Young's modulus dP/dλ at λ = 1 (3μ0 for an incompressible law).
  double initial_modulus() const { return tangent(1.0); }
  double lambda_min() const { return lo_; }
  double lambda_max() const { return hi_; }

 private:
  double lo_, hi_, step_;
  std::vector<double> p_, dp_;
};

}  // namespace softarm::fem

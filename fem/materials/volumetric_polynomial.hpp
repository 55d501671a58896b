#pragma once
// The Abaqus volumetric energy shared by every split law (thesis eqs 1–3):
//
//   U(J) = Σ_{i=1..3} (1/D_i) (J − 1)^(2i),        K0 = U''(1) = 2 / D1.
//
// Abaqus semantics: a D_i that is 0 (or not given) means "this term is
// absent", not "infinitely stiff" (CalculiX instead reads D = 0 as a tiny
// compressibility). With D1 = 0 the law is incompressible: K0 = +inf, and the
// element must enforce J = 1 by other means (hybrid / penalty).
#include <array>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "fem/materials/hyperelastic_law.hpp"

namespace softarm::fem {

class VolumetricPolynomial {
 public:
  static constexpr int max_terms = 3;

  VolumetricPolynomial() = default;
  /// D in 1/MPa, at most three entries, each >= 0 (0 = no term). `field` names
  /// the JSON list for error messages.
  explicit VolumetricPolynomial(const std::vector<double>& D, const std::string& field = "D_per_MPa");

  VolumetricResponse evaluate(double J) const;
  /// 2 / D1; +inf when D1 = 0 (incompressible).
  double bulk_modulus() const;
  /// The D_i as given, trailing zeros dropped (JSON form).
  std::vector<double> coefficients() const;

 private:
  std::array<double, max_terms> D_{0.0, 0.0, 0.0};
};

}  // namespace softarm::fem

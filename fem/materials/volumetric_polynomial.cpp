#include "fem/materials/volumetric_polynomial.hpp"

#include <cmath>
#include <limits>
#include <sstream>

#include "fem/core/input_error.hpp"
#include "fem/materials/coefficient_check.hpp"

namespace softarm::fem {

VolumetricPolynomial::VolumetricPolynomial(const std::vector<double>& D, const std::string& field) {
  if (D.size() > static_cast<std::size_t>(max_terms))
    throw InputError(field, "has " + std::to_string(D.size()) + " entries; valid: at most " +
                                std::to_string(max_terms) + " (D1, D2, D3)");
  for (std::size_t i = 0; i < D.size(); ++i) {
    if (!std::isfinite(D[i]) || D[i] < 0.0) {
      std::ostringstream msg;
      msg << "D" << i + 1 << " = " << D[i] << " 1/MPa is not valid; valid: >= 0 (0 means no term)";
      throw InputError(indexed_field(field, i), msg.str());
    }
    D_[i] = D[i];
  }
}

VolumetricResponse VolumetricPolynomial::evaluate(double J) const {
  // d/dJ (J−1)^(2i) = 2i (J−1)^(2i−1), d²/dJ² = 2i(2i−1)(J−1)^(2i−2); integer powers keep J = 1 exact.
  VolumetricResponse r;
  const double x = J - 1.0;
  for (int i = 1; i <= max_terms; ++i) {
    const double D = D_[i - 1];
    if (D == 0.0) continue;
    const int n = 2 * i;
    r.U += std::pow(x, n) / D;
    r.dU += n * std::pow(x, n - 1) / D;
    r.d2U += n * (n - 1) * std::pow(x, n - 2) / D;
  }
  return r;
}

double VolumetricPolynomial::bulk_modulus() const {
  return D_[0] > 0.0 ? 2.0 / D_[0] : std::numeric_limits<double>::infinity();
}

std::vector<double> VolumetricPolynomial::coefficients() const {
  std::vector<double> out(D_.begin(), D_.end());
  while (!out.empty() && out.back() == 0.0) out.pop_back();
  return out;
}

}  // namespace softarm::fem

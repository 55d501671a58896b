#include "fem/materials/isochoric_law.hpp"

namespace softarm::fem {

IsochoricStretches isochoric_stretches(const Jet3& c1, const Jet3& c2, const Jet3& c3) {
  // J^(-2/3) = (c1 c2 c3)^(-1/3).
  const Jet3 j_m23 = pow(c1 * c2 * c3, -1.0 / 3.0);
  return {{j_m23 * c1, j_m23 * c2, j_m23 * c3}};
}

Jet3 IsochoricStretches::first_invariant() const { return cbar[0] + cbar[1] + cbar[2]; }

Jet3 IsochoricStretches::second_invariant() const {
  return cbar[0] * cbar[1] + cbar[1] * cbar[2] + cbar[2] * cbar[0];
}

nlohmann::json IsochoricVolumetricLaw::to_json() const {
  nlohmann::json j = coefficients_json();
  j["law"] = kind();
  j["D_per_MPa"] = volumetric_.coefficients();
  return j;
}

VolumetricPolynomial IsochoricVolumetricLaw::read_volumetric(JsonReader& reader, int max_terms) {
  const std::string doc = "Abaqus volumetric coefficients D1..D" + std::to_string(max_terms) +
                          ", 1/MPa; U = sum (1/D_i)(J-1)^(2i), K0 = 2/D1; 0 = no term, [] = incompressible";
  const std::vector<double> D = reader.required_number_list(
      "D_per_MPa", Range::non_negative(), doc, "e.g. [0.7029] (K0 = 2/D1), or [] for an incompressible law");
  if (D.size() > static_cast<std::size_t>(max_terms))
    throw InputError(reader.field("D_per_MPa"), "has " + std::to_string(D.size()) + " entries; valid for this law: at most " +
                                                    std::to_string(max_terms));
  return VolumetricPolynomial(D, reader.field("D_per_MPa"));
}

}  // namespace softarm::fem

#pragma once
// A named material: its hyperelastic law plus the data the engine needs
// around it (density for mass, strength and elongation at break for the
// burst-pressure criteria, spec §4), and where the numbers come from.
// Built-ins are the thesis' materials (spec §2); JSON can name one or give a
// law with its coefficients.
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "fem/materials/hyperelastic_law.hpp"

namespace softarm::fem {

struct Material {
  std::string name;                           // "dragon_skin_30"
  std::shared_ptr<const HyperelasticLaw> law;
  double density_g_cm3 = 0;
  double tensile_strength_MPa = std::numeric_limits<double>::quiet_NaN();  // NaN when unknown
  double elongation_at_break = std::numeric_limits<double>::quiet_NaN();   // strain at break as a fraction (3.64 = 364 %)
  std::string source;                          // where the numbers come from
};

/// A built-in material; an unknown name raises InputError(field_path) listing the known names.
const Material& builtin_material(const std::string& name, const std::string& field_path);
std::vector<std::string> builtin_material_names();

/// The law families material_from_json accepts under "law".
std::vector<std::string> material_law_names();

/// A material given in JSON: either a string naming a built-in, or an object
/// {"name":..., "law": "ogden"|"neo_hookean"|"mooney_rivlin"|"yeoh"|"saint_venant_kirchhoff",
///  coefficients with units in keys: "mu_MPa": [..], "alpha": [..], "D_per_MPa": [..] (required for
///  the split laws; [] = incompressible), "C10_MPa", "C01_MPa", "C20_MPa", "C30_MPa", "E_MPa",
///  "poisson_ratio", "density_g_cm3" (required), "tensile_strength_MPa", "elongation_at_break_percent",
///  "source"}. Unknown keys, unknown laws and invalid coefficients raise InputError naming the field.
Material material_from_json(const nlohmann::json& value, const std::string& field_path);
/// The object form; material_from_json(material_to_json(m), ...) reproduces m.
nlohmann::json material_to_json(const Material& material);

}  // namespace softarm::fem

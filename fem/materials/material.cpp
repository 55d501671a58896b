#include "fem/materials/material.hpp"

#include <algorithm>
#include <cmath>

#include "fem/core/input_error.hpp"
#include "fem/core/json_reader.hpp"
#include "fem/materials/mooney_rivlin.hpp"
#include "fem/materials/neo_hookean.hpp"
#include "fem/materials/ogden.hpp"
#include "fem/materials/saint_venant_kirchhoff.hpp"
#include "fem/materials/yeoh.hpp"

namespace softarm::fem {
namespace {

constexpr double MPa_per_psi = 6.894757e-3;

const char* const thesis_fit =
    "Ogden N=3 least-squares fit to ASTM D638 Type IV uniaxial tests, thesis Ch. 3 "
    "(Soft Poly-Limb MS thesis, Arizona State University, 2018; spec section 2); "
    "tensile strength, elongation at break and density: Smooth-On ";

Material dragon_skin(const std::string& name, const std::string& product, std::vector<double> mu,
                     std::vector<double> alpha, double D1, double strength_psi, double elongation, double density) {
  Material m;
  m.name = name;
  // D2 = D3 = 0 in the thesis: Abaqus "no term".
  m.law = std::make_shared<const Ogden>(std::move(mu), std::move(alpha), VolumetricPolynomial({D1, 0.0, 0.0}),
                                        "builtin." + name);
  m.density_g_cm3 = density;
  m.tensile_strength_MPa = strength_psi * MPa_per_psi;
  m.elongation_at_break = elongation;
  m.source = std::string(thesis_fit) + product + " technical data sheet";
  return m;
}

const std::vector<Material>& builtins() {
  static const std::vector<Material> list = [] {
    std::vector<Material> v;
    v.push_back(dragon_skin("dragon_skin_10", "Dragon Skin 10", {0.1802, -0.5538, 0.4099}, {-0.1997, 1.4793, 1.8837},
                            2.2373, 475.0, 10.0, 1.07));
    v.push_back(dragon_skin("dragon_skin_20", "Dragon Skin 20", {1.3077, -2.3497, 1.2075}, {1.1087, -0.0317, -1.6291},
                            0.4900, 550.0, 6.2, 1.08));
    v.push_back(dragon_skin("dragon_skin_30", "Dragon Skin 30", {1.1806, 0.8743, -1.9396}, {1.0698, -1.2370, 0.1347},
                            0.7029, 500.0, 3.64, 1.08));
    Material abs;
    abs.name = "digital_abs";
    abs.law = std::make_shared<const SaintVenantKirchhoff>(2620.0, 0.35, "builtin.digital_abs");
    abs.density_g_cm3 = 1.17;
    abs.source =
        "E = 2620 MPa, nu = 0.35 (linear elastic, rings and connectors): thesis Ch. 3 / spec section 2, used as "
        "Saint Venant-Kirchhoff; density: Stratasys Digital ABS data sheet; strength and elongation not modelled";
    v.push_back(std::move(abs));
    return v;
  }();
  return list;
}

std::string quoted_list(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "\"" : ", \"") + n + "\"";
  return s;
}

std::shared_ptr<const HyperelasticLaw> law_from_json(const std::string& law, JsonReader& reader) {
  if (law == "neo_hookean") return NeoHookean::from_json(reader);
  if (law == "mooney_rivlin") return MooneyRivlin::from_json(reader);
  if (law == "yeoh") return Yeoh::from_json(reader);
  if (law == "ogden") return Ogden::from_json(reader);
  return SaintVenantKirchhoff::from_json(reader);  // the only choice left (choice() validated it)
}

}  // namespace

std::vector<std::string> builtin_material_names() {
  std::vector<std::string> names;
  for (const auto& m : builtins()) names.push_back(m.name);
  return names;
}

std::vector<std::string> material_law_names() {
  return {"ogden", "neo_hookean", "mooney_rivlin", "yeoh", "saint_venant_kirchhoff"};
}

const Material& builtin_material(const std::string& name, const std::string& field_path) {
  for (const auto& m : builtins())
    if (m.name == name) return m;
  throw InputError(field_path, "unknown material \"" + name + "\"; built-in materials: " +
                                   quoted_list(builtin_material_names()) + " (or give an object with a \"law\")");
}

Material material_from_json(const nlohmann::json& value, const std::string& field_path) {
  if (value.is_string()) return builtin_material(value.get<std::string>(), field_path);
  if (!value.is_object())
    throw InputError(field_path, "expected a built-in material name (" + quoted_list(builtin_material_names()) +
                                     ") or an object with a \"law\", got " + value.dump());
  JsonReader reader(value, field_path);
  Material m;
  m.name = reader.string("name", "custom", "material name used in reports");
  if (!reader.has("law"))
    throw InputError(reader.field("law"), "required string is missing; valid: " + quoted_list(material_law_names()));
  const std::string law = reader.choice("law", "", material_law_names(), "hyperelastic law family");
  m.law = law_from_json(law, reader);
  m.density_g_cm3 = reader.number("density_g_cm3", Range::positive(), "density, g/cm^3");
  if (auto s = reader.optional_number("tensile_strength_MPa", Range::positive(), "tensile strength, MPa"))
    m.tensile_strength_MPa = *s;
  if (auto e = reader.optional_number("elongation_at_break_percent", Range::positive(),
                                      "elongation at break, % (364 = stretch 4.64 at break)"))
    m.elongation_at_break = *e / 100.0;
  m.source = reader.string("source", "user input", "where the numbers come from");
  reader.finish();
  return m;
}

nlohmann::json material_to_json(const Material& material) {
  nlohmann::json j = material.law->to_json();
  j["name"] = material.name;
  j["density_g_cm3"] = material.density_g_cm3;
  if (std::isfinite(material.tensile_strength_MPa)) j["tensile_strength_MPa"] = material.tensile_strength_MPa;
  if (std::isfinite(material.elongation_at_break)) j["elongation_at_break_percent"] = material.elongation_at_break * 100.0;
  j["source"] = material.source;
  return j;
}

}  // namespace softarm::fem

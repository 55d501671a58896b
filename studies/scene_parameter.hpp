#pragma once
// One parameter of a scene document set by name: a dotted path into the scene
// ("geometry.wall_thickness_normalised", "materials.sheath", "load.chamber_pressures_kPa") or a
// derived parameter:
//   taper_ratio  the 3CA takes the distal segment's radii from thesis eqs 5–7,
//                (r_t)_3 = (r_b)_3 + ((r_t)_1 − (r_b)_3)/3 with (r_t)_1 = (r_b)_3 / t_r,
//                (r_b)_3 the base scene's bottom_radius_mm (9 mm: t_r = 0.5 gives the
//                thesis 3CA, 9 → 12 mm).
// Setting one of a physical/normalised pair (wall_thickness_mm | _normalised, …)
// removes the other from the base, so the scene reader sees exactly one.
// A study's spec checks its parameters with it and its points are built by it.
#include <nlohmann/json.hpp>
#include <string>

namespace softarm::studies {

/// The base scene with `parameter` set to `value` (throws fem::InputError naming `field`).
nlohmann::json with_parameter(nlohmann::json scene, const std::string& parameter, const nlohmann::json& value,
                              const std::string& field);

/// The value as text for tables and words (numbers with up to 4 significant digits).
std::string value_text(const nlohmann::json& value);
}  // namespace softarm::studies

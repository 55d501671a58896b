#pragma once
// The points of a study: the Cartesian product of its sweep axes, each turned
// into a complete scene document by overriding the base scene.
//
// A parameter is a dotted path into the scene ("geometry.wall_thickness_normalised",
// "materials.sheath", "load.chamber_pressures_kPa") or a derived parameter:
//   taper_ratio  the 3CA takes the distal segment's radii from thesis eqs 5–7,
//                (r_t)_3 = (r_b)_3 + (r_t)_1 − (r_b)_3)/3 with (r_t)_1 = (r_b)_3 / t_r,
//                (r_b)_3 the base scene's bottom_radius_mm (9 mm: t_r = 0.5 gives the
//                thesis 3CA, 9 → 12 mm).
// Setting one of a physical/normalised pair (wall_thickness_mm | _normalised, …)
// removes the other from the base, so the scene reader sees exactly one.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "studies/study_spec.hpp"

namespace softarm::studies {

struct StudyPoint {
  int index = 0;                        // position in sweep order (first axis fastest)
  std::vector<nlohmann::json> values;   // one per axis
  std::string key;                      // identity in the results file: the values as canonical JSON
  nlohmann::json scene;                 // the complete scene document for this point
};

/// Every point, first axis varying fastest.
std::vector<StudyPoint> study_points(const StudySpec& spec);

/// Every point's scene read as its evaluation will read it (fem::read_scene_config), before any runs:
/// a sweep value the scene refuses (outside its range, a wall thicker than the radius) throws
/// fem::InputError naming the axis' value (sweep[a].values[j]), the scene's field and why, instead of
/// a point recorded "invalid" in a run that exits 0. (What only meshing finds stays a point's verdict.)
void check_points(const StudySpec& spec, const std::vector<StudyPoint>& points);

/// The base scene with `parameter` set to `value` (throws fem::InputError naming `field`).
nlohmann::json with_parameter(nlohmann::json scene, const std::string& parameter, const nlohmann::json& value,
                              const std::string& field);

/// Index of the curve a point belongs to (the combination of all axes but the first).
int curve_index(const StudySpec& spec, const StudyPoint& point);
/// Words for a curve: "materials.tube = dragon_skin_20" (empty for a single curve).
std::string curve_label(const StudySpec& spec, const StudyPoint& point);
/// The value as text for tables and words (numbers with up to 4 significant digits).
std::string value_text(const nlohmann::json& value);

}  // namespace softarm::studies

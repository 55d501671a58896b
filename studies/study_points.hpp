#pragma once
// The points of a study: the Cartesian product of its sweep axes, each turned
// into a complete scene document by overriding the base scene.
// Each value is set on the base scene by with_parameter (scene_parameter.hpp).
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "studies/scene_parameter.hpp"
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

/// Index of the curve a point belongs to (the combination of all axes but the first).
int curve_index(const StudySpec& spec, const StudyPoint& point);
/// Words for a curve: "materials.tube = dragon_skin_20" (empty for a single curve).
std::string curve_label(const StudySpec& spec, const StudyPoint& point);
}  // namespace softarm::studies

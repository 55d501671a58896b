#pragma once
// A short untapered 3CA for checks against its whole 3D model: the thesis 3CA's distal section
// (r = 9 mm, configs/convergence/tca_thesis_hex20r.json's materials and sizes) over `rings` ring
// pitches of 160/30 mm, chambers 2 and 3 ramped to 150 kPa in `output_count` outputs, no gravity;
// Hex20/P1 at 27 points, level 1, `axial_level`'s layers.
#include <string>

#include "fem/core/json_reader.hpp"
#include "fem/scenes/scene_config.hpp"

namespace softarm::test {

inline fem::TcaSceneSpec untapered_3ca(int rings, int axial_level, int output_count) {
  nlohmann::json j = fem::load_json_file(std::string(SOFTARM_SOURCE_DIR) + "/configs/convergence/tca_thesis_hex20r.json");
  j.erase("description");
  j["geometry"]["length_mm"] = rings * 160.0 / 30;
  j["geometry"]["top_radius_mm"] = 9;
  j["geometry"].erase("ring_count_normalised");
  j["geometry"]["ring_count"] = rings;
  j["mesh"] = {{"level", 1}, {"axial_level", axial_level}, {"element_order", 2}, {"serendipity", true},
               {"reduced_integration", false}};
  j["load"] = {{"chamber_pressures_kPa", {0, 150, 150}}, {"gravity_m_s2", {0, 0, 0}}, {"output_count", output_count}};
  return fem::read_scene_config(j).tca;
}

}  // namespace softarm::test

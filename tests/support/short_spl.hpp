#pragma once
// A short SPL for the arm's cell tests: three 5-ring segments (26.7 mm, the thesis' taper and
// sections), 10 mm connectors, no gravity; chambers 2 and 3 at 150 kPa, 5 and 6 at 120, 7 at 100:
// every segment bends in the x-z plane (a half model). Its 3D model on Hex20/P1 at 27 points, level 1
// with level 1's layers (30,174 dofs, ~25 s); its cells take that mesh where a test says so.
#include <string>

#include "fem/core/json_reader.hpp"
#include "fem/scenes/scene_config.hpp"
#include "fem/scenes/spl_pressure_cells.hpp"

namespace softarm::test {

inline fem::SplSceneSpec short_spl() {
  nlohmann::json j =
      fem::load_json_file(std::string(SOFTARM_SOURCE_DIR) + "/configs/convergence/spl_thesis_pose_hex20.json");
  j.erase("description");
  j["geometry"]["length_mm"] = 5 * 160.0 / 30;
  j["geometry"].erase("ring_count_normalised");
  j["geometry"]["ring_count"] = 5;
  j["geometry"]["connector_thickness_mm"] = 10;
  j["mesh"] = {{"level", 1}, {"axial_level", 1}, {"element_order", 2}, {"serendipity", true}};
  j["load"] = {{"chamber_pressures_kPa", {0, 150, 150, 0, 120, 120, 100, 0, 0}}, {"gravity_m_s2", {0, 0, 0}}, {"output_count", 2}};
  j["output"] = {{"vtu", false}};
  return fem::read_scene_config(j).spl;
}

/// The short SPL's pressure cells over [0, 150] kPa on the one-division grid (3 rays), on level 1's
/// layers (about a minute and a half on 2 cores): made once per test process, shared by the tests.
constexpr double kShortSplPeak_kPa = 150;
constexpr int kShortSplCellLevels = 4;
inline void short_spl_cell_layers(fem::TcaSceneSpec& s) { s.axial_level = 1; }
inline const fem::SplPressureCells& short_spl_pressure_cells() {
  static const fem::SplPressureCells cells =
      fem::spl_pressure_cells(short_spl(), kShortSplPeak_kPa, 1, kShortSplCellLevels, short_spl_cell_layers);
  return cells;
}

}  // namespace softarm::test

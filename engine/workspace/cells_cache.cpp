#include "engine/workspace/cells_cache.hpp"

#include <filesystem>
#include <fstream>

#include <optional>

#include "fem/core/json_reader.hpp"
#include "fem/reduced/pressure_space.hpp"
#include "fem/reduced/cell_tables_json.hpp"
#include "studies/progress_bar.hpp"

namespace softarm::engine {
namespace {
using nlohmann::json;

/// What the cells depend on: the arm, and the grid.
json cells_key(const ArmInput& arm, double max_pressure_kPa, int divisions) {
  json key = arm.cells_key;
  key["max_pressure_kPa"] = max_pressure_kPa;
  key["direction_divisions"] = divisions;
  key["cell_levels"] = fem::kDefaultCellLevels;
  return key;
}

json cells_json(const json& key, const fem::SplPressureCells& cells) {
  json rays = json::array();
  for (const fem::SplCells& r : cells.rays) rays.push_back({{"tables", fem::cell_tables_json(r.rod)}, {"notes", r.notes}});
  return {{"key", key}, {"seconds", cells.seconds}, {"rays", rays}};
}

/// The cells in `j`, or none where it is not for `key` (or not readable as cells).
std::optional<fem::SplPressureCells> read_cells(const json& j, const json& key, const fem::SplSceneSpec& arm,
                                                std::string& why_not) {
  if (!j.contains("key") || j.at("key") != key) {
    why_not = "written for another arm, bound or grid";
    return std::nullopt;
  }
  try {
    fem::SplPressureCells cells;
    cells.max_pressure_kPa = key.at("max_pressure_kPa");
    cells.divisions = key.at("direction_divisions");
    cells.directions = fem::direction_grid(cells.divisions);
    cells.seconds = j.at("seconds");
    for (const json& r : j.at("rays")) {
      fem::SplCells ray;
      fem::read_cell_tables(r.at("tables"), ray.rod);
      ray.rod.gravity_m_s2 = arm.gravity_m_s2;
      ray.rod.tip_mass_kg = arm.tip_mass_kg;
      ray.notes = r.at("notes");
      cells.rays.push_back(std::move(ray));
    }
    if (cells.rays.size() != cells.directions.size()) throw std::runtime_error("one table per ray expected");
    return cells;
  } catch (const std::exception& e) {
    why_not = std::string("unreadable (") + e.what() + ")";
    return std::nullopt;
  }
}
}  // namespace

fem::SplPressureCells cached_pressure_cells(const ArmInput& arm, double max_pressure_kPa, int divisions,
                                            const std::string& cells_file, std::ostream& log) {
  const json key = cells_key(arm, max_pressure_kPa, divisions);
  if (std::filesystem::exists(cells_file)) {
    std::string why_not;
    json j;
    try {
      j = fem::load_json_file(cells_file);
    } catch (const std::exception& e) {
      why_not = e.what();
    }
    if (why_not.empty())
      if (auto cells = read_cells(j, key, arm.spl, why_not)) {
        log << "cells: read from " << cells_file << " (they took " << static_cast<int>(cells->seconds) << " s)\n";
        return *cells;
      }
    log << "cells: " << cells_file << " not used: " << why_not << "; running them again\n";
  }
  log << "cells: the arm's cells along " << fem::direction_grid(divisions).size()
      << " rays of each segment's pressure space, 0 to " << max_pressure_kPa << " kPa\n"
      << std::flush;
  fem::SplPressureCells cells = fem::spl_pressure_cells(arm.spl, max_pressure_kPa, divisions, fem::kDefaultCellLevels,
                                                        {}, studies::task_progress(log, "cells"));
  if (cells.failure.empty()) {
    std::ofstream out(cells_file);
    out << cells_json(key, cells).dump();
    if (!out) log << "cells: could not write " << cells_file << "\n";
  }
  return cells;
}

}  // namespace softarm::engine

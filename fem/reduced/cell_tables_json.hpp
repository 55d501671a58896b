#pragma once
// The spatial cell rod's tables (spatial_cell_rod.hpp) as JSON and back: the pieces with their cells'
// and end cells' tables, so that cells run once can be posed again later (the workspace's cells,
// bench_spl_cell_rod --save-cells). Doubles are written in their shortest round-trip form (nlohmann),
// so the tables come back bit for bit. Gravity and the tip mass are not part of the tables.
#include <nlohmann/json.hpp>

#include "fem/reduced/spatial_cell_rod.hpp"

namespace softarm::fem {

nlohmann::json cell_tables_json(const SpatialCellRodSpec& rod);
/// Replaces rod.pieces with those of `j`; throws nlohmann::json::exception where a key is missing.
void read_cell_tables(const nlohmann::json& j, SpatialCellRodSpec& rod);

}  // namespace softarm::fem

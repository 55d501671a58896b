#pragma once
// The workspace's HTML report: the reached tips in three projections (seen from above, from the front
// and from the side), coloured in four bands of a quantity (the pressure sum or the tip's tilt), with
// the extent, the occupied volume and the cost in a table.
#include <string>

#include "studies/workspace.hpp"

namespace softarm::engine {

/// Writes the report to `path`; `colour_by`: "pressure_sum" or "tip_tilt"; `scene` names the config.
void write_workspace_report(const std::string& path, const studies::WorkspaceResult& w, const std::string& colour_by,
                            const std::string& scene);

}  // namespace softarm::engine

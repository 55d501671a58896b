#pragma once
// The payload margin over a workspace's poses (engine/workspace/reach.hpp, payload_margin), computed at
// a subsample only: a continuation in the tip mass costs about 40 s a pose on the thesis arm, against
// milliseconds for the pose itself.
#include <cstddef>
#include <optional>
#include <vector>

#include "fem/core/parallel.hpp"
#include "fem/scenes/spl_pressure_cells.hpp"
#include "studies/workspace.hpp"

namespace softarm::engine {

/// Poses whose payload margin a report coloured by it computes, unless told: a few minutes on the thesis arm.
constexpr int kDefaultMarginPoses = 24;

/// The poses whose margin is computed: the first `count` reached after the 512 corners (the sequence's,
/// spread over the pressure space), then, for a short sweep, the first reached corners; indices into
/// the sweep's points.
std::vector<std::size_t> margin_poses(const studies::WorkspaceResult& workspace, int count);

/// The payload margin at margin_poses(workspace, count), side by side on this process' threads: each
/// pose's own pressures hold its tip there with the payload, and payload_margin searches on from them
/// (one branch). Fills those points' payload_margin_kg and payload_margin_at_least; returns the seconds.
double margins_at_poses(const fem::SplPressureCells& cells, studies::WorkspaceResult& workspace, int count,
                        const std::optional<double>& payload_kg, const fem::TaskProgress& progress = {});

}  // namespace softarm::engine

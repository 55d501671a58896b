#pragma once
// An arm's workspace: the tip positions and axes its nine chamber pressures reach within [0, P], on
// its pressure cells (fem/scenes/spl_pressure_cells.hpp), under the cells' gravity and a payload.
//
// The pressures visited (workspace_pressures): every corner of [0, P]⁹ first (512: the extremes of
// the pressure space, where the workspace's boundary mostly lies), then Roberts' R₉ sequence,
// xᵢ = frac(½ + i·α), α_d = g^−(d+1) with g the real root of g¹⁰ = g + 1 above 1: a Kronecker
// sequence of low discrepancy in every projection, deterministic, and extensible (the first N of a
// longer run are the N of a shorter one).
//
// Its size: the extent (the box of the reached tips) and the occupied volume, the volume of the cubes
// of edge `voxel_mm` holding a reached tip: a lower estimate of the reachable volume at that
// resolution, which grows with the samples until each cube inside is hit.
//
// Its peak stretch (judge_workspace_peaks): in each pose, each segment's largest chamber-axis stretch
// (fem/scenes/chamber_stretch.hpp) read through that segment's lone-RRA FEM map to the tube's local
// peak principal stretch, averaged over the criteria's ball (fem/scenes/tube_peaks.hpp).
#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "fem/core/parallel.hpp"
#include "fem/scenes/tube_peaks.hpp"
#include "fem/scenes/spl_pressure_cells.hpp"

namespace softarm::studies {

/// The corners of [0, P]⁹, 2⁹, that the sampling visits first.
inline constexpr int kWorkspaceCorners = 512;

/// The first `count` pressure vectors (kPa) of the workspace's sampling in [0, max]⁹.
std::vector<std::array<double, 9>> workspace_pressures(double max_kPa, int count);

struct WorkspaceSettings {
  int samples = 10000;                  // pressure vectors, corners included
  std::optional<double> payload_kg;     // at the tip (else the scene's tip mass)
  double voxel_mm = 10;                 // the occupied volume's cube edge
  /// The rod's integration interval in the sweep: 1 mm, against the rod's 0.5 mm elsewhere. On the thesis
  /// arm that is 2.6 times the poses per second, its tips within 0.4 mm of the finer rod's
  /// (bench_workspace --interval-mm 1; docs/workspace.md): far below the cubes the volume counts.
  double rod_interval_mm = 1.0;
  /// The arm's design, where the poses' chamber stretches are wanted (judge_workspace_peaks).
  std::optional<fem::SplDesign> design;
};

struct WorkspacePoint {
  std::array<double, 9> pressure_kPa{};
  bool ok = false;
  std::string why;                      // where not ok: outside the cells' reach, or no equilibrium
  bool beyond_cells = false;            // not ok because a segment lies past where its cells reached
  Eigen::Vector3d tip_mm = Eigen::Vector3d::Zero();
  Eigen::Vector3d tip_axis = Eigen::Vector3d::Zero();  // the tip face's outward normal (unit)
  double tip_tilt_deg = 0;              // from hanging straight down the rest axis
  double pressure_sum_kPa = 0;
  std::array<double, 3> chamber_stretch{1, 1, 1};  // per segment, its chambers' largest axial stretch
  fem::TubePeak peak;                   // the tube's peak stretch (judge_workspace_peaks; segment 0: not judged)
  /// The extra tip mass the arm still holds at this tip position (engine/workspace/reach.hpp,
  /// payload_margin), where it was computed; `at_least` where the bracket's end still held.
  std::optional<double> payload_margin_kg;
  bool payload_margin_at_least = false;
};

struct WorkspaceResult {
  std::vector<WorkspacePoint> points;
  int reached = 0;
  Eigen::Vector3d lower_mm = Eigen::Vector3d::Zero(), upper_mm = Eigen::Vector3d::Zero();  // the extent
  double occupied_volume_mm3 = 0;
  double pose_seconds = 0;              // wall time of the poses
  double poses_per_second = 0;
};

/// The workspace of `cells` at settings' samples, posed side by side on this process' threads.
WorkspaceResult sweep_workspace(const fem::SplPressureCells& cells, const WorkspaceSettings& settings,
                                const fem::TaskProgress& progress = {});

/// Fills every reached point's peak stretch from its chamber stretches (the sweep's, with a design) on
/// the maps of `arm`'s segments (fem/scenes/tube_peaks.hpp), each lone RRA's path covering the largest
/// chamber stretch of its segment over the poses and at most `max_pressure_kPa`; returns the maps.
fem::TubePeakMaps judge_workspace_peaks(WorkspaceResult& workspace, const fem::SplSceneSpec& arm,
                                        double max_pressure_kPa, int rra_mesh_level = 1,
                                        double averaging_radius_mm = fem::kDefaultPeakAveragingRadius_mm);

/// The poses whose centrelines a run draws: rest (the first sample, workspace_pressures), and the
/// reached poses at each end of the extent in x, y and z, in that order, a pose twice only once;
/// indices into the sweep's points.
std::vector<std::size_t> extent_poses(const WorkspaceResult& workspace);

}  // namespace softarm::studies

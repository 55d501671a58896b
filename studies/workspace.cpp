#include "studies/workspace.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>
#include <tuple>

#include "fem/scenes/chamber_stretch.hpp"
#include "fem/core/angles.hpp"

namespace softarm::studies {
namespace {
using fem::kDeg;

/// g with g¹⁰ = g + 1, g > 1 (Newton from 1.1): the generalised golden ratio of Roberts' R₉.
double roberts_ratio() {
  double g = 1.1;
  for (int i = 0; i < 60; ++i) g -= (std::pow(g, 10) - g - 1) / (10 * std::pow(g, 9) - 1);
  return g;
}

/// The cubes of edge h holding a reached tip, times h³.
double occupied_volume_mm3(const std::vector<WorkspacePoint>& points, double h) {
  std::set<std::tuple<long long, long long, long long>> cubes;
  for (const WorkspacePoint& p : points)
    if (p.ok)
      cubes.emplace(std::llround(std::floor(p.tip_mm.x() / h)), std::llround(std::floor(p.tip_mm.y() / h)),
                    std::llround(std::floor(p.tip_mm.z() / h)));
  return static_cast<double>(cubes.size()) * h * h * h;
}

WorkspacePoint pose_point(const fem::SplPressureCells& cells, const std::array<double, 9>& p,
                          const WorkspaceSettings& settings) {
  const std::optional<double>& payload_kg = settings.payload_kg;
  WorkspacePoint out;
  out.pressure_kPa = p;
  for (double x : p) out.pressure_sum_kPa += x;
  const fem::SpatialCellRodState s = fem::pose_at_pressures(cells, p, nullptr, payload_kg);
  out.ok = s.ok;
  if (!s.ok) {
    out.why = s.diagnosis;
    out.beyond_cells = s.beyond_tables;
    return out;
  }
  out.tip_mm = s.position.back();
  // d3 (+z at rest) points from the tip towards the clamp: the tip face's outward normal is −d3.
  // (+ 0: no "-0" in the outputs where an entry is zero.)
  out.tip_axis = (-s.frame.back().col(2)).array() + 0.0;
  out.tip_tilt_deg = std::acos(std::clamp(s.frame.back().col(2).z(), -1.0, 1.0)) * kDeg;
  // The pieces' lengths and caps are every ray's (rod_at_pressures changes the cells' tables only).
  if (settings.design) out.chamber_stretch = fem::chamber_axis_stretch(*settings.design, cells.rays.front().rod, s);
  return out;
}
}  // namespace

std::vector<std::array<double, 9>> workspace_pressures(double max_kPa, int count) {
  std::vector<std::array<double, 9>> out;
  for (int corner = 0; corner < kWorkspaceCorners && static_cast<int>(out.size()) < count; ++corner) {
    std::array<double, 9> p{};
    for (int k = 0; k < 9; ++k) p[k] = (corner >> k) & 1 ? max_kPa : 0.0;
    out.push_back(p);
  }
  const double g = roberts_ratio();
  std::array<double, 9> alpha{};
  for (int d = 0; d < 9; ++d) alpha[d] = std::pow(g, -(d + 1));
  for (long long i = 1; static_cast<int>(out.size()) < count; ++i) {
    std::array<double, 9> p{};
    for (int d = 0; d < 9; ++d) {
      const double x = 0.5 + static_cast<double>(i) * alpha[d];
      p[d] = max_kPa * (x - std::floor(x));
    }
    out.push_back(p);
  }
  return out;
}

WorkspaceResult sweep_workspace(const fem::SplPressureCells& cells, const WorkspaceSettings& settings,
                                const fem::TaskProgress& progress) {
  WorkspaceResult out;
  // The rods at any pressures take the first ray's interval (spl_pressure_cells.cpp, rod_at_pressures).
  fem::SplPressureCells sweep_cells = cells;
  if (!sweep_cells.rays.empty()) sweep_cells.rays.front().rod.interval_mm = settings.rod_interval_mm;
  const auto pressures = workspace_pressures(cells.max_pressure_kPa, settings.samples);
  out.points.resize(pressures.size());
  const auto t0 = std::chrono::steady_clock::now();
  // Poses in blocks, so that each task is long enough to pay for its scheduling and the progress
  // line is not redrawn ten thousand times.
  constexpr int kBlock = 250;
  const int n = static_cast<int>(pressures.size()), blocks = (n + kBlock - 1) / kBlock;
  fem::parallel_tasks(
      blocks,
      [&](int b) {
        for (int i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i)
          out.points[i] = pose_point(sweep_cells, pressures[i], settings);
      },
      progress);
  out.pose_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out.poses_per_second = out.pose_seconds > 0 ? n / out.pose_seconds : 0;
  bool first = true;
  for (const WorkspacePoint& p : out.points) {
    if (!p.ok) continue;
    ++out.reached;
    out.lower_mm = first ? p.tip_mm : Eigen::Vector3d(out.lower_mm.cwiseMin(p.tip_mm));
    out.upper_mm = first ? p.tip_mm : Eigen::Vector3d(out.upper_mm.cwiseMax(p.tip_mm));
    first = false;
  }
  out.occupied_volume_mm3 = occupied_volume_mm3(out.points, settings.voxel_mm);
  return out;
}

fem::TubePeakMaps judge_workspace_peaks(WorkspaceResult& w, const fem::SplSceneSpec& arm, double max_pressure_kPa,
                                        int rra_mesh_level, double averaging_radius_mm) {
  std::array<double, 3> largest{1, 1, 1};
  for (const WorkspacePoint& p : w.points)
    if (p.ok)
      for (int n = 0; n < 3; ++n) largest[n] = std::max(largest[n], p.chamber_stretch[n]);
  const fem::TubePeakMaps maps = fem::tube_peak_maps(arm, largest, max_pressure_kPa, rra_mesh_level, averaging_radius_mm);
  for (WorkspacePoint& p : w.points)
    if (p.ok) p.peak = maps.at(p.chamber_stretch);
  return maps;
}

std::vector<std::size_t> extent_poses(const WorkspaceResult& w) {
  std::vector<std::size_t> chosen;
  const auto add = [&](std::size_t i) {
    if (w.points[i].ok && std::find(chosen.begin(), chosen.end(), i) == chosen.end()) chosen.push_back(i);
  };
  if (!w.points.empty()) add(0);
  for (int axis = 0; axis < 3; ++axis) {
    std::size_t low = 0, high = 0;
    bool any = false;
    for (std::size_t i = 0; i < w.points.size(); ++i) {
      if (!w.points[i].ok) continue;
      if (!any || w.points[i].tip_mm[axis] < w.points[low].tip_mm[axis]) low = i;
      if (!any || w.points[i].tip_mm[axis] > w.points[high].tip_mm[axis]) high = i;
      any = true;
    }
    if (any) add(low), add(high);
  }
  return chosen;
}

}  // namespace softarm::studies

// The workspace and reach on an arm's pressure cells (engine/workspace/): poses per second on one
// thread and on all, the workspace of --samples poses, and the thesis' arbitrary pose (§7: chambers 2,
// 3 at 345 kPa, 5 at 86, 6 at 345, 9 at 59) found again by reach from its tip. The cells come from
// --cells (a `softarm workspace` run's cells.json for the same scene), else they are run (minutes)
// and kept there.
//
//   bench_workspace [scene] [--cells F] [--directions N] [--samples N] [--threads N] [--interval-mm H] [--pose p1,...,p9]
//   --pose: also the tip at these nine pressures (kPa), e.g. a reach solution to run in 3D
//   --interval-mm H: also the workspace with the rod integrated over intervals of H mm (its default
//     is 0.5 mm): poses per second and the largest tip difference from the default's
#include <algorithm>
#include <array>
#include <chrono>
#include <iomanip>
#include <iostream>
#include <vector>

#include "benchmarks/bench_options.hpp"
#include "engine/workspace/cells_cache.hpp"
#include "engine/workspace/reach.hpp"
#include "fem/core/input_error.hpp"
#include "fem/core/parallel.hpp"
#include "fem/core/thesis_values.hpp"
#include "studies/workspace.hpp"

using namespace softarm;

int main(int argc, char** argv) try {
  std::string scene = "configs/spl_thesis_pose.json", cells_file = "out/workspace/cells.json";
  int samples = 10000, threads = fem::thread_count(), divisions = 1;
  double interval_mm = 0;
  std::vector<double> pose;
  CLI::App app{"the workspace and reach on an arm's pressure cells: poses per second, the thesis pose found again"};
  app.add_option("scene", scene, "an spl scene config or a requirements file");
  app.add_option("--cells", cells_file, "the pressure cells' file (read where it matches, else written)");
  app.add_option("--samples", samples, "poses of the workspace")->check(CLI::Range(1, 1000000));
  app.add_option("--threads", threads, "threads for the workspace's second sweep")->check(CLI::Range(1, 256));
  app.add_option("--interval-mm", interval_mm, "also integrate the rod over intervals of this length")
      ->check(bench::Positive)
      ->default_str("none");
  app.add_option("--directions", divisions, "divisions of each segment's direction grid of the cells")
      ->check(CLI::Range(1, 4))
      ->capture_default_str();
  app.add_option("--pose", pose, "also the tip at these nine pressures, kPa")->delimiter(',')->expected(9)->check(bench::Finite);
  if (const auto code = bench::parse_or_exit(app, argc, argv)) return *code;
  const engine::ArmInput arm = engine::read_arm_input(scene);
  const fem::SplPressureCells cells = engine::cached_pressure_cells(
      arm, arm.max_pressure_kPa.value_or(fem::thesis::kWorkingPressure_kPa), divisions, cells_file, std::cout);
  if (!cells.failure.empty()) {
    std::cout << "no cells: " << cells.failure << "\n";
    return 1;
  }
  std::cout << std::fixed << std::setprecision(1) << "cells: " << cells.seconds << " s for " << cells.rays.size() << " rays\n";
  studies::WorkspaceSettings settings;
  settings.samples = samples;
  for (int t : {1, threads}) {
    fem::set_thread_count(t);
    const studies::WorkspaceResult w = studies::sweep_workspace(cells, settings);
    std::cout << std::setprecision(2) << "workspace, " << t << " thread(s): " << w.reached << " of " << w.points.size()
              << " poses in " << w.pose_seconds << " s, " << std::setprecision(0) << w.poses_per_second
              << " poses/s; extent " << std::setprecision(1) << w.lower_mm.transpose() << " to " << w.upper_mm.transpose()
              << " mm; occupied " << std::setprecision(2) << w.occupied_volume_mm3 * 1e-6 << " L at 10 mm cubes\n";
  }
  if (!pose.empty()) {
    std::array<double, 9> p{};
    std::copy(pose.begin(), pose.end(), p.begin());
    const fem::SpatialCellRodState s = fem::pose_at_pressures(cells, p);
    std::cout << std::setprecision(2) << "pose: ";
    if (s.ok) std::cout << "tip " << s.position.back().transpose() << " mm, rest tip " << fem::pose_at_pressures(cells, {}).position.back().transpose() << " mm\n";
    else std::cout << s.diagnosis << "\n";
  }
  if (interval_mm > 0) {
    fem::set_thread_count(1);
    studies::WorkspaceSettings fine_settings = settings, coarse_settings = settings;
    fine_settings.rod_interval_mm = cells.rays.front().rod.interval_mm;  // the rod's own
    coarse_settings.rod_interval_mm = interval_mm;
    const studies::WorkspaceResult fine = studies::sweep_workspace(cells, fine_settings);
    const studies::WorkspaceResult w = studies::sweep_workspace(cells, coarse_settings);
    double largest = 0;
    for (std::size_t i = 0; i < w.points.size(); ++i)
      if (w.points[i].ok && fine.points[i].ok) largest = std::max(largest, (w.points[i].tip_mm - fine.points[i].tip_mm).norm());
    std::cout << std::setprecision(2) << "intervals of " << interval_mm << " mm, 1 thread: " << w.pose_seconds << " s, "
              << std::setprecision(0) << w.poses_per_second << " poses/s (" << fine.poses_per_second << " at "
              << std::setprecision(2) << fine_settings.rod_interval_mm << " mm); tips at most " << std::setprecision(3) << largest
              << " mm from the default's\n";
  }
  // The thesis' arbitrary pose, forward and back.
  const std::array<double, 9> thesis = {0, 345, 345, 0, 86, 345, 0, 0, 59};
  std::array<double, 9> p = thesis;
  for (double& x : p) x = std::min(x, cells.max_pressure_kPa);
  const fem::SpatialCellRodState forward = fem::pose_at_pressures(cells, p);
  if (!forward.ok) {
    std::cout << "thesis pose: " << forward.diagnosis << "\n";
    return 1;
  }
  engine::ReachTarget target{"thesis pose", forward.position.back(), {}};
  const engine::ReachResult r = engine::reach(cells, target, {});
  std::cout << std::setprecision(1) << "thesis pose: tip " << target.position_mm.transpose() << " mm at "
            << "0, 344.7, 344.7, 0, 86, 344.7, 0, 0, 59 kPa\n"
            << "reach: " << (r.reachable ? "reached" : "NOT reached") << ", " << r.solutions.size()
            << " distinct solution(s), " << r.evaluations << " rod solves in " << std::setprecision(2) << r.seconds << " s\n";
  for (const auto& s : r.solutions) {
    std::cout << "  " << std::setprecision(4) << s.distance_mm << " mm off at";
    for (double x : s.pressure_kPa) std::cout << " " << std::setprecision(1) << x;
    std::cout << " kPa\n";
  }
  return 0;
} catch (const fem::InputError& e) {
  std::cerr << e.what() << "\n";
  return 2;
}

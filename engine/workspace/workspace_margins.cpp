#include "engine/workspace/workspace_margins.hpp"

#include <algorithm>
#include <chrono>

#include "engine/workspace/reach.hpp"

namespace softarm::engine {

std::vector<std::size_t> margin_poses(const studies::WorkspaceResult& w, int count) {
  constexpr auto kCorners = static_cast<std::size_t>(studies::kWorkspaceCorners);
  std::vector<std::size_t> chosen;
  const auto full = [&] { return static_cast<int>(chosen.size()) >= count; };
  for (std::size_t i = kCorners; i < w.points.size() && !full(); ++i)
    if (w.points[i].ok) chosen.push_back(i);
  for (std::size_t i = 0; i < std::min(kCorners, w.points.size()) && !full(); ++i)
    if (w.points[i].ok) chosen.push_back(i);
  return chosen;
}

double margins_at_poses(const fem::SplPressureCells& cells, studies::WorkspaceResult& w, int count,
                        const std::optional<double>& payload_kg, const fem::TaskProgress& progress) {
  const std::vector<std::size_t> chosen = margin_poses(w, count);
  ReachSettings settings;
  settings.payload_kg = payload_kg;
  PayloadMarginSettings margin;
  margin.max_branches = 1;
  const auto t0 = std::chrono::steady_clock::now();
  fem::parallel_tasks(
      static_cast<int>(chosen.size()),
      [&](int k) {
        studies::WorkspacePoint& p = w.points[chosen[k]];
        ReachResult here;
        here.reachable = true;
        ReachSolution own;
        own.pressure_kPa = p.pressure_kPa;
        own.tip_mm = p.tip_mm;
        here.solutions = {own};
        const PayloadMargin m = payload_margin(cells, {"pose", p.tip_mm, {}}, settings, here, margin);
        p.payload_margin_kg = m.margin_kg;
        p.payload_margin_at_least = m.at_least;
      },
      progress);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace softarm::engine

#include "fem/scenes/spl_pressure_cells.hpp"

#include <algorithm>
#include <chrono>
#include <sstream>

#include "fem/reduced/cell_interpolation.hpp"
#include "fem/reduced/pressure_space.hpp"

namespace softarm::fem {
namespace {

/// Every segment's chambers at P·(1, a, b).
SplSceneSpec ray_scene(const SplSceneSpec& spec, double max_pressure_kPa, const Eigen::Vector2d& direction) {
  SplSceneSpec s = spec;
  for (int n = 0; n < 3; ++n) {
    s.chamber_pressure_kPa[3 * n] = max_pressure_kPa;
    s.chamber_pressure_kPa[3 * n + 1] = max_pressure_kPa * direction.x();
    s.chamber_pressure_kPa[3 * n + 2] = max_pressure_kPa * direction.y();
  }
  return s;
}

/// The rays' torsion at rest, taken from the first ray (the others skip it).
void copy_torsion(const SplCells& from, SplCells& to) {
  for (std::size_t i = 0; i < from.rod.pieces.size(); ++i) {
    auto& cells = to.rod.pieces[i].cells;
    for (std::size_t c = 0; c < cells.size(); ++c)
      cells[c].torsion_compliance_per_Nmm2 = from.rod.pieces[i].cells[c].torsion_compliance_per_Nmm2;
    auto& ends = to.rod.pieces[i].ends;
    for (std::size_t e = 0; e < ends.size(); ++e) ends[e].twist_compliance_per_Nmm = from.rod.pieces[i].ends[e].twist_compliance_per_Nmm;
  }
}

/// One segment's reading of the rays at its own pressures.
struct SegmentReading {
  double level = 0;                        // s / P
  std::vector<std::pair<int, double>> rays;  // (ray, weight)
  Eigen::Matrix2d axial_map = Eigen::Matrix2d::Identity();
};

/// Σ_r w_r · (the column at `level` of ray r's table `column`), or nothing where a ray did not reach it.
template <class T, class Column>
std::optional<T> blend(const SegmentReading& at, const Column& column) {
  std::optional<T> sum;
  for (const auto& [ray, weight] : at.rays) {
    const auto& [levels, values] = column(ray);
    const std::optional<T> v = along_ramp(levels, values, at.level);
    if (!v) return std::nullopt;
    sum = sum ? T(*sum + weight * *v) : T(weight * *v);
  }
  return sum;
}

/// Ray 0's table with its ramp replaced by two levels: rest (0) and the blended state (1).
bool blend_cell(const SplPressureCells& cells, std::size_t piece, std::size_t c, const SegmentReading& at,
                SpatialCellTable& out) {
  const auto table = [&](int ray) -> const SpatialCellTable& { return cells.rays[ray].rod.pieces[piece].cells[c]; };
  const auto stretch = blend<double>(at, [&](int r) { return std::tie(table(r).level, table(r).stretch); });
  const auto axial = blend<double>(at, [&](int r) { return std::tie(table(r).level, table(r).axial_compliance_per_N); });
  const auto curvature = blend<Eigen::Vector2d>(at, [&](int r) { return std::tie(table(r).level, table(r).curvature_per_mm); });
  const auto bending = blend<Eigen::Matrix2d>(
      at, [&](int r) { return std::tie(table(r).level, table(r).bending_compliance_per_Nmm2); });
  if (!stretch || !axial || !curvature || !bending) return false;
  const SpatialCellTable& rest = table(0);
  out = rest;
  out.level = {0.0, 1.0};
  out.stretch = {rest.stretch.front(), *stretch};
  out.axial_compliance_per_N = {rest.axial_compliance_per_N.front(), *axial};
  out.curvature_per_mm = {rest.curvature_per_mm.front(), at.axial_map * *curvature};
  out.bending_compliance_per_Nmm2 = {rest.bending_compliance_per_Nmm2.front(),
                                     at.axial_map * *bending * at.axial_map.transpose()};
  return true;
}

bool blend_end(const SplPressureCells& cells, std::size_t piece, std::size_t e, const SegmentReading& at,
               SpatialEndTable& out) {
  const auto table = [&](int ray) -> const SpatialEndTable& { return cells.rays[ray].rod.pieces[piece].ends[e]; };
  const auto elongation = blend<double>(at, [&](int r) { return std::tie(table(r).level, table(r).elongation_mm); });
  const auto rotation = blend<Eigen::Vector2d>(at, [&](int r) { return std::tie(table(r).level, table(r).rotation_rad); });
  if (!elongation || !rotation) return false;
  const SpatialEndTable& rest = table(0);
  out = rest;
  out.level = {0.0, 1.0};
  out.elongation_mm = {rest.elongation_mm.front(), *elongation};
  out.rotation_rad = {rest.rotation_rad.front(), at.axial_map * *rotation};
  return true;
}
}  // namespace

SplPressureCells spl_pressure_cells(const SplSceneSpec& spec, double max_pressure_kPa, int divisions, int cell_levels,
                                    const std::function<void(TcaSceneSpec&)>& adjust, const TaskProgress& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  SplPressureCells out;
  out.max_pressure_kPa = max_pressure_kPa;
  out.divisions = divisions;
  out.directions = direction_grid(divisions);
  const int rays = static_cast<int>(out.directions.size());
  for (int r = 0; r < rays; ++r) {
    // One bar over all the rays' tasks: each ray's count offset by the rays before it.
    const TaskProgress ray_progress = progress ? TaskProgress([&, r](int done, int total) { progress(r * total + done, rays * total); })
                                               : TaskProgress{};
    out.rays.push_back(spl_cells(ray_scene(spec, max_pressure_kPa, out.directions[r]), cell_levels, adjust, r == 0, {},
                                 ray_progress));
    if (!out.rays.back().failure.empty()) {
      out.failure = out.rays.back().failure;
      return out;
    }
    if (r > 0) copy_torsion(out.rays.front(), out.rays.back());
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

double segment_reach_kPa(const SplPressureCells& cells, int n) {
  double reach = cells.max_pressure_kPa;
  for (const SplCells& ray : cells.rays) {
    int segment = -1;
    for (const SpatialCellPiece& piece : ray.rod.pieces) {
      if (piece.cells.empty()) continue;  // a connector
      if (++segment != n) continue;
      for (const SpatialCellTable& c : piece.cells) reach = std::min(reach, c.level.back() * cells.max_pressure_kPa);
      for (const SpatialEndTable& e : piece.ends) reach = std::min(reach, e.level.back() * cells.max_pressure_kPa);
    }
  }
  return reach;
}

PressureRod rod_at_pressures(const SplPressureCells& cells, const std::array<double, 9>& p) {
  PressureRod out;
  if (!cells.failure.empty() || cells.rays.empty()) {
    out.why = cells.failure.empty() ? "no cells" : cells.failure;
    return out;
  }
  const double bound = cells.max_pressure_kPa * (1 + 1e-12);
  for (int k = 0; k < 9; ++k)
    if (!(p[k] >= 0 && p[k] <= bound)) {
      std::ostringstream why;
      why << "chamber " << k + 1 << " at " << p[k] << " kPa: outside the cells' range [0, " << cells.max_pressure_kPa << "] kPa";
      out.why = why.str();
      return out;
    }
  out.rod = cells.rays.front().rod;
  for (std::size_t piece = 0, n = 0; piece < out.rod.pieces.size(); ++piece) {
    SpatialCellPiece& target = out.rod.pieces[piece];
    if (target.cells.empty()) continue;  // a connector
    const CanonicalPressures c = canonical_pressures({p[3 * n], p[3 * n + 1], p[3 * n + 2]});
    const SegmentReading at{c.peak_kPa / cells.max_pressure_kPa, direction_weights(cells.divisions, c.a, c.b), c.axial_map};
    bool reached = true;
    for (std::size_t i = 0; i < target.cells.size() && reached; ++i) reached = blend_cell(cells, piece, i, at, target.cells[i]);
    for (std::size_t e = 0; e < target.ends.size() && reached; ++e) reached = blend_end(cells, piece, e, at, target.ends[e]);
    if (!reached) {
      std::ostringstream why;
      why << "segment " << n + 1 << " at " << p[3 * n] << ", " << p[3 * n + 1] << ", " << p[3 * n + 2]
          << " kPa: beyond where its cells reached along the nearby rays (a limit point or a stall)";
      out.why = why.str();
      out.beyond_cells = true;
      return out;
    }
    ++n;
  }
  out.ok = true;
  return out;
}

SpatialCellRodState pose_at_pressures(const SplPressureCells& cells, const std::array<double, 9>& p,
                                      const SpatialCellRodState* start, std::optional<double> tip_mass_kg) {
  PressureRod r = rod_at_pressures(cells, p);
  if (!r.ok) {
    SpatialCellRodState s;
    s.diagnosis = r.why;
    s.beyond_tables = r.beyond_cells;
    return s;
  }
  if (tip_mass_kg) r.rod.tip_mass_kg = *tip_mass_kg;
  return solve_spatial_cell_rod(r.rod, 1.0, start);
}

}  // namespace softarm::fem

#include "objectives/cell_rod_evaluation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "fem/core/number_text.hpp"
#include "fem/scenes/spl_cell_rod.hpp"
#include "fem/scenes/solver_work_json.hpp"
#include "objectives/solid_segment_check.hpp"
#include "fem/core/angles.hpp"

namespace softarm::objectives {
namespace {
using Clock = std::chrono::steady_clock;
using fem::kDeg;
// The payload's lift: the tip's turn between two load levels (1/32 of the ramp) above which the arm is
// taken to snap through a fold (payload_capacity.cpp rejects tip jumps of over 20 deg likewise).
constexpr double kMaxTurnPerLevel_deg = 20;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

}  // namespace

// The path settings are those of every 3D check of a design (use_design_check_path).
fem::SplSceneSpec arm_cell_scene(const ArmCandidate& c, const EvaluationSettings& s) {
  fem::SplSceneSpec spec;
  spec.design = c.design;
  spec.tube_material = c.tube;
  spec.ring_material = c.rings;
  spec.sheath_material = c.sheath;
  spec.connector_material = c.connector;
  for (int n = 0; n < 3; ++n) {
    spec.chamber_pressure_kPa[3 * n + 1] = s.working_pressure_kPa;
    spec.chamber_pressure_kPa[3 * n + 2] = s.working_pressure_kPa;
  }
  spec.gravity_m_s2 = Eigen::Vector3d(0, 0, -s.gravity_m_s2);
  use_design_check_path(spec.steps, spec.limit);
  return spec;
}

namespace {

/// The highest load level every table of `pieces` covers (a cell that stopped short ends its table there).
double covered_level(const std::vector<fem::SpatialCellPiece>& pieces) {
  double level = 1;
  for (const auto& p : pieces) {
    for (const auto& t : p.cells) level = std::min(level, t.level.empty() ? 0.0 : t.level.back());
    for (const auto& t : p.ends) level = std::min(level, t.level.empty() ? 0.0 : t.level.back());
  }
  return level;
}

/// Levels 0, 1/n, 2/n, … up to `top`, `top` itself last.
std::vector<double> level_grid(int n, double top) {
  std::vector<double> levels;
  for (int k = 0; k <= n && static_cast<double>(k) / n < top - 1e-12; ++k) levels.push_back(static_cast<double>(k) / n);
  levels.push_back(top);
  return levels;
}

/// The tip axis' turn from rest towards the horizontal unit vector `bend` (the rod hangs from its
/// clamp along −z; d3 = +z at rest, so the downward tangent −d3 = (sin θ·bend, −cos θ)).
double turn_towards_deg(const fem::SpatialCellRodState& s, const Eigen::Vector3d& bend) {
  const Eigen::Vector3d d3 = s.frame.back().col(2);
  return std::atan2(-d3.dot(bend), d3.z()) * kDeg;
}

/// The tip axis' angle from vertical (the hanging arm's lift angle).
double tilt_deg(const fem::SpatialCellRodState& s) {
  return std::acos(std::clamp(s.frame.back().col(2).z(), -1.0, 1.0)) * kDeg;
}

/// Segment n alone on its own cells, top clamped, gravity perpendicular to the axis against the bend:
/// its bending path at the cells' levels, and the largest pressurised-chamber stretch at each.
void bend_segment_on_cells(const fem::SplCells& cells, const ArmCandidate& c, const EvaluationSettings& s, int n,
                           int cell_levels, SegmentMeasures& out, std::vector<double>& chamber_stretch, int& poses) {
  fem::SpatialCellRodSpec rod;
  rod.pieces = {cells.rod.pieces.at(static_cast<std::size_t>(2 * n + 1))};
  const double top = covered_level(rod.pieces);
  // The bend's direction: where the pressures alone turn the tip.
  Eigen::Vector3d bend(1, 0, 0);
  if (top > 0) {
    const fem::SpatialCellRodState free = fem::solve_spatial_cell_rod(rod, top);
    ++poses;
    const Eigen::Vector3d tip = free.ok ? free.position.back() : Eigen::Vector3d::Zero();
    if (tip.head<2>().norm() > 1e-9) bend = Eigen::Vector3d(tip.x(), tip.y(), 0).normalized();
  }
  rod.gravity_m_s2 = -s.gravity_m_s2 * bend;
  const fem::TcaDesign& design = c.design.segments[static_cast<std::size_t>(n)];
  fem::SpatialCellRodState last;
  for (double t : level_grid(cell_levels, top)) {
    const fem::SpatialCellRodState st = fem::solve_spatial_cell_rod(rod, t, last.ok ? &last : nullptr);
    ++poses;
    if (!st.ok) {
      out.rod_diagnosis = st.diagnosis;
      break;
    }
    last = st;
    const double p = t * s.working_pressure_kPa;
    double angle = turn_towards_deg(st, bend);  // past 180 deg: unwrapped against the last level's
    if (!out.bending_deg.empty()) angle += 360 * std::round((out.bending_deg.back() - angle) / 360);
    if (!out.bending_deg.empty() && out.pressure_for_target_kPa < 0 && angle >= s.target_bending_deg) {
      const double a0 = out.bending_deg.back(), p0 = out.pressure_kPa.back();
      out.pressure_for_target_kPa = p0 + (s.target_bending_deg - a0) * (p - p0) / (angle - a0);
    }
    out.pressure_kPa.push_back(p);
    out.bending_deg.push_back(angle);
    // Chambers 2 and 3 lie R_c/2 from the neutral plane on the stretched side: λ₀ + |κ₀|·R_c/2, the
    // largest over the segment's cells (each table read at this level, linearly).
    double stretch = 1;
    for (const fem::SpatialCellTable& cell : rod.pieces[0].cells) {
      if (cell.level.empty()) continue;
      double lambda = cell.stretch.front(), kappa = cell.curvature_per_mm.front().norm();
      if (cell.level.size() >= 2) {
        const auto hi = std::lower_bound(cell.level.begin(), cell.level.end(), t);
        const std::size_t i = std::clamp<std::size_t>(static_cast<std::size_t>(hi - cell.level.begin()), 1,
                                                       cell.level.size() - 1);
        const double w = (t - cell.level[i - 1]) / (cell.level[i] - cell.level[i - 1]);
        lambda = cell.stretch[i - 1] + w * (cell.stretch[i] - cell.stretch[i - 1]);
        kappa = cell.curvature_per_mm[i - 1].norm() + w * (cell.curvature_per_mm[i].norm() - cell.curvature_per_mm[i - 1].norm());
      }
      stretch = std::max(stretch, lambda + kappa * design.axis_distance(cell.z_mm) / 2);
    }
    chamber_stretch.push_back(stretch);
  }
  // A path that ends where its cells' tables end (below the working pressure where a cell stopped)
  // is no failure of the rod: the cells' stop is judged at the pressure they traced (the caller).
  out.bending_deg_at_working = out.bending_deg.empty() ? 0.0 : out.bending_deg.back();
}

struct Lift {
  bool ok = false;
  double pressure_kPa = 0, reach_mm = 0;
  std::string why;  // why not
  std::vector<double> x_mm, z_mm;
};

/// The hanging arm with `mass_kg` at its tip: the first level at which the tip axis reaches the
/// lift angle from vertical, and whether the mass is held out far enough there.
Lift lift(fem::SpatialCellRodSpec rod, double mass_kg, const EvaluationSettings& s, double top, int levels, int& poses) {
  rod.tip_mass_kg = mass_kg;
  const double min_reach = s.lift_reach_fraction * fem::spatial_cell_rod_length_mm(rod);
  fem::SpatialCellRodState last;
  double previous_tilt = 0, previous_t = 0;
  Lift out;
  for (double t : level_grid(levels, top)) {
    const fem::SpatialCellRodState st = fem::solve_spatial_cell_rod(rod, t, last.ok ? &last : nullptr);
    ++poses;
    if (!st.ok) {
      out.why = "no equilibrium near the last at " + std::to_string(t * s.working_pressure_kPa) + " kPa (" + st.diagnosis + ")";
      return out;
    }
    const double tilt = tilt_deg(st);
    if (last.ok && tilt - previous_tilt > kMaxTurnPerLevel_deg) {  // a snap through a fold, not a lift
      out.why = "the tip turns " + std::to_string(tilt - previous_tilt) + " deg between two levels near " +
                std::to_string(t * s.working_pressure_kPa) + " kPa (a fold)";
      return out;
    }
    if (tilt >= s.lift_angle_deg) {
      // Land on the lift angle: bisection on the level between the last two (the rod is linear in
      // neither), the pose and its reach judged there.
      fem::SpatialCellRodState at = st, below = last;
      double lo = previous_t, hi = t;
      for (int it = 0; it < 12 && below.ok; ++it) {
        const double mid = 0.5 * (lo + hi);
        const fem::SpatialCellRodState m = fem::solve_spatial_cell_rod(rod, mid, &below);
        ++poses;
        if (!m.ok) break;
        if (tilt_deg(m) >= s.lift_angle_deg) hi = mid, at = m;
        else lo = mid, below = m;
      }
      out.pressure_kPa = hi * s.working_pressure_kPa;
      out.reach_mm = at.position.back().head<2>().norm();
      const Eigen::Vector2d dir = out.reach_mm > 1e-12 ? Eigen::Vector2d(at.position.back().head<2>() / out.reach_mm)
                                                       : Eigen::Vector2d(1, 0);
      for (const auto& r : at.position) {
        out.x_mm.push_back(r.head<2>().dot(dir));
        out.z_mm.push_back(r.z() - at.position.front().z());
      }
      out.ok = out.reach_mm >= min_reach;
      if (!out.ok) out.why = "the payload's reach falls below the minimum";
      return out;
    }
    previous_tilt = tilt, previous_t = t;
    last = st;
  }
  out.why = "the tip stays below the lift angle up to " + fem::number_text(top * s.working_pressure_kPa) + " kPa";
  return out;
}

/// The largest tip mass the hanging arm lifts (bisection on the mass; the lift fails beyond it).
void payload_on_cells(const fem::SplCells& cells, const EvaluationSettings& s, ArmMeasures& out, int levels,
                      int& poses) {
  fem::SpatialCellRodSpec rod = cells.rod;
  rod.gravity_m_s2 = Eigen::Vector3d(0, 0, -s.gravity_m_s2);
  const double top = covered_level(rod.pieces);
  Lift low = lift(rod, 0.0, s, top, levels, poses);
  if (!low.ok) {
    out.payload_kg = 0;
    out.payload_note = "even unloaded: " + low.why;
    return;
  }
  double lo = 0, hi = 0.25;
  Lift high = lift(rod, hi, s, top, levels, poses);
  while (high.ok && hi < 64) {
    lo = hi, low = high;
    hi *= 2;
    high = lift(rod, hi, s, top, levels, poses);
  }
  if (high.ok) lo = hi, low = high;  // 64 kg still lifts: report it, bracket unclosed
  for (int it = 0; it < 14 && high.ok == false; ++it) {
    const double mid = 0.5 * (lo + hi);
    Lift m = lift(rod, mid, s, top, levels, poses);
    if (m.ok) lo = mid, low = std::move(m);
    else hi = mid, high = std::move(m);
  }
  out.payload_kg = lo;
  out.payload_lift_pressure_kPa = low.pressure_kPa;
  out.payload_note = high.ok ? "the bracket's upper end (64 kg) still lifts" : high.why;
  out.payload_tip_x_mm = low.x_mm;
  out.payload_tip_z_mm = low.z_mm;
}
}  // namespace

CellRodEvaluation evaluate_arm_on_cells(const ArmCandidate& c, const EvaluationSettings& s, int cell_levels,
                                        const std::function<void(fem::TcaSceneSpec&)>& adjust,
                                        const fem::TaskSpread& spread, const fem::TaskProgress& progress) {
  const auto t0 = Clock::now();
  for (const auto& seg : c.design.segments) fem::validate(seg);
  CellRodEvaluation out;
  ArmMeasures& m = out.measures;
  const fem::ArmRod arm = arm_rod(c, s);  // exact part masses
  m.mass_kg = arm.mass_kg();
  m.masses = arm.part_masses_kg();
  m.length_mm = arm.length_mm();

  // Planar loads in every segment's mirror plane: no torsion to measure.
  const fem::SplCells cells = fem::spl_cells(arm_cell_scene(c, s), cell_levels, adjust, false, spread, progress);
  out.cell_seconds = cells.seconds;
  out.cell_work = cells.work;
  out.cells = cells.cells;
  out.end_cells = cells.end_cells;
  out.largest_cell_dofs = cells.largest_cell_dofs;
  out.largest_end_cell_dofs = cells.largest_end_cell_dofs;
  out.segment_outcome = cells.segment_outcome;
  out.segment_reached_kPa = cells.segment_reached_kPa;
  out.notes = cells.notes;
  fem::TcaSceneSpec mesh = fem::spl_segment_cell_scene(arm_cell_scene(c, s), 0, cell_levels);  // the cells' mesh
  if (adjust) adjust(mesh);
  std::ostringstream model;
  model << "cell rod: " << cells.cells << " ring-pitch cells (" << cells.largest_cell_dofs << " dofs) and "
        << cells.end_cells << " end cells (" << cells.largest_end_cell_dofs << " dofs), Hex20/P1 at 27 points, level "
        << mesh.mesh_level << ", level " << (mesh.axial_level > 0 ? mesh.axial_level : mesh.mesh_level) << "'s layers";
  out.model = model.str();
  if (!cells.failure.empty()) {
    out.failure = cells.failure;
    m.seconds = seconds_since(t0);
    return out;
  }

  const auto t_pose = Clock::now();
  m.min_bending_deg = 1e300;
  for (int n = 0; n < 3; ++n) {
    SegmentMeasures& seg = m.segments[static_cast<std::size_t>(n)];
    std::vector<double> stretch;
    bend_segment_on_cells(cells, c, s, n, cell_levels, seg, stretch, out.poses);
    const double needed = stretch.empty() ? 1.1 : *std::max_element(stretch.begin(), stretch.end());
    judge_segment(seg, stretch, c, s, n, segment_rra_fem(c, s, n, needed));
    // A stop of the cells below the working pressure is criterion (c) at the pressure they traced
    // (finer than the rod's levels), unless another criterion already holds below it.
    const double stop_kPa = out.segment_reached_kPa[n];
    if (out.segment_outcome[n] != fem::PathOutcome::completed &&
        (seg.safe_pressure_kPa < 0 || stop_kPa < seg.safe_pressure_kPa)) {
      seg.safe_pressure_kPa = stop_kPa;
      seg.governing = out.segment_outcome[n] == fem::PathOutcome::stalled
                          ? "stall of the cells"
                          : fem::in_words(out.segment_outcome[n]) + " (cells)";
      seg.burst_utilisation = std::max(seg.burst_utilisation, s.working_pressure_kPa / std::max(stop_kPa, 1.0));
    }
    add_segment(m, seg);
  }
  payload_on_cells(cells, s, m, 2 * cell_levels, out.poses);
  out.pose_seconds = seconds_since(t_pose);
  m.seconds = seconds_since(t0);
  return out;
}

namespace {
nlohmann::json segment_json(const SegmentMeasures& s) {
  return {{"pressure_kPa", s.pressure_kPa},
          {"bending_deg", s.bending_deg},
          {"bending_deg_at_working", s.bending_deg_at_working},
          {"pressure_for_target_kPa", s.pressure_for_target_kPa},
          {"chamber_stretch", s.chamber_stretch},
          {"peak_stretch", s.peaks.stretch},
          {"peak_log_strain", s.peaks.log_strain},
          {"peak_stress_MPa", s.peaks.stress_MPa},
          {"point_peak_stretch", s.peaks.point_stretch},
          {"peaks_extrapolated", s.peaks.extrapolated},
          {"burst_utilisation", s.burst_utilisation},
          {"safe_pressure_kPa", s.safe_pressure_kPa},
          {"governing", s.governing},
          {"diagnosis", s.rod_diagnosis},
          {"rra_fem_extension_mm", s.rra_fem_extension_mm},
          {"rra_rod_extension_mm", s.rra_rod_extension_mm},
          {"rra_pressure_kPa", s.rra_pressure_kPa},
          {"rra_extension_mm", s.rra_extension_mm}};
}

SegmentMeasures segment_from_json(const nlohmann::json& j) {
  SegmentMeasures s;
  s.pressure_kPa = j.at("pressure_kPa").get<std::vector<double>>();
  s.bending_deg = j.at("bending_deg").get<std::vector<double>>();
  s.bending_deg_at_working = j.at("bending_deg_at_working").get<double>();
  s.pressure_for_target_kPa = j.at("pressure_for_target_kPa").get<double>();
  s.chamber_stretch = j.at("chamber_stretch").get<double>();
  s.peaks.stretch = j.at("peak_stretch").get<double>();
  s.peaks.log_strain = j.at("peak_log_strain").get<double>();
  s.peaks.stress_MPa = j.at("peak_stress_MPa").get<double>();
  s.peaks.point_stretch = j.value("point_peak_stretch", s.peaks.stretch);
  s.peaks.extrapolated = j.at("peaks_extrapolated").get<bool>();
  s.burst_utilisation = j.at("burst_utilisation").get<double>();
  s.safe_pressure_kPa = j.at("safe_pressure_kPa").get<double>();
  s.governing = j.at("governing").get<std::string>();
  s.rod_diagnosis = j.at("diagnosis").get<std::string>();
  s.rra_fem_extension_mm = j.at("rra_fem_extension_mm").get<double>();
  s.rra_rod_extension_mm = j.at("rra_rod_extension_mm").get<double>();
  s.rra_pressure_kPa = j.at("rra_pressure_kPa").get<double>();
  s.rra_extension_mm = j.at("rra_extension_mm").get<double>();
  return s;
}
}  // namespace

nlohmann::json to_json(const CellRodEvaluation& e) {
  const ArmMeasures& m = e.measures;
  nlohmann::json segments = nlohmann::json::array(), outcomes = nlohmann::json::array();
  for (const auto& s : m.segments) segments.push_back(segment_json(s));
  for (const auto o : e.segment_outcome) outcomes.push_back(fem::to_string(o));
  return {{"mass_kg", m.mass_kg},
          {"mass_by_part_kg", {m.masses.tube, m.masses.rings, m.masses.sheath, m.masses.connectors}},
          {"length_mm", m.length_mm},
          {"payload_kg", m.payload_kg},
          {"payload_note", m.payload_note},
          {"payload_lift_pressure_kPa", m.payload_lift_pressure_kPa},
          {"payload_x_mm", m.payload_tip_x_mm},
          {"payload_z_mm", m.payload_tip_z_mm},
          {"segments", segments},
          {"min_bending_deg", m.min_bending_deg},
          {"burst_utilisation", m.burst_utilisation},
          {"burst_governing", m.burst_governing},
          {"safe_pressure_kPa", m.safe_pressure_kPa},
          {"durability_log_strain", m.durability_log_strain},
          {"seconds", m.seconds},
          {"segment_outcome", outcomes},
          {"segment_reached_kPa", e.segment_reached_kPa},
          {"cells", e.cells},
          {"end_cells", e.end_cells},
          {"largest_cell_dofs", e.largest_cell_dofs},
          {"largest_end_cell_dofs", e.largest_end_cell_dofs},
          {"cell_seconds", e.cell_seconds},
          {"cell_work", fem::solver_work_to_json(e.cell_work)},
          {"pose_seconds", e.pose_seconds},
          {"poses", e.poses},
          {"model", e.model},
          {"failure", e.failure},
          {"notes", e.notes}};
}

CellRodEvaluation cell_rod_evaluation_from_json(const nlohmann::json& j) {
  CellRodEvaluation e;
  ArmMeasures& m = e.measures;
  m.mass_kg = j.at("mass_kg").get<double>();
  const auto parts = j.at("mass_by_part_kg").get<std::array<double, 4>>();
  m.masses.tube = parts[0], m.masses.rings = parts[1], m.masses.sheath = parts[2], m.masses.connectors = parts[3];
  m.length_mm = j.at("length_mm").get<double>();
  m.payload_kg = j.at("payload_kg").get<double>();
  m.payload_note = j.at("payload_note").get<std::string>();
  m.payload_lift_pressure_kPa = j.at("payload_lift_pressure_kPa").get<double>();
  m.payload_tip_x_mm = j.at("payload_x_mm").get<std::vector<double>>();
  m.payload_tip_z_mm = j.at("payload_z_mm").get<std::vector<double>>();
  for (std::size_t n = 0; n < 3; ++n) m.segments[n] = segment_from_json(j.at("segments").at(n));
  m.min_bending_deg = j.at("min_bending_deg").get<double>();
  m.burst_utilisation = j.at("burst_utilisation").get<double>();
  m.burst_governing = j.at("burst_governing").get<std::string>();
  m.safe_pressure_kPa = j.at("safe_pressure_kPa").get<double>();
  m.durability_log_strain = j.at("durability_log_strain").get<double>();
  m.seconds = j.at("seconds").get<double>();
  for (std::size_t n = 0; n < 3; ++n)
    e.segment_outcome[n] = fem::path_outcome_named(j.at("segment_outcome").at(n).get<std::string>());
  e.segment_reached_kPa = j.at("segment_reached_kPa").get<std::array<double, 3>>();
  e.cells = j.at("cells").get<int>();
  e.end_cells = j.at("end_cells").get<int>();
  e.largest_cell_dofs = j.at("largest_cell_dofs").get<int>();
  e.largest_end_cell_dofs = j.at("largest_end_cell_dofs").get<int>();
  e.cell_seconds = j.at("cell_seconds").get<double>();
  // A checkpoint written before the cells' solves were kept has none: they stay zero.
  if (j.contains("cell_work")) e.cell_work = fem::solver_work_from_json(j.at("cell_work"));
  e.pose_seconds = j.at("pose_seconds").get<double>();
  e.poses = j.at("poses").get<int>();
  e.model = j.at("model").get<std::string>();
  e.failure = j.at("failure").get<std::string>();
  e.notes = j.at("notes").get<std::string>();
  return e;
}

}  // namespace softarm::objectives

#include "fem/scenes/spl_cell_rod.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "fem/core/parallel.hpp"
#include "fem/reduced/rod_layout.hpp"
#include "fem/scenes/tca_cell_rod.hpp"
#include "fem/core/angles.hpp"

namespace softarm::fem {
namespace {

/// A node's pose from rest: position, rotation, and the tilt of its axis (z at rest).
FacePose pose_at(const SpatialCellRodState& s, int node) {
  const double c = std::clamp(s.frame[node].col(2).z(), -1.0, 1.0);
  return {s.position[node], s.frame[node], std::acos(c) * kDeg};
}
}  // namespace

TcaSceneSpec spl_segment_cell_scene(const SplSceneSpec& spec, int n, int cell_levels) {
  TcaSceneSpec s;
  s.design = spec.design.segments[n];
  s.tube_material = spec.tube_material;
  s.ring_material = spec.ring_material;
  s.sheath_material = spec.sheath_material;
  s.allow_symmetry = spec.allow_symmetry;
  s.chamber_pressure_kPa = {spec.chamber_pressure_kPa[3 * n], spec.chamber_pressure_kPa[3 * n + 1],
                            spec.chamber_pressure_kPa[3 * n + 2]};
  const double peak = *std::max_element(s.chamber_pressure_kPa.begin(), s.chamber_pressure_kPa.end());
  if (peak > 0)
    for (int i = 1; i <= cell_levels; ++i) s.output_pressures_kPa.push_back(peak * i / cell_levels);
  s.newton = spec.newton;
  s.steps = spec.steps;
  s.limit = spec.limit;
  use_cell_rod_rung(s);
  return s;
}

EndFaceSupport spl_end_support(int n, TcaEnd end) {
  return end == TcaEnd::bottom && n == 2 ? EndFaceSupport::free : EndFaceSupport::bonded;
}

namespace {
/// The cells an SPL needs: a job per ring-pitch cell of every segment and, where the segment has
/// room, one per end (each with the face its connector or the free tip gives it), on each
/// segment's cell scene.
struct CellJob {
  int segment, ring;
  std::size_t piece;
};
struct EndCellJob {
  int segment;
  TcaEnd end;
  EndFaceSupport face;
  std::size_t piece;
};
struct CellPlan {
  std::vector<CellJob> cells;
  std::vector<EndCellJob> ends;
  std::array<TcaSceneSpec, 3> scenes;
};

/// The rod's pieces from the shoulder (connector, segment 1, connector, segment 2, connector, segment
/// 3) into `out`, and the plan of their cells; false (with out.failure) for a segment without rings.
bool plan_cells(const SplSceneSpec& spec, int cell_levels, const std::function<void(TcaSceneSpec&)>& adjust,
                SplCells& out, CellPlan& plan) {
  for (const RodPiece& piece : spl_rod_pieces(spec.design, spec.connector_material)) {
    SpatialCellPiece p;
    if (piece.kind == RodPiece::Kind::connector) {
      p.length_mm = piece.length_mm;
      p.mass_kg = piece.mass_kg;
      out.rod.pieces.push_back(p);
      continue;
    }
    const int n = static_cast<int>(out.rod.pieces.size()) / 2;
    TcaSceneSpec& scene = plan.scenes[n];
    scene = spl_segment_cell_scene(spec, n, cell_levels);
    if (adjust) adjust(scene);
    p.length_mm = scene.design.actuator.length_mm;
    p.cap_mm = scene.design.actuator.end_cap_thickness_mm;
    const int ring_count = scene.design.actuator.ring_count;
    out.rings[n] = cell_rod_rings(ring_count);
    if (out.rings[n].empty()) {
      out.failure = "segment " + std::to_string(n + 1) + " has no rings: the cell rod needs a ring pitch";
      return false;
    }
    for (int ring : out.rings[n]) plan.cells.push_back({n, ring, out.rod.pieces.size()});
    out.end_rings[n] = end_cell_rings(scene.cell_rod_end_rings, ring_count);
    if (scene.cell_rod_end_rings > 0 && out.end_rings[n] == 0)
      out.end_cells_note += (out.end_cells_note.empty() ? "" : "; ") + std::string("segment ") + std::to_string(n + 1) +
                            ": " + no_end_cells_note(scene.cell_rod_end_rings, ring_count);
    if (out.end_rings[n] > 0)
      for (TcaEnd end : {TcaEnd::top, TcaEnd::bottom})
        plan.ends.push_back({n, end, spl_end_support(n, end), out.rod.pieces.size()});
    out.rod.pieces.push_back(p);
  }
  return true;
}

/// The end cells, then the cells and each one's torsion at rest: side by side on this process'
/// threads (parallel_tasks), or spread by `spread` (over MPI ranks) and returned as text.
std::vector<CellJobResult> run_cells(const CellPlan& plan, const SplCells& out, bool with_torsion,
                                     const TaskSpread& spread, const TaskProgress& progress) {
  const int end_count = static_cast<int>(plan.ends.size());
  const int job_count = end_count + static_cast<int>(plan.cells.size());
  const auto run_job = [&](int i) {
    if (i < end_count) {
      const EndCellJob& e = plan.ends[i];
      return run_end_cell_job(plan.scenes[e.segment], e.end, out.end_rings[e.segment], e.face, with_torsion);
    }
    const CellJob& c = plan.cells[i - end_count];
    return run_cell_job(plan.scenes[c.segment], c.ring, with_torsion);
  };
  std::vector<CellJobResult> results(job_count);
  if (spread) {
    const std::vector<std::string> texts = spread(job_count, [&](int i) { return to_text(run_job(i)); });
    for (int i = 0; i < job_count; ++i) results[i] = cell_job_from_text(texts.at(i));
  } else {
    parallel_tasks(job_count, [&](int i) { results[i] = run_job(i); }, progress);
  }
  return results;
}

/// Each segment's lowest stop over its cells and end cells (the limit point's pressure where traced).
void note_segment_stops(const CellPlan& plan, const std::vector<CellJobResult>& results, SplCells& out) {
  const auto note_stop = [&](int n, const CellJobResult& r) {
    const double reached = r.outcome == PathOutcome::limit_point && r.estimated_limit_pressure_kPa > 0
                               ? r.estimated_limit_pressure_kPa
                               : r.reached_pressure_kPa;
    if (r.outcome != PathOutcome::completed && (out.segment_outcome[n] == PathOutcome::completed ||
                                                 reached < out.segment_reached_kPa[n])) {
      out.segment_outcome[n] = r.outcome;
      out.segment_reached_kPa[n] = reached;
    }
  };
  for (int n = 0; n < 3; ++n) {
    const auto& p = plan.scenes[n].chamber_pressure_kPa;
    out.segment_reached_kPa[n] = *std::max_element(p.begin(), p.end());
  }
  const std::size_t end_count = plan.ends.size();
  for (std::size_t i = 0; i < end_count; ++i) note_stop(plan.ends[i].segment, results[i]);
  for (std::size_t i = 0; i < plan.cells.size(); ++i) note_stop(plan.cells[i].segment, results[end_count + i]);
}

/// The end cells' turns, elongations and twist compliances onto their pieces; false (with
/// out.failure) for an end cell with no torsional stiffness.
bool take_end_cells(const CellPlan& plan, const std::vector<CellJobResult>& results, SplCells& out) {
  for (std::size_t i = 0; i < plan.ends.size(); ++i) {
    const EndCellJob& e = plan.ends[i];
    const CellJobResult& r = results[i];
    out.largest_end_cell_dofs = std::max(out.largest_end_cell_dofs, r.dofs);
    out.outcomes.push_back(r.outcome);
    const std::string name = "segment " + std::to_string(e.segment + 1) + ", " + (e.end == TcaEnd::top ? "top" : "bottom") + " end";
    if (r.outcome != PathOutcome::completed) out.notes += " (" + name + ": " + r.diagnosis + ")";
    if (std::isnan(r.torsion)) {
      out.failure = name + ": the end cell's tangent at rest is not positive definite (no torsional stiffness)";
      return false;
    }
    out.rod.pieces[e.piece].ends.push_back(r.end);
    out.rod.pieces[e.piece].ends.back().twist_compliance_per_Nmm = r.torsion;
  }
  out.end_cells = static_cast<int>(plan.ends.size());
  return true;
}

/// The cells' tables (with 1/GJ where asked) onto their pieces; false (with out.failure) for a cell
/// with no torsional stiffness.
bool take_cells(const CellPlan& plan, const std::vector<CellJobResult>& results, bool with_torsion, SplCells& out) {
  const std::size_t end_count = plan.ends.size();
  for (std::size_t i = 0; i < plan.cells.size(); ++i) {
    const CellJobResult& r = results[end_count + i];
    const int n = plan.cells[i].segment, ring = plan.cells[i].ring;
    out.half_model[n] = r.half_model;
    out.largest_cell_dofs = std::max(out.largest_cell_dofs, r.dofs);
    ++out.cells;
    out.outcomes.push_back(r.outcome);
    if (r.outcome != PathOutcome::completed)
      out.notes += " (segment " + std::to_string(n + 1) + ", ring " + std::to_string(ring) + ": " + r.diagnosis + ")";
    if (with_torsion && !(r.torsion > 0)) {
      out.failure = "segment " + std::to_string(n + 1) + ", ring " + std::to_string(ring) +
                    ": the cell's tangent at rest is not positive definite (no torsional stiffness)";
      return false;
    }
    auto& tables = out.rod.pieces[plan.cells[i].piece].cells;
    tables.push_back(r.cell);
    tables.back().torsion_compliance_per_Nmm2 = with_torsion ? 1 / r.torsion : 0.0;
  }
  return true;
}
}  // namespace

SplCells spl_cells(const SplSceneSpec& spec, int cell_levels, const std::function<void(TcaSceneSpec&)>& adjust,
                   bool with_torsion, const TaskSpread& spread, const TaskProgress& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  SplCells out;
  out.rod.gravity_m_s2 = spec.gravity_m_s2;
  out.rod.tip_mass_kg = spec.tip_mass_kg;
  CellPlan plan;
  if (!plan_cells(spec, cell_levels, adjust, out, plan)) return out;
  const std::vector<CellJobResult> results = run_cells(plan, out, with_torsion, spread, progress);
  for (const CellJobResult& r : results) out.work.add(r.work);
  note_segment_stops(plan, results, out);
  if (!take_end_cells(plan, results, out) || !take_cells(plan, results, with_torsion, out)) return out;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

SplCellRodResult pose_spl_cell_rod(const SplCells& cells, const std::vector<double>& output_levels) {
  SplCellRodResult out;
  if (!cells.failure.empty()) {
    out.diagnosis = cells.failure;
    return out;
  }
  out.mass_kg = spatial_cell_rod_mass_kg(cells.rod);
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<double> levels = {0.0};
  levels.insert(levels.end(), output_levels.begin(), output_levels.end());
  SpatialCellRodState last;
  for (double t : levels) {
    const SpatialCellRodState s = solve_spatial_cell_rod(cells.rod, t, last.ok ? &last : nullptr);
    if (!s.ok) {
      out.diagnosis = s.diagnosis + cells.notes;
      break;
    }
    last = s;
    const int tip = static_cast<int>(s.position.size()) - 1;
    out.curve.push_back({t, s.position[tip], pose_at(s, tip).tilt_deg, s.iterations, s.position});
  }
  out.rod_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out.converged = out.curve.size() == levels.size();
  out.reached_level = out.curve.empty() ? 0.0 : out.curve.back().load_fraction;
  out.outcome = out.converged ? PathOutcome::completed : outcome_of_parts(cells.outcomes);
  if (last.ok)
    for (int n = 1; n <= 3; ++n) {
      const std::string segment = "segment " + std::to_string(n);
      out.joints.push_back({segment + " top" + (n == 1 ? " (shoulder connector)" : ""),
                            pose_at(last, last.piece_first_node[2 * n - 1])});
      out.joints.push_back({segment + " bottom" + (n == 3 ? " (tip)" : ""), pose_at(last, last.piece_last_node[2 * n - 1])});
    }
  return out;
}

SplCellRodResult run_cell_rod_spl(const SplSceneSpec& spec, int cell_levels) {
  return pose_spl_cell_rod(spl_cells(spec, cell_levels), spec.output_levels);
}

}  // namespace softarm::fem

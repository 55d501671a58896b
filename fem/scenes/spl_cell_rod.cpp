#include "fem/scenes/spl_cell_rod.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "fem/core/parallel.hpp"
#include "fem/reduced/rod_layout.hpp"
#include "fem/scenes/tca_cell.hpp"
#include "fem/scenes/twist_compliance.hpp"

namespace softarm::fem {
namespace {
constexpr double kDeg = 57.295779513082320876;

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

SplCells spl_cells(const SplSceneSpec& spec, int cell_levels, const std::function<void(TcaSceneSpec&)>& adjust,
                   bool with_torsion) {
  const auto t0 = std::chrono::steady_clock::now();
  SplCells out;
  out.rod.gravity_m_s2 = spec.gravity_m_s2;
  out.rod.tip_mass_kg = spec.tip_mass_kg;
  // Pieces from the shoulder: connector, segment 1, connector, segment 2, connector, segment 3;
  // a job per cell of every segment.
  struct Job {
    int segment, ring;
    std::size_t piece;
  };
  struct EndJob {
    int segment;
    TcaEnd end;
    EndFaceSupport face;
    std::size_t piece;
  };
  std::vector<Job> jobs;
  std::vector<EndJob> end_jobs;
  std::array<TcaSceneSpec, 3> scenes;
  for (const RodPiece& piece : spl_rod_pieces(spec.design, spec.connector_material)) {
    SpatialCellPiece p;
    if (piece.kind == RodPiece::Kind::connector) {
      p.length_mm = piece.length_mm;
      p.mass_kg = piece.mass_kg;
      out.rod.pieces.push_back(p);
      continue;
    }
    const int n = static_cast<int>(out.rod.pieces.size()) / 2;
    scenes[n] = spl_segment_cell_scene(spec, n, cell_levels);
    if (adjust) adjust(scenes[n]);
    p.length_mm = scenes[n].design.actuator.length_mm;
    p.cap_mm = scenes[n].design.actuator.end_cap_thickness_mm;
    const int ring_count = scenes[n].design.actuator.ring_count;
    out.rings[n] = cell_rod_rings(ring_count);
    if (out.rings[n].empty()) {
      out.failure = "segment " + std::to_string(n + 1) + " has no rings: the cell rod needs a ring pitch";
      return out;
    }
    for (int ring : out.rings[n]) jobs.push_back({n, ring, out.rod.pieces.size()});
    out.end_rings[n] = end_cell_rings(scenes[n].cell_rod_end_rings, ring_count);
    if (scenes[n].cell_rod_end_rings > 0 && out.end_rings[n] == 0)
      out.end_cells_note += (out.end_cells_note.empty() ? "" : "; ") + std::string("segment ") + std::to_string(n + 1) +
                            ": " + no_end_cells_note(scenes[n].cell_rod_end_rings, ring_count);
    if (out.end_rings[n] > 0) {
      for (TcaEnd end : {TcaEnd::top, TcaEnd::bottom})
        end_jobs.push_back({n, end, spl_end_support(n, end), out.rod.pieces.size()});
    }
    out.rod.pieces.push_back(p);
  }
  // The end cells, then the cells and each one's torsion at rest, side by side (parallel_tasks).
  const int end_count = static_cast<int>(end_jobs.size());
  std::vector<TcaEndCellResult> ends(end_jobs.size());
  std::vector<double> end_twist(end_jobs.size(), 0.0);  // bonded ends' twist compliance at rest
  std::vector<TcaCellResult> cells(jobs.size());
  std::vector<double> torsion(jobs.size());
  parallel_tasks(end_count + static_cast<int>(jobs.size()), [&](int i) {
    if (i < end_count) {
      const EndJob& e = end_jobs[i];
      ends[i] = run_tca_end_cell(scenes[e.segment], e.end, out.end_rings[e.segment], e.face);
      if (with_torsion && e.face == EndFaceSupport::bonded)
        end_twist[i] = end_cell_twist_compliance(scenes[e.segment], e.end, out.end_rings[e.segment]);
      return;
    }
    i -= end_count;
    cells[i] = run_tca_cell(scenes[jobs[i].segment], jobs[i].ring);
    if (with_torsion) torsion[i] = cell_torsion_stiffness(scenes[jobs[i].segment], jobs[i].ring);
  });
  // Each segment's lowest stop over its cells and end cells (the limit point's pressure where traced).
  const auto note_stop = [&](int n, const PressurePathResult& path) {
    const double reached = path.outcome == PathOutcome::limit_point && path.estimated_limit_pressure_kPa > 0
                               ? path.estimated_limit_pressure_kPa
                               : path.reached_pressure_kPa;
    if (path.outcome != PathOutcome::completed && (out.segment_outcome[n] == PathOutcome::completed ||
                                                    reached < out.segment_reached_kPa[n])) {
      out.segment_outcome[n] = path.outcome;
      out.segment_reached_kPa[n] = reached;
    }
  };
  for (int n = 0; n < 3; ++n) {
    const auto& p = scenes[n].chamber_pressure_kPa;
    out.segment_reached_kPa[n] = *std::max_element(p.begin(), p.end());
  }
  for (std::size_t i = 0; i < end_jobs.size(); ++i) note_stop(end_jobs[i].segment, ends[i].path);
  for (std::size_t i = 0; i < jobs.size(); ++i) note_stop(jobs[i].segment, cells[i].path);
  for (std::size_t i = 0; i < end_jobs.size(); ++i) {
    const EndJob& e = end_jobs[i];
    const auto& p = scenes[e.segment].chamber_pressure_kPa;
    out.largest_end_cell_dofs = std::max(out.largest_end_cell_dofs, ends[i].dofs);
    out.outcomes.push_back(ends[i].path.outcome);
    const std::string name = "segment " + std::to_string(e.segment + 1) + ", " + (e.end == TcaEnd::top ? "top" : "bottom") + " end";
    if (ends[i].path.outcome != PathOutcome::completed) out.notes += " (" + name + ": " + ends[i].path.diagnosis + ")";
    if (std::isnan(end_twist[i])) {
      out.failure = name + ": the end cell's tangent at rest is not positive definite (no torsional stiffness)";
      return out;
    }
    out.rod.pieces[e.piece].ends.push_back(spatial_end_table(ends[i], *std::max_element(p.begin(), p.end())));
    out.rod.pieces[e.piece].ends.back().twist_compliance_per_Nmm = end_twist[i];
  }
  out.end_cells = end_count;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    const TcaCellResult& cell = cells[i];
    const int n = jobs[i].segment, ring = jobs[i].ring;
    const auto& p = scenes[n].chamber_pressure_kPa;
    out.half_model[n] = cell.model.half;
    out.largest_cell_dofs = std::max(out.largest_cell_dofs, cell.dofs);
    ++out.cells;
    out.outcomes.push_back(cell.path.outcome);
    if (cell.path.outcome != PathOutcome::completed)
      out.notes += " (segment " + std::to_string(n + 1) + ", ring " + std::to_string(ring) + ": " +
                   cell.path.diagnosis + ")";
    if (with_torsion && !(torsion[i] > 0)) {
      out.failure = "segment " + std::to_string(n + 1) + ", ring " + std::to_string(ring) +
                    ": the cell's tangent at rest is not positive definite (no torsional stiffness)";
      return out;
    }
    auto& tables = out.rod.pieces[jobs[i].piece].cells;
    tables.push_back(spatial_cell_table(cell, *std::max_element(p.begin(), p.end())));
    tables.back().torsion_compliance_per_Nmm2 = with_torsion ? 1 / torsion[i] : 0.0;
  }
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
    out.curve.push_back({t, s.position[tip], pose_at(s, tip).tilt_deg, s.iterations});
  }
  out.rod_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out.converged = out.curve.size() == levels.size();
  out.reached_level = out.curve.empty() ? 0.0 : out.curve.back().load_fraction;
  out.outcome = out.converged ? PathOutcome::completed : PathOutcome::stalled;
  if (!out.converged && std::count(cells.outcomes.begin(), cells.outcomes.end(), PathOutcome::limit_point) > 0)
    out.outcome = PathOutcome::limit_point;
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

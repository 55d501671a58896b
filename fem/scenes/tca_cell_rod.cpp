#include "fem/scenes/tca_cell_rod.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include <Eigen/Geometry>

#include "fem/core/parallel.hpp"
#include "fem/scenes/fidelity.hpp"
#include "fem/scenes/twist_compliance.hpp"
#include "fem/core/angles.hpp"

namespace softarm::fem {

void use_cell_rod_rung(TcaSceneSpec& spec) {
  for (const ModelLevel& m : fidelity_ladder("tca").levels)
    if (m.cell_rod) {
      spec.mesh_level = m.mesh_level;
      spec.axial_level = m.axial_level;
      spec.element_order = m.element_order;
      spec.serendipity = m.serendipity;
      spec.integration = m.reduced_integration ? ElementIntegration::reduced : ElementIntegration::full;
      spec.cell_rod_end_rings = m.end_rings;
    }
}

namespace {

/// The 3CA's cell rod through the spatial rod (spatial_cell_rod.hpp): its only piece the 3CA, its
/// clamp at the top, every load in any direction; the bending angle is the tip axis' tilt from rest,
/// negative where the tip leans away from the pressures' bend direction (the sag under gravity).
CellRodState solve_spatial_tca(const SpatialCellRodSpec& rod, const Eigen::Vector3d& bend, double peak_kPa,
                               double pressure_kPa, SpatialCellRodState& last) {
  CellRodState out;
  out.pressure_kPa = pressure_kPa;
  const SpatialCellRodState s =
      solve_spatial_cell_rod(rod, peak_kPa > 0 ? pressure_kPa / peak_kPa : 0.0, last.ok ? &last : nullptr);
  out.iterations = s.iterations;
  if (!s.ok) {
    out.diagnosis = s.diagnosis;
    return out;
  }
  last = s;
  const Eigen::Vector3d tangent = -s.frame.back().col(2), tip = s.position.back();  // down the 3CA at rest
  out.bending_angle_deg = std::acos(std::clamp(-tangent.z(), -1.0, 1.0)) * kDeg;
  if (tangent.dot(bend) < 0) out.bending_angle_deg = -out.bending_angle_deg;
  out.tip_along_bend_mm = tip.dot(bend);
  out.tip_across_bend_mm = tip.dot(Eigen::Vector3d::UnitZ().cross(bend));
  out.tip_z_mm = tip.z();
  out.centreline_mm = s.position;
  out.ok = true;
  return out;
}
}  // namespace

bool tca_needs_spatial_rod(const TcaSceneSpec& spec) {
  // In one plane (the pressures and gravity share a mirror plane through the axis: a half model
  // would do) the planar rod, on which the ladder's error was measured; else the spatial rod, whose
  // cells also give their torsion.
  TcaSceneSpec mirror = spec;
  mirror.allow_symmetry = true;
  return !choose_tca_model(mirror).half;
}

TcaRodCells run_tca_rod_cells(const TcaSceneSpec& spec, bool with_torsion, const TaskProgress& progress,
                              const TcaRodCells* ring_cells) {
  TcaRodCells out;
  const int n = spec.design.actuator.ring_count;
  out.with_torsion = with_torsion;
  out.rings = cell_rod_rings(n);
  out.end_rings = end_cell_rings(spec.cell_rod_end_rings, n);
  if (spec.cell_rod_end_rings > 0 && out.end_rings == 0) out.end_cells_note = no_end_cells_note(spec.cell_rod_end_rings, n);
  const int end_count = out.end_rings > 0 ? 2 : 0;
  out.cells.resize(out.rings.size());
  out.ends.resize(end_count);
  out.torsion.assign(out.rings.size(), 0.0);
  out.end_twist.assign(end_count, 0.0);
  if (ring_cells) {
    if (ring_cells->rings != out.rings || ring_cells->cells.size() != out.rings.size() ||
        (with_torsion && !ring_cells->with_torsion))
      throw std::logic_error("run_tca_rod_cells: ring-pitch cells run about other rings or without torsion");
    out.cells = ring_cells->cells;
    out.torsion = ring_cells->torsion;
  }
  const int ring_tasks = ring_cells ? 0 : static_cast<int>(out.rings.size());
  // The cells side by side, one thread each (parallel_tasks); the larger end cells first.
  const auto t_cells = std::chrono::steady_clock::now();
  parallel_tasks(end_count + ring_tasks, [&](int i) {
    if (i < end_count) {
      const TcaEnd end = i == 0 ? TcaEnd::bottom : TcaEnd::top;
      out.ends[i] = run_tca_end_cell(spec, end, out.end_rings, tca_scene_end_support(end));
      if (with_torsion && tca_scene_end_support(end) == EndFaceSupport::bonded)
        out.end_twist[i] = end_cell_twist_compliance(spec, end, out.end_rings);
      return;
    }
    i -= end_count;
    out.cells[i] = run_tca_cell(spec, out.rings[i]);
    if (with_torsion) out.torsion[i] = cell_torsion_stiffness(spec, out.rings[i]);
  }, progress);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_cells).count();
  return out;
}

CellRodTcaResult run_cell_rod_tca(const TcaSceneSpec& spec, const TaskProgress& progress) {
  if (spec.design.actuator.ring_count < 1) return pose_cell_rod_tca(spec, {});
  return pose_cell_rod_tca(spec, run_tca_rod_cells(spec, tca_needs_spatial_rod(spec), progress));
}

CellRodTcaResult pose_cell_rod_tca(const TcaSceneSpec& spec, const TcaRodCells& pieces) {
  CellRodTcaResult out;
  out.outcome = PathOutcome::stalled;  // until the rod has reached every output
  if (spec.design.actuator.ring_count < 1) {
    out.diagnosis = "the cell rod needs rings: a 3CA without them has no ring pitch (and barely bends)";
    return out;
  }
  out.spatial = tca_needs_spatial_rod(spec);
  if (out.spatial && !pieces.with_torsion)
    throw std::logic_error("pose_cell_rod_tca: loads out of one plane need the cells' torsion");
  const int n = spec.design.actuator.ring_count;
  if (pieces.rings != cell_rod_rings(n) || pieces.cells.size() != pieces.rings.size() ||
      pieces.end_rings != end_cell_rings(spec.cell_rod_end_rings, n) ||
      pieces.ends.size() != (pieces.end_rings > 0 ? 2u : 0u))
    throw std::logic_error("pose_cell_rod_tca: cells run for another design or end cells");
  Eigen::Vector3d bend = tca_bend_direction(spec.chamber_pressure_kPa);
  if (bend.norm() > 0) bend.normalize();
  out.rings = pieces.rings;
  out.end_rings = pieces.end_rings;
  out.end_cells_note = pieces.end_cells_note;
  const auto& cells = pieces.cells;
  const auto& ends = pieces.ends;
  const auto& torsion = pieces.torsion;
  const auto& end_twist = pieces.end_twist;
  out.cell_seconds = pieces.seconds;
  for (const auto& c : cells) out.work.add(c.path, c.dofs, c.seconds);
  for (const auto& e : ends) out.work.add(e.path, e.dofs, e.seconds);
  out.cell_dofs = cells.back().dofs;
  out.end_cell_dofs = ends.empty() ? 0 : ends.back().dofs;
  const CellRodSpec rod = tca_cell_rod(spec, cells, ends);
  const double peak = *std::max_element(spec.chamber_pressure_kPa.begin(), spec.chamber_pressure_kPa.end());
  SpatialCellRodSpec spatial;
  if (out.spatial) {
    SpatialCellPiece piece;
    piece.length_mm = rod.length_mm;
    piece.cap_mm = rod.cap_mm;
    for (std::size_t i = 0; i < cells.size(); ++i) {
      if (!(torsion[i] > 0)) {
        out.diagnosis = "the cell about ring " + std::to_string(out.rings[i]) +
                        " has no torsional stiffness (its tangent at rest is not positive definite)";
        return out;
      }
      piece.cells.push_back(spatial_cell_table(cells[i], peak));
      piece.cells.back().torsion_compliance_per_Nmm2 = 1 / torsion[i];
    }
    for (std::size_t i = 0; i < ends.size(); ++i) {
      if (std::isnan(end_twist[i])) {
        out.diagnosis = "the clamped end cell has no torsional stiffness (its tangent at rest is not positive definite)";
        return out;
      }
      piece.ends.push_back(spatial_end_table(ends[i], peak));
      piece.ends.back().twist_compliance_per_Nmm = end_twist[i];
    }
    spatial.pieces = {piece};
    spatial.gravity_m_s2 = spec.gravity_m_s2;
  }
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<double> pressures = {0.0};
  pressures.insert(pressures.end(), spec.output_pressures_kPa.begin(), spec.output_pressures_kPa.end());
  std::vector<TcaState> states;
  SpatialCellRodState last;
  for (double p : pressures) {
    CellRodState s = out.spatial ? solve_spatial_tca(spatial, bend, peak, p, last) : solve_cell_rod(rod, p);
    if (!out.spatial) {  // the planar rod's (along the bend, 0, z) into the scene frame
      const Eigen::Vector3d along = bend.norm() > 0 ? bend : Eigen::Vector3d::UnitX();
      for (Eigen::Vector3d& node : s.centreline_mm) node = node.x() * along + node.z() * Eigen::Vector3d::UnitZ();
    }
    if (!s.ok) {
      out.diagnosis = s.diagnosis;
      for (const auto& c : cells)
        if (c.path.outcome != PathOutcome::completed) out.diagnosis += " (" + c.path.diagnosis + ")";
      for (const auto& e : ends)
        if (e.path.outcome != PathOutcome::completed) out.diagnosis += " (" + e.path.diagnosis + ")";
      break;
    }
    out.curve.push_back(s);
    TcaState t;
    t.pressure_kPa = s.pressure_kPa;
    t.bending_angle_deg = s.bending_angle_deg;
    states.push_back(t);
  }
  out.rod_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out.converged = out.curve.size() == pressures.size();
  out.reached_pressure_kPa = out.curve.empty() ? 0.0 : out.curve.back().pressure_kPa;
  // Short of the last output: a cell's failure (limit point, material, element) is the rod's, else a stall.
  std::vector<PathOutcome> parts;
  for (const auto& c : cells) parts.push_back(c.path.outcome);
  for (const auto& e : ends) parts.push_back(e.path.outcome);
  out.outcome = out.converged ? PathOutcome::completed : outcome_of_parts(parts);
  out.target_pressure_kPa = pressure_at_bending(states, spec.target_bending_deg);
  return out;
}

}  // namespace softarm::fem

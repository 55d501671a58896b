#include "objectives/arm_evaluation.hpp"

#include "fem/core/parallel.hpp"
#include "fem/materials/burst_criteria.hpp"

#include "objectives/payload_capacity.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include "fem/core/angles.hpp"

namespace softarm::objectives {
namespace {
using fem::kDeg;
constexpr double kHanging = -1.5707963267948966;  // clamp direction: the axis points down (−Z)

fem::RodPiece segment_piece(const fem::TcaDesign& d) {
  fem::RodPiece p;
  p.kind = fem::RodPiece::Kind::tca;
  p.design = d;
  return p;
}

fem::ArmRodSpec rod_spec(const ArmCandidate& c, const EvaluationSettings& s) {
  fem::ArmRodSpec spec;
  spec.tube = c.tube;
  spec.sheath = c.sheath;
  spec.rings = c.rings;
  spec.nodes_per_segment = s.rod_nodes_per_segment;
  spec.ring_confinement = s.ring_confinement;
  return spec;
}

}  // namespace

fem::RraCalibration segment_rra_fem(const ArmCandidate& c, const EvaluationSettings& s, int n, double stretch) {
  fem::RraSceneSpec spec;
  spec.design = c.design.segments[n].actuator;
  spec.tube_material = c.tube;
  spec.ring_material = c.rings;
  spec.mesh_level = s.rra_mesh_level;
  spec.peak_averaging_radius_mm = s.peak_averaging_radius_mm;
  return fem::calibrate_rra_to_stretch(spec, stretch, s.working_pressure_kPa);
}

namespace {
// Burst utilisation of the local peaks: spec §4 criteria (a), (b).
std::pair<double, std::string> utilisation(const fem::RraCalibration::Peaks& peaks, const fem::Material& m, double sf) {
  const fem::BurstUtilisation u = fem::burst_utilisation(m, peaks.stress_MPa, peaks.stretch, sf);
  return {u.value, u.criterion};
}

// Phase 1: the segment's bending path by the rod (records the chambers' axial stretch).
SegmentMeasures bend_segment(const ArmCandidate& c, const EvaluationSettings& s, int n,
                             std::vector<double>& chamber_stretch) {
  SegmentMeasures out;
  const fem::ArmRod rod = segment_rod(c, s, n);
  fem::RodLoad load;
  load.chamber_pressure_kPa = {{0.0, s.working_pressure_kPa, s.working_pressure_kPa}};
  load.gravity_m_s2 = {-s.gravity_m_s2, 0.0};  // against the bend (towards +x)
  load.clamp_angle_rad = kHanging;
  const auto on_step = [&](double fraction, const fem::RodState& st) {
    const double p = fraction * s.working_pressure_kPa;
    const double angle = rod.tip_rotation(st, load) * kDeg;
    if (!out.bending_deg.empty() && out.pressure_for_target_kPa < 0 && angle >= s.target_bending_deg) {
      const double a0 = out.bending_deg.back(), p0 = out.pressure_kPa.back();
      out.pressure_for_target_kPa = p0 + (s.target_bending_deg - a0) * (p - p0) / (angle - a0);
    }
    out.pressure_kPa.push_back(p);
    out.bending_deg.push_back(angle);
    chamber_stretch.push_back(rod.extremes(st, load, 0).chamber_max_stretch);
  };
  const fem::RodState st = rod.follow(load, s.pressure_steps, on_step);
  out.bending_deg_at_working = out.bending_deg.empty() ? 0.0 : out.bending_deg.back();
  if (!st.converged) out.rod_diagnosis = st.diagnosis;
  return out;
}

}  // namespace

// Phase 2: the burst criteria and durability along the path, from the lone RRA's FEM peaks.
void judge_segment(SegmentMeasures& out, const std::vector<double>& chamber_stretch, const ArmCandidate& c,
                   const EvaluationSettings& s, int n, const fem::RraCalibration& cal) {
  if (!cal.pressure_kPa.empty()) {
    out.rra_pressure_kPa = cal.pressure_kPa.back();
    out.rra_fem_extension_mm = cal.fem_extension_mm.back();
    out.rra_rod_extension_mm = cal.rod_extension_mm.back();
  }
  // The lone RRA's extension at the reporting pressure: the rod with the calibrated force factor
  // (exact at the FEM's output pressures, constant factor beyond its last one).
  const double p_ext = s.rra_extension_pressure_kPa;
  out.rra_extension_mm = fem::rod_rra_extension_mm(c.design.segments[n].actuator, fem::FibreLaw(*c.tube.law),
                                                   p_ext, cal.force_factor.at(p_ext));
  // The rod cannot hold p_ext (a section past its fibres' Drucker limit: the RRA balloons
  // below it): report the FEM's extension at the last pressure it reached, never NaN.
  if (!std::isfinite(out.rra_extension_mm)) out.rra_extension_mm = out.rra_fem_extension_mm;
  double previous_u = 0, previous_p = 0;
  for (std::size_t i = 0; i < chamber_stretch.size(); ++i) {
    const double p = out.pressure_kPa[i];
    out.chamber_stretch = chamber_stretch[i];
    out.peaks = cal.peaks_at(out.chamber_stretch);
    const auto [u, by] = utilisation(out.peaks, c.tube, s.safety_factor);
    if (out.safe_pressure_kPa < 0 && u >= 1) {
      out.safe_pressure_kPa = previous_p + (1 - previous_u) * (p - previous_p) / (u - previous_u);
      out.governing = by;
    }
    out.burst_utilisation = u;
    previous_u = u, previous_p = p;
  }
  bool limit_point_governs = false;  // the safe pressure is a limit point's, not a criterion's
  if (!out.rod_diagnosis.empty()) {
    const double reached = out.pressure_kPa.empty() ? 0.0 : out.pressure_kPa.back();
    if (out.safe_pressure_kPa < 0 || reached < out.safe_pressure_kPa) {
      out.safe_pressure_kPa = reached;
      out.governing = "limit point (rod)";
      limit_point_governs = true;
    }
  }
  // The lone RRA's path met a limit point (ballooning caps) before the stretch the 3CA needs.
  if (cal.limit_point && (out.safe_pressure_kPa < 0 || cal.last_pressure_kPa < out.safe_pressure_kPa)) {
    out.safe_pressure_kPa = cal.last_pressure_kPa;
    out.governing = "limit point (RRA FEM)";
    limit_point_governs = true;
  }
  // A limit point below the working pressure: utilisation as the pressure ratio (> 1).
  if (out.safe_pressure_kPa >= 0 && limit_point_governs)
    out.burst_utilisation = std::max(out.burst_utilisation, s.working_pressure_kPa / std::max(out.safe_pressure_kPa, 1.0));
}

fem::ArmRod segment_rod(const ArmCandidate& c, const EvaluationSettings& s, int segment) {
  fem::ArmRodSpec spec = rod_spec(c, s);
  spec.pieces = {segment_piece(c.design.segments[segment])};
  return fem::ArmRod(spec);
}

fem::ArmRod arm_rod(const ArmCandidate& c, const EvaluationSettings& s) {
  fem::ArmRodSpec spec = rod_spec(c, s);
  spec.pieces = fem::spl_rod_pieces(c.design, c.connector);
  return fem::ArmRod(spec);
}

void add_segment(ArmMeasures& arm, const SegmentMeasures& m) {
  arm.min_bending_deg = std::min(arm.min_bending_deg, m.bending_deg_at_working);
  if (m.burst_utilisation >= arm.burst_utilisation) {
    arm.burst_utilisation = m.burst_utilisation;
    arm.burst_governing = m.governing.empty() ? "none up to the working pressure" : m.governing;
  }
  if (m.safe_pressure_kPa >= 0 && (arm.safe_pressure_kPa < 0 || m.safe_pressure_kPa < arm.safe_pressure_kPa))
    arm.safe_pressure_kPa = m.safe_pressure_kPa;
  arm.durability_log_strain = std::max(arm.durability_log_strain, m.peaks.log_strain);
}

ArmMeasures evaluate_arm(const ArmCandidate& c, const EvaluationSettings& s) {
  const auto t0 = std::chrono::steady_clock::now();
  for (const auto& seg : c.design.segments) fem::validate(seg);
  ArmMeasures out;
  const fem::ArmRod arm = arm_rod(c, s);
  out.mass_kg = arm.mass_kg();
  out.masses = arm.part_masses_kg();
  out.length_mm = arm.length_mm();

  out.min_bending_deg = 1e300;
  // Each segment's bending path by the rod, then its lone-RRA FEM path, then the criteria along
  // the path: the three segments side by side, one thread each (fem::parallel_tasks; inside a
  // concurrent evaluation of the search, one after the other). Every FEM path then runs on one
  // thread, whatever the thread count, so the measures do not depend on it. (An earlier attempt
  // crashed twice in ~600 designs inside UMFPACK's solve; the cause was LinearSolver's LU keeping
  // only a reference to a tangent Newton had freed, which crashed sequential runs too; fixed there.)
  std::array<std::vector<double>, 3> stretch;
  std::array<std::exception_ptr, 3> failure;  // the first segment's failure is the one reported
  fem::parallel_tasks(3, [&](int n) {
    try {
      out.segments[n] = bend_segment(c, s, n, stretch[n]);
      const double needed = stretch[n].empty() ? 1.1 : *std::max_element(stretch[n].begin(), stretch[n].end());
      judge_segment(out.segments[n], stretch[n], c, s, n, segment_rra_fem(c, s, n, needed));
    } catch (...) {
      failure[n] = std::current_exception();
    }
  });
  for (int n = 0; n < 3; ++n) {
    if (failure[n]) std::rethrow_exception(failure[n]);
    add_segment(out, out.segments[n]);
  }

  PayloadSettings ps;
  ps.working_pressure_kPa = s.working_pressure_kPa;
  ps.lift_angle_deg = s.lift_angle_deg;
  ps.reach_fraction = s.lift_reach_fraction;
  ps.gravity_m_s2 = s.gravity_m_s2;
  ps.pressure_steps = s.pressure_steps;
  if (std::isfinite(c.sheath.elongation_at_break))
    ps.sheath_allowable_stretch = (1 + c.sheath.elongation_at_break) / s.safety_factor;
  const PayloadResult payload = payload_capacity(arm, ps);
  out.payload_kg = payload.capacity_kg;
  out.payload_note = payload.limited_by;
  out.payload_lift_pressure_kPa = payload.lift_pressure_kPa;
  out.payload_tip_x_mm = payload.x_mm;
  out.payload_tip_z_mm = payload.z_mm;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

double durability_reference_log_strain(double pressure_kPa, int mesh_level, double averaging_radius_mm) {
  fem::RraSceneSpec spec;  // RraDesign's defaults are the thesis RRA (Table 7)
  spec.tube_material = fem::builtin_material("dragon_skin_30", "durability_reference");
  spec.ring_material = fem::builtin_material("digital_abs", "durability_reference");
  spec.mesh_level = mesh_level;
  spec.peak_averaging_radius_mm = averaging_radius_mm;
  spec.path.max_pressure_kPa = pressure_kPa;
  spec.path.output_pressures_kPa = {pressure_kPa};
  const fem::RraResult r = fem::run_rra_scene(spec);
  return r.curve.empty() ? std::nan("") : r.curve.back().averaged.log_strain;
}

}  // namespace softarm::objectives

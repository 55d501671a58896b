#include "objectives/solid_segment_check.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "fem/scenes/tca_cell_rod.hpp"
#include "fem/scenes/tca_scene.hpp"

namespace softarm::objectives {

double bending_at_pressure(const SegmentMeasures& rod, double p) {
  const auto& P = rod.pressure_kPa;
  const auto& B = rod.bending_deg;
  if (P.empty()) return 0.0;
  if (p >= P.back()) return B.back();
  const auto hi = std::upper_bound(P.begin(), P.end(), p);
  if (hi == P.begin()) return B.front();
  const std::size_t i = static_cast<std::size_t>(hi - P.begin());
  const double t = (p - P[i - 1]) / (P[i] - P[i - 1]);
  return B[i - 1] + t * (B[i] - B[i - 1]);
}

double SolidSegmentCheck::bending_error_percent() const {
  return std::abs(bending_deg) > 1e-12 ? 100.0 * (rod_bending_deg - bending_deg) / std::abs(bending_deg) : 0.0;
}

std::string SolidSegmentCheck::working_pressure_verdict() const {
  std::ostringstream at;
  at << std::fixed << std::setprecision(1) << reached_pressure_kPa << " kPa)";
  if (path == fem::PathOutcome::completed) return "held";
  if (path == fem::PathOutcome::limit_point) return "NOT held (ballooning limit point at " + at.str();
  if (fem::is_failure(path)) return "NOT held (" + fem::in_words(path) + " at " + at.str();
  return "not established (the 3D path stalled at " + at.str();
}

nlohmann::json to_json(const SolidSegmentCheck& c) {
  const auto optional_kPa = [](const std::optional<double>& p) { return p ? nlohmann::json(*p) : nlohmann::json(); };
  return {{"segment", c.segment},
          {"element", c.element},
          {"dofs", c.dofs},
          {"reached_pressure_kPa", c.reached_pressure_kPa},
          {"outcome", c.outcome},
          {"path", fem::to_string(c.path)},
          {"bending_deg_3d", c.bending_deg},
          {"bending_deg_rod", c.rod_bending_deg},
          {"pressure_for_target_bending_kPa_3d", optional_kPa(c.pressure_for_target_kPa)},
          {"pressure_for_target_bending_kPa_rod", optional_kPa(c.rod_pressure_for_target_kPa)},
          {"seconds", c.seconds}};
}

SolidSegmentCheck solid_check_from_json(const nlohmann::json& j) {
  const auto optional_kPa = [&j](const char* key) {
    return j.at(key).is_null() ? std::optional<double>() : std::optional<double>(j.at(key).get<double>());
  };
  SolidSegmentCheck c;
  c.segment = j.at("segment").get<int>();
  c.element = j.at("element").get<std::string>();
  c.dofs = j.at("dofs").get<int>();
  c.reached_pressure_kPa = j.at("reached_pressure_kPa").get<double>();
  c.outcome = j.at("outcome").get<std::string>();
  c.path = fem::path_outcome_named(j.at("path").get<std::string>());
  c.bending_deg = j.at("bending_deg_3d").get<double>();
  c.rod_bending_deg = j.at("bending_deg_rod").get<double>();
  c.pressure_for_target_kPa = optional_kPa("pressure_for_target_bending_kPa_3d");
  c.rod_pressure_for_target_kPa = optional_kPa("pressure_for_target_bending_kPa_rod");
  c.seconds = j.at("seconds").get<double>();
  return c;
}

void use_design_check_path(fem::StepSettings& steps, fem::LimitPointSettings& limit) {
  steps.initial_increment = 0.03;
  steps.min_increment = 1e-3;
  limit.volume_control_fraction = 1.0;
}

fem::TcaSceneSpec solid_segment_scene(const ArmCandidate& c, int segment, int mesh_level) {
  fem::TcaSceneSpec spec;
  spec.design = c.design.segments.at(static_cast<std::size_t>(segment - 1));
  spec.tube_material = c.tube;
  spec.ring_material = c.rings;
  spec.sheath_material = c.sheath;
  spec.mesh_level = mesh_level;
  spec.element_order = 2;
  spec.serendipity = true;
  spec.integration = fem::ElementIntegration::reduced;
  return spec;
}

namespace {
/// The check on the cell rod: the same load, the cells on the ladder's rung (fidelity.cpp).
SolidSegmentCheck check_on_cell_rod(fem::TcaSceneSpec spec, int segment, const SegmentMeasures& rod,
                                    const std::function<void(double, double)>& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  fem::use_cell_rod_rung(spec);
  const fem::CellRodTcaResult r = fem::run_cell_rod_tca(spec);
  if (progress)
    for (const auto& state : r.curve) progress(state.pressure_kPa, state.bending_angle_deg);
  SolidSegmentCheck out;
  out.segment = segment;
  out.element = "cell rod on ring-pitch cells" +
                (r.end_rings > 0 ? " and both ends through " + std::to_string(r.end_rings) + " rings" : std::string()) +
                ", H2s/P1 at 27 points, level 1, layers of level 4";
  out.dofs = r.cell_dofs;
  out.reached_pressure_kPa = r.reached_pressure_kPa;
  out.path = r.outcome;
  out.outcome = r.outcome == fem::PathOutcome::completed ? "completed" : r.diagnosis;
  out.bending_deg = r.curve.empty() ? 0.0 : r.curve.back().bending_angle_deg;
  out.rod_bending_deg = bending_at_pressure(rod, out.reached_pressure_kPa);
  out.pressure_for_target_kPa = r.target_pressure_kPa;
  if (rod.pressure_for_target_kPa >= 0) out.rod_pressure_for_target_kPa = rod.pressure_for_target_kPa;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}
}  // namespace

SolidSegmentCheck check_segment_in_3d(const ArmCandidate& c, const EvaluationSettings& s, int segment,
                                      const SegmentMeasures& rod, int mesh_level,
                                      const std::function<void(double, double)>& progress, SolidCheckModel model) {
  const auto t0 = std::chrono::steady_clock::now();
  fem::TcaSceneSpec spec = solid_segment_scene(c, segment, mesh_level);
  // The rod's load (arm_evaluation.cpp, bend_segment): chambers 2 and 3, gravity against the bend.
  const double p = s.working_pressure_kPa;
  spec.chamber_pressure_kPa = {0.0, p, p};
  spec.gravity_m_s2 = Eigen::Vector3d(-s.gravity_m_s2, 0.0, 0.0);
  for (int i = 1; i <= s.pressure_steps; ++i) spec.output_pressures_kPa.push_back(p * i / s.pressure_steps);
  spec.target_bending_deg = s.target_bending_deg;
  use_design_check_path(spec.steps, spec.limit);
  if (model == SolidCheckModel::cell_rod) return check_on_cell_rod(spec, segment, rod, progress);
  const fem::TcaResult r = fem::run_tca_scene(spec, [&](const fem::TcaState& state) {
    if (progress) progress(state.pressure_kPa, state.bending_angle_deg);
  });
  SolidSegmentCheck out;
  out.segment = segment;
  out.element = r.element_name;
  out.dofs = r.dofs;
  out.reached_pressure_kPa = r.path.reached_pressure_kPa;
  out.outcome = r.path.outcome == fem::PathOutcome::completed ? "completed" : r.path.diagnosis;
  out.path = r.path.outcome;
  // The state at the largest pressure (volume control may pass the maximum and fall back).
  const auto highest = std::max_element(r.states.begin(), r.states.end(), [](const auto& a, const auto& b) {
    return a.pressure_kPa < b.pressure_kPa;
  });
  out.bending_deg = highest == r.states.end() ? 0.0 : highest->bending_angle_deg;
  out.rod_bending_deg = bending_at_pressure(rod, out.reached_pressure_kPa);
  out.pressure_for_target_kPa = r.target_pressure_kPa;
  if (rod.pressure_for_target_kPa >= 0) out.rod_pressure_for_target_kPa = rod.pressure_for_target_kPa;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace softarm::objectives

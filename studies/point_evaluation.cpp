#include "studies/point_evaluation.hpp"

#include <chrono>
#include <cmath>
#include <map>

#include "fem/core/input_error.hpp"
#include "fem/materials/burst_criteria.hpp"
#include "fem/scenes/reduced_scenes.hpp"
#include "fem/scenes/scene_config.hpp"

namespace softarm::studies {
using nlohmann::json;

namespace {

double rounded(double x, double digits = 1e4) { return std::round(x * digits) / digits; }

json finite_or_null(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }

/// Spec §4 (a), (b): the larger of the stress and stretch ratios to their allowables.
double criteria_ab(const fem::Material& m, double stress_MPa, double stretch, double safety_factor) {
  return fem::burst_utilisation(m, stress_MPa, stretch, safety_factor).value;
}

/// The deformed outline of an axisymmetric mesh: element edges (corner to corner)
/// used by one element only, per part, as [r0, z0, r1, z1] rows rounded to µm.
json outline(const fem::Mesh& mesh, const fem::Vector& x) {
  std::map<std::pair<int, int>, std::pair<int, int>> edges;  // sorted corners → (count, element)
  for (int e = 0; e < mesh.num_elements(); ++e) {
    const int* n = mesh.element(e);
    for (int k = 0; k < 4; ++k) {
      const int a = n[k], b = n[(k + 1) % 4];
      auto& entry = edges[{std::min(a, b), std::max(a, b)}];
      entry.first += 1;
      entry.second = e;
    }
  }
  json parts = json::object();
  for (const auto& [corners, use] : edges) {
    if (use.first != 1) continue;
    const auto [a, b] = corners;
    parts[mesh.part_names[mesh.part[use.second]]].push_back(
        {rounded(x[2 * a], 1e3), rounded(x[2 * a + 1], 1e3), rounded(x[2 * b], 1e3), rounded(x[2 * b + 1], 1e3)});
  }
  return parts;
}

json evaluate_rra_fem(const StudySpec& spec, const fem::RraSceneSpec& scene) {
  const fem::RraResult r = fem::run_rra_scene(scene);
  json out;
  json& curve = out["curve"];
  curve["pressure_kPa"] = json::array();
  curve["extension_mm"] = json::array();
  for (const auto& c : r.curve) {
    curve["pressure_kPa"].push_back(c.pressure_kPa);
    curve["extension_mm"].push_back(c.extension_mm);
  }
  const fem::RraCurvePoint& last = r.curve.back();
  out["extension_mm"] = last.extension_mm;
  out["mass_g"] = (r.tube_mass_kg + r.ring_mass_kg) * 1e3;
  out["reached_pressure_kPa"] = r.path.reached_pressure_kPa;
  out["max_pressure_kPa"] = scene.path.max_pressure_kPa;
  if (!fem::is_answer(r.path.outcome)) out["status"] = "incomplete";
  out["tube_max_stretch"] = last.tube_max_stretch;
  out["tube_max_principal_stress_MPa"] = last.tube_max_principal_stress_MPa;
  out["tube_max_log_strain"] = last.tube_max_log_strain;
  out["tube_averaged_stretch"] = last.averaged.stretch;
  out["tube_averaged_stress_MPa"] = last.averaged.stress_MPa;
  // Criteria (a), (b) on the ball averages: the point values above sit at the singular groove lip.
  double utilisation = criteria_ab(scene.tube_material, last.averaged.stress_MPa, last.averaged.stretch,
                                   spec.safety_factor);
  out["limit_pressure_kPa"] = nullptr;
  if (r.path.outcome == fem::PathOutcome::limit_point) {
    const double p_limit = r.path.estimated_limit_pressure_kPa > 0 ? r.path.estimated_limit_pressure_kPa
                                                                   : r.path.reached_pressure_kPa;
    out["limit_pressure_kPa"] = p_limit;
    utilisation = std::max(utilisation, scene.path.max_pressure_kPa / p_limit);  // criterion (c)
  } else if (fem::is_answer(r.path.outcome) && r.path.outcome != fem::PathOutcome::completed &&
             r.path.reached_pressure_kPa > 0) {
    // A named material or element failure: the design fails where the path ended.
    utilisation = std::max(utilisation, scene.path.max_pressure_kPa / r.path.reached_pressure_kPa);
  }
  out["burst_utilisation"] = utilisation;
  if (r.path.outcome != fem::PathOutcome::completed) out["diagnosis"] = r.path.diagnosis;
  out["shape"] = {{"kind", "axisymmetric_outline"}, {"parts", outline(r.mesh, r.final_positions)}};
  out["model"] = r.element_name + " axisymmetric, level " + std::to_string(scene.mesh_level);
  out["dofs"] = r.dofs;
  return out;
}

json evaluate_rra_rod(const fem::RraSceneSpec& scene) {
  const fem::ReducedRraResult r = fem::run_reduced_rra(scene);
  json out;
  json& curve = out["curve"];
  curve["pressure_kPa"] = r.pressure_kPa;
  curve["extension_mm"] = json::array();
  for (double e : r.extension_mm) curve["extension_mm"].push_back(finite_or_null(e));
  out["extension_mm"] = curve["extension_mm"].back();
  out["reached_pressure_kPa"] = scene.path.max_pressure_kPa;
  out["max_pressure_kPa"] = scene.path.max_pressure_kPa;
  out["model"] = "rod (uncalibrated chamber force)";
  out["dofs"] = 0;
  return out;
}

json evaluate_tca_rod(const StudySpec& spec, const fem::TcaSceneSpec& scene) {
  const fem::ReducedTcaResult r = fem::run_reduced_tca(scene, spec.rod_nodes);
  const double p_max = std::max({scene.chamber_pressure_kPa[0], scene.chamber_pressure_kPa[1], scene.chamber_pressure_kPa[2]});
  json out;
  out["curve"] = {{"pressure_kPa", r.pressure_kPa}, {"bending_deg", r.bending_deg}};
  out["bending_deg"] = r.bending_deg.empty() ? 0.0 : r.bending_deg.back();
  out["pressure_for_target_kPa"] = r.target_pressure_kPa ? json(*r.target_pressure_kPa) : json(nullptr);
  out["mass_g"] = r.mass_kg * 1e3;
  out["reached_pressure_kPa"] = r.pressure_kPa.empty() ? 0.0 : r.pressure_kPa.back();
  out["max_pressure_kPa"] = p_max;
  if (!r.centreline_mm.empty()) {
    out["tip_x_mm"] = r.centreline_mm.back().x();
    out["tip_z_mm"] = r.centreline_mm.back().z();
  }
  out["tube_max_stretch"] = r.extremes.tube_max_stretch;
  out["sheath_max_stretch"] = r.extremes.sheath_max_stretch;
  double utilisation = std::max(criteria_ab(scene.tube_material, 0, r.extremes.tube_max_stretch, spec.safety_factor),
                                criteria_ab(scene.sheath_material, 0, r.extremes.sheath_max_stretch, spec.safety_factor));
  if (!r.converged) {
    out["diagnosis"] = r.diagnosis;
    if (!r.pressure_kPa.empty() && r.pressure_kPa.back() > 0)
      utilisation = std::max(utilisation, p_max / r.pressure_kPa.back());  // criterion (c)
  }
  out["burst_utilisation"] = utilisation;
  // The centreline and the envelope's half-width (RRA axis distance + outer radius + sheath).
  json shape = {{"kind", "rod_centreline"}, {"x_mm", json::array()}, {"z_mm", json::array()},
                {"half_width_mm", json::array()}};
  const auto& s_ref = r.arc_length_mm;
  const double length = scene.design.actuator.length_mm;
  for (std::size_t i = 0; i < r.centreline_mm.size(); ++i) {
    const double z_ref = length - s_ref[i];  // the clamp is the top face (z = l)
    shape["x_mm"].push_back(rounded(r.centreline_mm[i].x(), 1e3));
    shape["z_mm"].push_back(rounded(r.centreline_mm[i].z(), 1e3));
    shape["half_width_mm"].push_back(rounded(scene.design.axis_distance(z_ref) +
                                             scene.design.actuator.outer_radius(z_ref) +
                                             scene.design.sheath_thickness_mm, 1e3));
  }
  out["shape"] = shape;
  out["model"] = "rod, " + std::to_string(spec.rod_nodes) + " nodes";
  out["dofs"] = 3 * r.nodes;
  return out;
}

json evaluate_tca_fem(const fem::TcaSceneSpec& scene) {
  const fem::TcaResult r = fem::run_tca_scene(scene);
  std::vector<double> p, angle;
  for (const auto& s : r.states) {
    p.push_back(s.pressure_kPa);
    angle.push_back(s.bending_angle_deg);
  }
  json out;
  out["curve"] = {{"pressure_kPa", p}, {"bending_deg", angle}};
  const fem::TcaState& last = r.states.back();
  out["bending_deg"] = last.bending_angle_deg;
  out["pressure_for_target_kPa"] = r.target_pressure_kPa ? json(*r.target_pressure_kPa) : json(nullptr);
  out["mass_g"] = r.mass_kg * 1e3;
  out["reached_pressure_kPa"] = r.path.reached_pressure_kPa;
  out["max_pressure_kPa"] = scene.output_pressures_kPa.back();
  if (!fem::is_answer(r.path.outcome)) out["status"] = "incomplete";
  out["tip_x_mm"] = last.tip_position_mm.x();
  out["tip_z_mm"] = last.tip_position_mm.z();
  double utilisation = 0;
  for (const auto& peak : r.final_peaks) {
    const fem::Material& m = peak.part == "sheath" ? scene.sheath_material : scene.tube_material;
    if (peak.part == "tube" || peak.part == "sheath")
      utilisation = std::max(utilisation, criteria_ab(m, peak.max_principal_stress_MPa, peak.max_principal_stretch, 1.5));
  }
  // A limit point or a named material or element failure below the last pressure: the design fails there.
  if (fem::is_answer(r.path.outcome) && r.path.outcome != fem::PathOutcome::completed && r.path.reached_pressure_kPa > 0)
    utilisation = std::max(utilisation, r.states.back().pressure_kPa > 0 ? scene.output_pressures_kPa.back() /
                                                                               r.path.reached_pressure_kPa
                                                                         : 1.0);
  out["burst_utilisation"] = utilisation;
  if (r.path.outcome != fem::PathOutcome::completed) out["diagnosis"] = r.path.diagnosis;
  out["model"] = r.model.name + ", " + r.element_name + " level " + std::to_string(scene.mesh_level);
  out["dofs"] = r.dofs;
  return out;
}

}  // namespace

json evaluate_point(const StudySpec& spec, const StudyPoint& point) {
  const auto t0 = std::chrono::steady_clock::now();
  json out;
  try {
    const fem::SceneConfig scene = fem::read_scene_config(point.scene);
    if (scene.scene == "rra")
      out = spec.model == "rod" ? evaluate_rra_rod(scene.rra) : evaluate_rra_fem(spec, scene.rra);
    else
      out = spec.model == "rod" ? evaluate_tca_rod(spec, scene.tca) : evaluate_tca_fem(scene.tca);
    if (out.contains("bending_deg")) out["normalised_bending"] = out["bending_deg"].get<double>() / 90.0;
    if (!out.contains("status")) out["status"] = "ok";
  } catch (const fem::InputError& e) {
    out = {{"status", "invalid"}, {"diagnosis", e.what()}};
  } catch (const std::exception& e) {
    out = {{"status", "failed"}, {"diagnosis", std::string("error: ") + e.what()}};
  }
  // Never a NaN in a result: a non-finite output is recorded as null with a note.
  std::vector<std::string> not_finite;
  for (auto& [key, value] : out.items())
    if (value.is_number_float() && !std::isfinite(value.get<double>())) {
      value = nullptr;
      not_finite.push_back(key);
    }
  for (const auto& key : not_finite)
    out["diagnosis"] = out.value("diagnosis", std::string()) + (out.contains("diagnosis") ? "; " : "") + key +
                       " was not finite (recorded as null)";
  out["index"] = point.index;
  out["key"] = point.key;
  out["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace softarm::studies

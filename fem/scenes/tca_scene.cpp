#include "fem/scenes/tca_scene.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <memory>

#include "fem/assembly/energy_problem.hpp"
#include "fem/forms/chamber_pressure_form.hpp"
#include "fem/forms/gravity_form.hpp"
#include "fem/forms/make_elastic_form.hpp"
#include "fem/mesh/tca_mesher.hpp"
#include "fem/post/face_measures.hpp"
#include "fem/core/angles.hpp"

namespace softarm::fem {
namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

}  // namespace

ModelChoice choose_tca_model(const TcaSceneSpec& spec) {
  const auto& p = spec.chamber_pressure_kPa;
  return choose_mirror_model({p[0], p[1], p[2]}, spec.gravity_m_s2, spec.allow_symmetry);
}

std::optional<double> pressure_at_bending(const std::vector<TcaState>& s, double angle_deg) {
  for (std::size_t i = 1; i < s.size(); ++i) {
    if (s[i].bending_angle_deg < angle_deg) continue;
    // Inverse interpolation p(θ): quadratic through three states around the crossing when they are monotonic.
    const std::size_t a = i >= 2 ? i - 2 : i - 1, b = a + 1, c = std::min(a + 2, s.size() - 1);
    const double t0 = s[a].bending_angle_deg, t1 = s[b].bending_angle_deg, t2 = s[c].bending_angle_deg;
    if (c > b && t0 < t1 && t1 < t2) {
      const double t = angle_deg;
      return s[a].pressure_kPa * (t - t1) * (t - t2) / ((t0 - t1) * (t0 - t2)) +
             s[b].pressure_kPa * (t - t0) * (t - t2) / ((t1 - t0) * (t1 - t2)) +
             s[c].pressure_kPa * (t - t0) * (t - t1) / ((t2 - t0) * (t2 - t1));
    }
    const auto& lo = s[i - 1];
    const auto& hi = s[i];
    const double f = (angle_deg - lo.bending_angle_deg) / (hi.bending_angle_deg - lo.bending_angle_deg);
    return lo.pressure_kPa + f * (hi.pressure_kPa - lo.pressure_kPa);
  }
  return std::nullopt;
}

SolidMeshOptions tca_twist_mesh_options(const TcaSceneSpec& spec) {
  TcaSceneSpec rest = spec;
  rest.gravity_m_s2.setZero();
  rest.chamber_pressure_kPa = {0, 0, 0};
  SolidMeshOptions options = solid_mesh_options(rest, choose_tca_model(rest));
  options.half = spec.allow_symmetry;
  options.first_axis_angle_rad = 0;
  return options;
}

Mesh tca_mesh(const TcaSceneSpec& spec, const ModelChoice& model) {
  validate(spec.design);
  return mesh_tca(spec.design, solid_mesh_options(spec, model));
}

std::vector<Material> tca_part_materials(const TcaSceneSpec& spec) {
  return {spec.tube_material, spec.ring_material, spec.sheath_material};
}

Eigen::Vector3d tca_bend_direction(const std::array<double, 3>& p) {
  Eigen::Vector3d bend = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) bend -= p[k] * Eigen::Vector3d(std::cos(k * 2 * kPi / 3), std::sin(k * 2 * kPi / 3), 0);
  return bend;
}

Eigen::Vector3d tca_solver_gravity(const TcaSceneSpec& spec, const ModelChoice& model) {
  return rotation_about_z(-model.frame_angle_rad) * spec.gravity_m_s2;
}

PressurePathSpec tca_pressure_path(const TcaSceneSpec& spec, const ChamberLoads& chambers, bool dead_loads_first,
                                   int node_dimension) {
  PressurePathSpec path;
  path.pressure_fractions = chambers.fractions;
  path.gravity_preload = dead_loads_first;
  path.max_pressure_kPa = chambers.peak_kPa;
  path.output_pressures_kPa = spec.output_pressures_kPa;
  path.newton = spec.newton;
  path.steps = spec.steps;
  path.limit = spec.limit;
  path.node_dimension = node_dimension;
  return path;
}

TcaResult run_tca_scene(const TcaSceneSpec& spec, const TcaProgress& progress) {
  const auto t_start = Clock::now();
  TcaResult out;
  out.model = choose_tca_model(spec);
  const double theta = out.model.frame_angle_rad;
  Mesh mesh = tca_mesh(spec, out.model);
  out.timings.mesh_s = since(t_start);

  const auto t_setup = Clock::now();
  const std::vector<Material> materials = tca_part_materials(spec);
  auto elastic = make_elastic_form(mesh, materials, VolumetricTreatment::projected_dilatation,
                                   hex20_integration(mesh, spec.integration));
  out.element_name = elastic->element_name();
  LoadState load;
  load.chamber_pressure_MPa.assign(mesh.chambers.size(), 0.0);
  EnergyProblem problem(flattened_positions(mesh), clamped_with_symmetry(mesh, "top"));
  problem.add_form(elastic);
  if (spec.newton.rotate_stiff_parts) problem.set_stiff_inclusions(stiff_parts(mesh, materials));
  const ChamberLoads chambers = add_chamber_loads(
      mesh, {spec.chamber_pressure_kPa.begin(), spec.chamber_pressure_kPa.end()}, load, problem);
  const bool weighs = spec.gravity_m_s2.norm() > 0;
  if (weighs)
    problem.add_form(std::make_shared<GravityForm>(mesh, materials, tca_solver_gravity(spec, out.model), load));
  problem.finalize();
  out.dofs = problem.num_dofs();
  const double copies = out.model.half ? 2.0 : 1.0;
  out.part_mass_kg = part_masses_kg(mesh, materials, copies);
  for (const auto& [part, kg] : out.part_mass_kg) out.mass_kg += kg;
  out.timings.setup_s = since(t_setup);

  // The free face and its rest measures.
  const auto free_face = boundary_faces_in(mesh, mesh.node_sets.at("bottom"));
  const auto face = [&](const Vector& x) {
    const FaceMeasure m = measure_face(free_face, x);
    return out.model.half ? mirror_completed(m) : m;
  };
  const FaceMeasure rest = face(problem.reference_positions());
  const Eigen::Matrix3d to_user = rotation_about_z(theta);
  // The 3CA bends away from its pressurised chambers: towards −Σ p_k e_k (e_k the
  // chambers' axis directions, solver frame). The angle is signed by it, so a sag
  // under gravity against the bend reads negative.
  const Eigen::Vector3d bend_direction = rotation_about_z(-theta) * tca_bend_direction(spec.chamber_pressure_kPa);
  const auto state_of = [&](const PressureState& s, const Vector& x) {
    const FaceMeasure now = face(x);
    TcaState t;
    t.pressure_kPa = s.pressure_kPa;
    const double cosine = now.vector_area.normalized().dot(rest.vector_area.normalized());
    t.bending_angle_deg = std::acos(std::clamp(cosine, -1.0, 1.0)) * 180 / kPi;
    // The free face's outward normal (−z at rest) is the tip's tangent: it tilts
    // towards the side the 3CA bends to.
    if (now.vector_area.dot(bend_direction) < 0) t.bending_angle_deg = -t.bending_angle_deg;
    t.tip_position_mm = to_user * now.centroid;
    t.tip_displacement_mm = to_user * (now.centroid - rest.centroid);
    t.chamber_volume_mm3 = copies * s.chamber_volume_mm3;
    t.newton_iterations = s.newton_iterations;
    t.is_output = s.is_output;
    return t;
  };

  PressurePathSpec path = tca_pressure_path(spec, chambers, weighs, 3);
  path.checkpoint = spec.checkpoint;
  Vector x = problem.reference_positions();
  const auto t_solve = Clock::now();
  out.path = run_pressure_path(problem, chambers.loaded, load, x, path, [&](const PressureState& s, const Vector& xs, const ConvergedTangent&) {
    out.states.push_back(state_of(s, xs));
    if (!s.is_output) return;
    out.curve.push_back(out.states.back());
    out.curve_positions.push_back(rotated_about_z(xs, theta));
    if (progress) progress(out.curve.back());
  });
  if (!out.states.empty() && !out.states.back().is_output) {
    out.curve.push_back(out.states.back());
    out.curve_positions.push_back(rotated_about_z(x, theta));
  }
  out.timings.solve_s = since(t_solve);
  out.timings.assembly_s = problem.assembly_seconds();
  out.timings.factorize_s = out.path.factorize_s;
  out.timings.factorizations = out.path.factorizations;
  out.target_pressure_kPa = pressure_at_bending(out.states, spec.target_bending_deg);

  out.final_element_results = elastic->element_results(x);
  out.final_peaks = part_peaks(mesh, out.final_element_results);
  // Report in the user frame.
  out.final_positions = rotated_about_z(x, theta);
  const Vector X_user = rotated_about_z(flattened_positions(mesh), theta);
  for (int n = 0; n < mesh.num_nodes(); ++n) mesh.X.row(n) = X_user.segment<3>(3 * n).transpose();
  out.mesh = std::move(mesh);
  out.timings.total_s = since(t_start);
  return out;
}

}  // namespace softarm::fem

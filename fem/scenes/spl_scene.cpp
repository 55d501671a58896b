#include "fem/scenes/spl_scene.hpp"

#include <algorithm>
#include <chrono>
#include <memory>

#include "fem/assembly/energy_problem.hpp"
#include "fem/elements/reference_quadrature.hpp"
#include "fem/forms/chamber_pressure_form.hpp"
#include "fem/forms/gravity_form.hpp"
#include "fem/forms/make_elastic_form.hpp"
#include "fem/mesh/tca_mesher.hpp"
#include "fem/post/face_measures.hpp"

namespace softarm::fem {
namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// The connector material, its density set from connector_mass_g (each of three) when given.
Material connector_material(const SplSceneSpec& spec, const Mesh& mesh, double copies) {
  Material m = spec.connector_material;
  if (!spec.design.connector_mass_g) return m;
  const double volume_cm3 = 1e-3 * copies * part_volumes_mm3(mesh)[static_cast<std::size_t>(mesh.part_index("connector"))];
  m.density_g_cm3 = 3 * *spec.design.connector_mass_g / volume_cm3;
  return m;
}
}  // namespace

ModelChoice choose_spl_model(const SplSceneSpec& spec) {
  return choose_mirror_model({spec.chamber_pressure_kPa.begin(), spec.chamber_pressure_kPa.end()}, spec.gravity_m_s2,
                             spec.allow_symmetry);
}

SplResult run_spl_scene(const SplSceneSpec& spec, const std::function<void(const SplState&)>& progress) {
  const auto t_start = Clock::now();
  SplResult out;
  out.model = choose_spl_model(spec);
  const double theta = out.model.frame_angle_rad;
  Mesh mesh = mesh_spl(spec.design, solid_mesh_options(spec, out.model));
  out.timings.mesh_s = since(t_start);

  const auto t_setup = Clock::now();
  const double copies = out.model.half ? 2.0 : 1.0;
  const std::vector<Material> materials = {spec.tube_material, spec.ring_material, spec.sheath_material,
                                           connector_material(spec, mesh, copies)};
  auto elastic = make_elastic_form(mesh, materials, VolumetricTreatment::projected_dilatation,
                                   hex20_integration(mesh, spec.integration));
  out.element_name = elastic->element_name();
  LoadState load;
  load.chamber_pressure_MPa.assign(mesh.chambers.size(), 0.0);
  EnergyProblem problem(flattened_positions(mesh), clamped_with_symmetry(mesh, "top"));
  problem.add_form(elastic);
  if (spec.newton.rotate_stiff_parts) problem.set_stiff_inclusions(stiff_parts(mesh, materials));
  PressurePathSpec path;
  const ChamberLoads chambers = add_chamber_loads(
      mesh, {spec.chamber_pressure_kPa.begin(), spec.chamber_pressure_kPa.end()}, load, problem);
  path.pressure_fractions = chambers.fractions;
  const Vector X = flattened_positions(mesh);
  if (spec.gravity_m_s2.norm() > 0) {
    auto gravity = std::make_shared<GravityForm>(mesh, materials, rotation_about_z(-theta) * spec.gravity_m_s2, load);
    // The payload hangs on the tip face (half of it on a half model).
    const auto tip_face = boundary_faces_in(mesh, mesh.node_sets.at("bottom"));
    gravity->add_carried_mass(nodal_area_weights(tip_face, X), spec.tip_mass_kg / copies);
    problem.add_form(gravity);
    path.gravity_preload = true;
  }
  problem.finalize();
  out.dofs = problem.num_dofs();
  out.part_mass_kg = part_masses_kg(mesh, materials, copies);
  for (const auto& [part, kg] : out.part_mass_kg) out.mass_kg += kg;
  out.timings.setup_s = since(t_setup);

  const Eigen::Matrix3d to_user = rotation_about_z(theta);
  const auto tip_nodes = mesh.node_sets.at("bottom");
  const auto user_pose = [&](const std::vector<int>& nodes, const Vector& x) {
    FacePose pose = face_pose(nodes, X, x, out.model.half);
    pose.position_mm = to_user * pose.position_mm;
    pose.rotation = to_user * pose.rotation * to_user.transpose();
    return pose;
  };
  path.max_pressure_kPa = chambers.peak_kPa > 0 ? chambers.peak_kPa : 1.0;  // gravity alone: a unit scale
  for (double level : spec.output_levels) path.output_pressures_kPa.push_back(level * path.max_pressure_kPa);
  path.newton = spec.newton;
  path.steps = spec.steps;
  path.limit = spec.limit;
  path.node_dimension = 3;
  path.checkpoint = spec.checkpoint;
  Vector x = X;
  const auto t_solve = Clock::now();
  const auto state_of = [&](const PressureState& s, const Vector& xs) {
    const FacePose tip = user_pose(tip_nodes, xs);
    return SplState{s.pressure_kPa / path.max_pressure_kPa, tip.position_mm, tip.tilt_deg, s.newton_iterations, {}};
  };
  PressureState last;
  out.path = run_pressure_path(problem, chambers.loaded, load, x, path, [&](const PressureState& s, const Vector& xs, const ConvergedTangent&) {
    last = s;
    if (!s.is_output) return;
    out.curve.push_back(state_of(s, xs));
    out.curve_positions.push_back(rotated_about_z(xs, theta));
    if (progress) progress(out.curve.back());
  });
  if (!last.is_output) {
    out.curve.push_back(state_of(last, x));
    out.curve_positions.push_back(rotated_about_z(x, theta));
  }
  out.timings.solve_s = since(t_solve);
  out.timings.assembly_s = problem.assembly_seconds();
  out.timings.factorize_s = out.path.factorize_s;
  out.timings.factorizations = out.path.factorizations;

  for (int n = 1; n <= 3; ++n) {
    const std::string segment = "segment " + std::to_string(n);
    out.joints.push_back({segment + " top" + (n == 1 ? " (shoulder connector)" : ""),
                          user_pose(mesh.node_sets.at("segment_" + std::to_string(n) + "_top"), x)});
    out.joints.push_back({segment + " bottom" + (n == 3 ? " (tip)" : ""),
                          user_pose(mesh.node_sets.at("segment_" + std::to_string(n) + "_bottom"), x)});
  }
  out.final_element_results = elastic->element_results(x);
  out.final_peaks = part_peaks(mesh, out.final_element_results);
  out.final_positions = rotated_about_z(x, theta);
  const Vector X_user = rotated_about_z(X, theta);
  for (int n = 0; n < mesh.num_nodes(); ++n) mesh.X.row(n) = X_user.segment<3>(3 * n).transpose();
  out.mesh = std::move(mesh);
  out.timings.total_s = since(t_start);
  return out;
}

}  // namespace softarm::fem

#include "fem/scenes/tca_scene.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <memory>

#include "fem/assembly/energy_problem.hpp"
#include "fem/elements/reference_quadrature.hpp"
#include "fem/forms/chamber_pressure_form.hpp"
#include "fem/forms/gravity_form.hpp"
#include "fem/mesh/tca_mesher.hpp"
#include "fem/post/face_measures.hpp"

namespace softarm::fem {
namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
constexpr double kPi = 3.14159265358979323846;
constexpr double kKgPerMm3PerGcm3 = 1e-6;

Eigen::Matrix3d rotation_z(double angle) { return Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix(); }

/// Rotates every node-major 3-vector block of x about z.
Vector rotated(const Vector& x, double angle) {
  const Eigen::Matrix3d R = rotation_z(angle);
  Vector y(x.size());
  for (Eigen::Index n = 0; n < x.size() / 3; ++n) y.segment<3>(3 * n) = R * x.segment<3>(3 * n);
  return y;
}

/// Clamped top face; the symmetry plane keeps u_y = 0.
DirichletConstraints tca_constraints(const Mesh& mesh) {
  DirichletConstraints c;
  std::vector<char> clamped(mesh.num_nodes(), 0);
  for (int n : mesh.node_sets.at("top")) {
    clamped[n] = 1;
    for (int d = 0; d < 3; ++d) c.fix(3 * n + d);
  }
  if (const auto it = mesh.node_sets.find("symmetry"); it != mesh.node_sets.end())
    for (int n : it->second)
      if (!clamped[n]) c.fix(3 * n + 1);
  return c;
}

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}
}  // namespace

ModelChoice choose_tca_model(const TcaSceneSpec& spec) {
  const auto& p = spec.chamber_pressure_kPa;
  const double p_max = std::max({p[0], p[1], p[2]});
  const Eigen::Vector3d& g = spec.gravity_m_s2;
  ModelChoice full{"full model", "", false, 0, 0.0};
  if (!spec.allow_symmetry) {
    full.reason = "symmetry disabled by the config";
    return full;
  }
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const double theta = k * 2 * kPi / 3;
    const Eigen::Vector3d normal(-std::sin(theta), std::cos(theta), 0);
    const bool pressures = std::abs(p[i] - p[j]) <= 1e-12 * std::max(1.0, p_max);
    const bool gravity = std::abs(g.dot(normal)) <= 1e-12 * std::max(1.0, g.norm());
    if (pressures && gravity) {
      ModelChoice half{"half model (mirror plane through chamber " + std::to_string(k + 1) + ")", "", true, k + 1, theta};
      half.reason = "chambers " + std::to_string(i + 1) + " and " + std::to_string(j + 1) + " are at equal pressure (" +
                    fmt(p[i]) + " kPa) and gravity lies in the plane through the 3CA axis and chamber " +
                    std::to_string(k + 1) + ": geometry and loads are mirror-symmetric, so half the body carries "
                    "the whole answer at about half the unknowns";
      return half;
    }
  }
  full.reason = "no mirror plane carries both the chamber pressures (" + fmt(p[0]) + ", " + fmt(p[1]) + ", " +
                fmt(p[2]) + " kPa) and gravity";
  return full;
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

Mesh tca_mesh(const TcaSceneSpec& spec, const ModelChoice& model) {
  validate(spec.design);
  SolidMeshOptions options;
  options.level = spec.mesh_level;
  options.order = spec.element_order;
  options.half = model.half;
  options.first_axis_angle_rad = -model.frame_angle_rad;  // the mirror chamber on +x in the solver frame
  return mesh_tca(spec.design, options);
}

std::vector<Material> tca_part_materials(const TcaSceneSpec& spec) {
  return {spec.tube_material, spec.ring_material, spec.sheath_material};
}

Eigen::Vector3d tca_solver_gravity(const TcaSceneSpec& spec, const ModelChoice& model) {
  return rotation_z(-model.frame_angle_rad) * spec.gravity_m_s2;
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
  auto elastic = make_elastic_form(mesh, materials);
  out.element_name = elastic->element_name();
  LoadState load;
  load.chamber_pressure_MPa.assign(mesh.chambers.size(), 0.0);
  EnergyProblem problem(flattened_positions(mesh), tca_constraints(mesh));
  problem.add_form(elastic);
  const auto& p = spec.chamber_pressure_kPa;
  const double p_max = std::max({p[0], p[1], p[2]});
  std::vector<std::shared_ptr<ChamberPressureForm>> chambers;
  std::vector<const ChamberPressureForm*> loaded;
  PressurePathSpec path;
  for (int c = 0; c < 3; ++c)
    if (p[c] > 0 && !mesh.chambers[c].facets.empty()) {
      chambers.push_back(std::make_shared<ChamberPressureForm>(mesh, c, load));
      problem.add_form(chambers.back());
      loaded.push_back(chambers.back().get());
      path.pressure_fractions.push_back(p[c] / p_max);
    }
  if (spec.gravity_m_s2.norm() > 0) {
    problem.add_form(std::make_shared<GravityForm>(mesh, materials, tca_solver_gravity(spec, out.model), load));
    path.gravity_preload = true;
  }
  problem.finalize();
  out.dofs = problem.num_dofs();
  const double copies = out.model.half ? 2.0 : 1.0;
  const auto volumes = part_volumes_mm3(mesh);
  for (std::size_t i = 0; i < volumes.size(); ++i) {
    const double kg = copies * volumes[i] * materials[i].density_g_cm3 * kKgPerMm3PerGcm3;
    out.part_mass_kg.emplace_back(mesh.part_names[i], kg);
    out.mass_kg += kg;
  }
  out.timings.setup_s = since(t_setup);

  // The free face and its rest measures.
  const auto free_face = boundary_faces_in(mesh, mesh.node_sets.at("bottom"));
  const auto face = [&](const Vector& x) {
    const FaceMeasure m = measure_face(free_face, x);
    return out.model.half ? mirror_completed(m) : m;
  };
  const FaceMeasure rest = face(problem.reference_positions());
  const Eigen::Matrix3d to_user = rotation_z(theta);
  // The 3CA bends away from its pressurised chambers: towards −Σ p_k e_k (e_k the
  // chambers' axis directions, solver frame). The angle is signed by it, so a sag
  // under gravity against the bend reads negative.
  Eigen::Vector3d bend_direction = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) {
    const double angle = k * 2 * kPi / 3 - theta;
    bend_direction -= p[k] * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0);
  }
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

  path.max_pressure_kPa = p_max;
  path.output_pressures_kPa = spec.output_pressures_kPa;
  path.newton = spec.newton;
  path.steps = spec.steps;
  path.limit = spec.limit;
  Vector x = problem.reference_positions();
  const auto t_solve = Clock::now();
  out.path = run_pressure_path(problem, loaded, load, x, path, [&](const PressureState& s, const Vector& xs) {
    out.states.push_back(state_of(s, xs));
    if (!s.is_output) return;
    out.curve.push_back(out.states.back());
    if (progress) progress(out.curve.back());
  });
  if (!out.states.empty() && !out.states.back().is_output) out.curve.push_back(out.states.back());
  out.timings.solve_s = since(t_solve);
  out.timings.assembly_s = problem.assembly_seconds();
  out.timings.factorize_s = out.path.factorize_s;
  out.timings.factorizations = out.path.factorizations;
  out.target_pressure_kPa = pressure_at_bending(out.states, spec.target_bending_deg);

  out.final_element_results = elastic->element_results(x);
  for (std::size_t i = 0; i < mesh.part_names.size(); ++i) out.final_peaks.push_back({mesh.part_names[i]});
  for (int e = 0; e < mesh.num_elements(); ++e) {
    const auto& r = out.final_element_results[e];
    PartPeak& peak = out.final_peaks[static_cast<std::size_t>(mesh.part[e])];
    peak.max_principal_stretch = std::max(peak.max_principal_stretch, r.max_principal_stretch);
    peak.max_principal_stress_MPa = std::max(peak.max_principal_stress_MPa, r.max_principal_cauchy_MPa);
    peak.max_principal_log_strain = std::max(peak.max_principal_log_strain, r.max_principal_log_strain);
  }
  // Report in the user frame.
  out.final_positions = rotated(x, theta);
  const Vector X_user = rotated(flattened_positions(mesh), theta);
  for (int n = 0; n < mesh.num_nodes(); ++n) mesh.X.row(n) = X_user.segment<3>(3 * n).transpose();
  out.mesh = std::move(mesh);
  out.timings.total_s = since(t_start);
  return out;
}

}  // namespace softarm::fem

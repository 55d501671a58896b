#include "fem/scenes/rra_scene.hpp"

#include <algorithm>
#include <memory>

#include "fem/assembly/energy_problem.hpp"
#include "fem/forms/make_elastic_form.hpp"
#include "fem/mesh/rra_mesher.hpp"
#include "fem/post/region_average.hpp"

namespace softarm::fem {
namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Axis nodes keep r = 0 (symmetry); the fixed end is clamped.
DirichletConstraints rra_constraints(const Mesh& mesh) {
  DirichletConstraints c;
  std::vector<char> clamped(mesh.num_nodes(), 0);
  for (int n : mesh.node_sets.at("fixed_end")) {
    clamped[n] = 1;
    c.fix(2 * n);
    c.fix(2 * n + 1);
  }
  for (int n : mesh.node_sets.at("axis"))
    if (!clamped[n]) c.fix(2 * n);
  return c;
}

RraCurvePoint curve_point(const PressureState& s, const Mesh& mesh, const ElasticForm& elastic,
                          const Vector& x, int free_node, double extension_sign, double averaging_radius_mm) {
  RraCurvePoint p;
  p.pressure_kPa = s.pressure_kPa;
  p.chamber_volume_mm3 = s.chamber_volume_mm3;
  p.pv_stiffness_kPa_per_mm3 = s.pv_stiffness_kPa_per_mm3;
  p.newton_iterations = s.newton_iterations;
  p.extension_mm = extension_sign * (x[2 * free_node + 1] - mesh.X(free_node, 1)) + 0.0;  // + 0.0: no "-0.000"
  const int tube = mesh.part_index("tube"), rings = mesh.part_index("rings");
  const auto results = elastic.element_results(x);
  for (int e = 0; e < mesh.num_elements(); ++e) {
    const auto& r = results[e];
    if (mesh.part[e] == tube) {
      p.tube_max_stretch = std::max(p.tube_max_stretch, r.max_principal_stretch);
      p.tube_max_log_strain = std::max(p.tube_max_log_strain, r.max_principal_log_strain);
      p.tube_max_principal_stress_MPa = std::max(p.tube_max_principal_stress_MPa, r.max_principal_cauchy_MPa);
    } else if (mesh.part[e] == rings) {
      p.ring_max_principal_stress_MPa = std::max(p.ring_max_principal_stress_MPa, r.max_principal_cauchy_MPa);
    }
  }
  std::vector<double> stretch, stress, log_strain;
  for (const auto& r : results) {
    stretch.push_back(r.mean_principal_stretch);
    stress.push_back(r.mean_principal_cauchy_MPa);
    log_strain.push_back(r.mean_principal_log_strain);
  }
  p.averaged.stretch = max_region_average(mesh, stretch, tube, averaging_radius_mm).value;
  p.averaged.stress_MPa = max_region_average(mesh, stress, tube, averaging_radius_mm).value;
  p.averaged.log_strain = max_region_average(mesh, log_strain, tube, averaging_radius_mm).value;
  return p;
}
}  // namespace

Mesh rra_mesh(const RraSceneSpec& spec) {
  validate(spec.design);
  // Q2 elements get 2 layers through the wall at level 1 (5 nodes), Q1 3 (4 nodes).
  return spec.element_order == 2 ? mesh_rra_quadratic(spec.design, spec.mesh_level, 2)
                                 : mesh_rra(spec.design, spec.mesh_level, 3);
}

std::vector<Material> rra_part_materials(const Mesh& mesh, const RraSceneSpec& spec) {
  std::vector<Material> materials(mesh.part_names.size(), spec.tube_material);
  if (const int rings = mesh.part_index("rings"); rings >= 0) materials[rings] = spec.ring_material;
  return materials;
}

AbaqusDeck rra_abaqus_deck(const RraSceneSpec& spec, const Mesh& mesh, double pressure_kPa) {
  AbaqusDeck deck;
  deck.heading = "softarm RRA scene exported for CalculiX/Abaqus";
  deck.mesh = &mesh;
  deck.part_materials = rra_part_materials(mesh, spec);
  deck.clamped_node_sets = {"fixed_end"};
  deck.axis_node_sets = {"axis"};
  deck.chamber_pressure_MPa.assign(mesh.chambers.size(), 0.0);
  deck.chamber_pressure_MPa.at(0) = pressure_kPa * 1e-3;
  deck.printed_node_sets = {"free_end_centre"};
  return deck;
}

RraResult run_rra_scene(const RraSceneSpec& spec, const RraProgress& progress) {
  const auto t_start = Clock::now();
  RraResult out;
  out.mesh = rra_mesh(spec);
  const Mesh& mesh = out.mesh;
  out.timings.mesh_s = since(t_start);

  const auto t_setup = Clock::now();
  auto elastic = make_elastic_form(mesh, rra_part_materials(mesh, spec), spec.treatment);
  out.element_name = elastic->element_name();
  LoadState load;
  load.chamber_pressure_MPa.assign(mesh.chambers.size(), 0.0);
  auto chamber = std::make_shared<ChamberPressureForm>(mesh, 0, load);
  EnergyProblem problem(flattened_positions(mesh), rra_constraints(mesh));
  problem.add_form(elastic);
  problem.add_form(chamber);
  problem.finalize();
  out.dofs = problem.num_dofs();
  // Mass from the exact geometry (the mesh's polygonal rings lose up to 10 % at level 1).
  constexpr double kKgPerMm3PerGcm3 = 1e-6;
  out.tube_mass_kg = tube_volume_mm3(spec.design) * spec.tube_material.density_g_cm3 * kKgPerMm3PerGcm3;
  out.ring_mass_kg = ring_volume_mm3(spec.design) * spec.ring_material.density_g_cm3 * kKgPerMm3PerGcm3;
  out.timings.setup_s = since(t_setup);

  const int free_node = mesh.node_sets.at("free_end_centre").front();
  const double sign = spec.design.fixed_end == RraDesign::FixedEnd::top ? -1.0 : 1.0;
  Vector x = problem.reference_positions();
  const auto t_solve = Clock::now();
  PressurePathSpec path = spec.path;
  path.node_dimension = 2;  // (r, z)
  out.path = run_pressure_path(problem, {chamber.get()}, load, x, path, [&](const PressureState& s, const Vector& xs, const ConvergedTangent&) {
    if (!s.is_output) return;
    out.curve.push_back(curve_point(s, mesh, *elastic, xs, free_node, sign, spec.peak_averaging_radius_mm));
    out.curve_positions.push_back(xs);
    if (progress) progress(out.curve.back());
  });
  // A path that stopped early also reports the last state it reached: x is the state of the
  // largest pressure, which is past the last pressure-controlled one when volume control
  // climbed further (its states carry dp/dV from the tangent of their last Newton iteration).
  if (out.path.outcome != PathOutcome::completed) {
    PressureState last = out.path.history.back();
    for (const PressureState& s : out.path.beyond_limit)
      if (s.pressure_kPa > last.pressure_kPa) last = s;
    if (!last.is_output) {
      out.curve.push_back(curve_point(last, mesh, *elastic, x, free_node, sign, spec.peak_averaging_radius_mm));
      out.curve_positions.push_back(x);
    }
  }
  out.timings.solve_s = since(t_solve);
  out.timings.assembly_s = problem.assembly_seconds();
  out.timings.evaluations = problem.evaluations();
  out.final_positions = x;
  out.final_element_results = elastic->element_results(x);
  out.timings.total_s = since(t_start);
  return out;
}

}  // namespace softarm::fem

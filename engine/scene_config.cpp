#include "engine/scene_config.hpp"

#include <algorithm>

#include "fem/core/json_reader.hpp"

namespace softarm::engine {
using fem::InputError;
using fem::JsonReader;
using fem::Range;

namespace {

fem::PressurePathSpec read_load(JsonReader load, JsonReader solver) {
  fem::PressurePathSpec path;
  path.max_pressure_kPa = load.number("max_pressure_kPa", Range::positive(), "final chamber pressure, kPa");
  auto outputs = load.number_list("output_pressures_kPa", Range::positive(),
                                  "pressures at which the curve is reported (the solver lands on each exactly)");
  const int count = load.integer("output_count", 10, Range::closed(1, 10000),
                                 "number of evenly spaced output pressures when output_pressures_kPa is absent");
  if (outputs.empty())
    for (int i = 1; i <= count; ++i) outputs.push_back(path.max_pressure_kPa * i / count);
  for (double p : outputs)
    if (p > path.max_pressure_kPa * (1 + 1e-12))
      throw InputError(load.field("output_pressures_kPa"), "value " + std::to_string(p) +
                       " exceeds max_pressure_kPa = " + std::to_string(path.max_pressure_kPa));
  outputs.push_back(path.max_pressure_kPa);
  std::sort(outputs.begin(), outputs.end());
  outputs.erase(std::unique(outputs.begin(), outputs.end(),
                            [](double a, double b) { return std::abs(a - b) < 1e-12 * std::max(1.0, std::abs(b)); }),
                outputs.end());
  path.output_pressures_kPa = outputs;
  load.finish();

  auto& st = path.steps;
  st.initial_increment = solver.number("initial_increment_fraction", st.initial_increment, Range::open(0, 1),
                                       "first load increment as a fraction of the full load");
  st.max_increment = solver.number("max_increment_fraction", st.max_increment, Range::closed(1e-6, 1),
                                   "largest load increment as a fraction of the full load");
  st.min_increment = solver.number("min_increment_fraction", st.min_increment, Range::open(0, 1),
                                   "smallest increment before the path is declared stuck");
  auto& nw = path.newton;
  nw.max_iterations = solver.integer("max_newton_iterations", nw.max_iterations, Range::closed(1, 1000),
                                     "Newton iterations per step before a cut-back");
  nw.residual_tolerance = solver.number("residual_tolerance", nw.residual_tolerance, Range::open(0, 1),
                                        "‖r‖ / max(‖r₀‖, ‖f_load‖) at convergence");
  nw.update_tolerance = solver.number("update_tolerance", nw.update_tolerance, Range::open(0, 1),
                                      "‖δx‖ / ‖u‖ at convergence");
  st.verbose = solver.boolean("print_convergence_tables", false, "print a Newton convergence table for every step");
  path.limit.stiffness_fraction =
      solver.number("limit_point_stiffness_fraction", path.limit.stiffness_fraction, Range::open(0, 1),
                    "a failed step with dp/dV below this fraction of its initial value is reported as a limit point");
  solver.finish();
  return path;
}

fem::RraSceneSpec read_rra(JsonReader& root) {
  fem::RraSceneSpec spec;
  auto geometry = root.object("geometry", "RRA geometry (physical or normalised sizes)");
  spec.design = fem::read_rra_design(geometry);
  geometry.finish();
  fem::validate(spec.design);

  auto materials = root.object("materials", "materials by part: a built-in name or a material object");
  auto read_material = [&](const std::string& key, const char* default_name) {
    return fem::material_from_json(materials.has(key) ? materials.raw(key) : nlohmann::json(default_name),
                                   materials.field(key));
  };
  spec.tube_material = read_material("tube", "dragon_skin_30");
  spec.ring_material = read_material("rings", "digital_abs");
  materials.finish();

  auto mesh = root.object("mesh", "discretisation");
  spec.mesh_level = mesh.integer("level", spec.mesh_level, Range::closed(1, 6),
                                 "refinement level (each level halves the element size)");
  spec.element_order = mesh.integer("element_order", spec.element_order, Range::closed(1, 2),
                                    "1: bilinear Q1/P0 (mean dilatation); 2: biquadratic Q2/P1 (converges next to rigid rings)");
  const auto treatment = mesh.choice("volumetric_treatment", "projected_dilatation", {"projected_dilatation", "pointwise"},
                                     "projected_dilatation avoids locking; pointwise is kept for comparison only");
  spec.treatment = treatment == "pointwise" ? fem::VolumetricTreatment::pointwise : fem::VolumetricTreatment::projected_dilatation;
  mesh.finish();

  spec.path = read_load(root.object("load", "loading"), root.object("solver", "nonlinear solver controls"));
  return spec;
}

}  // namespace

SceneConfig read_scene_config(const nlohmann::json& document) {
  JsonReader root(document, "");
  SceneConfig config;
  config.scene = root.choice("scene", "rra", {"rra"}, "which assembly to simulate");
  config.rra = read_rra(root);
  auto output = root.object("output", "where results go");
  config.output.directory = output.string("directory", "out/" + config.scene, "output directory (created if absent)");
  config.output.vtu = output.boolean("vtu", true, "write the deformed mesh as VTU for ParaView");
  output.finish();
  root.string("description", "", "free text");
  root.finish();
  return config;
}

SceneConfig load_scene_config(const std::string& file_name) { return read_scene_config(fem::load_json_file(file_name)); }

}  // namespace softarm::engine

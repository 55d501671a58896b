#include "fem/scenes/scene_config.hpp"

#include <algorithm>
#include <optional>

#include "fem/core/json_reader.hpp"
#include "fem/mesh/tca_mesher.hpp"
#include "fem/scenes/fidelity.hpp"

namespace softarm::fem {
using fem::InputError;
using fem::JsonReader;
using fem::Range;

namespace {

/// Output pressures (sorted, ending at max_pressure): a list, or a count of evenly spaced ones.
std::vector<double> read_output_pressures(JsonReader& load, double max_pressure) {
  auto outputs = load.number_list("output_pressures_kPa", Range::positive(),
                                  "pressures at which the curve is reported (the solver lands on each exactly)");
  const int count = load.integer("output_count", 10, Range::closed(1, 10000),
                                 "number of evenly spaced output pressures when output_pressures_kPa is absent");
  if (outputs.empty())
    for (int i = 1; i <= count; ++i) outputs.push_back(max_pressure * i / count);
  for (double p : outputs)
    if (p > max_pressure * (1 + 1e-12))
      throw InputError(load.field("output_pressures_kPa"),
                       "value " + std::to_string(p) + " exceeds the peak pressure " + std::to_string(max_pressure) + " kPa");
  outputs.push_back(max_pressure);
  std::sort(outputs.begin(), outputs.end());
  outputs.erase(std::unique(outputs.begin(), outputs.end(),
                            [](double a, double b) { return std::abs(a - b) < 1e-12 * std::max(1.0, std::abs(b)); }),
                outputs.end());
  return outputs;
}

void read_solver(JsonReader solver, fem::NewtonSettings& nw, fem::StepSettings& st, fem::LimitPointSettings& limit) {
  st.initial_increment = solver.number("initial_increment_fraction", st.initial_increment, Range::open(0, 1),
                                       "first load increment as a fraction of the full load");
  st.max_increment = solver.number("max_increment_fraction", st.max_increment, Range::closed(1e-6, 1),
                                   "largest load increment as a fraction of the full load");
  st.min_increment = solver.number("min_increment_fraction", st.min_increment, Range::open(0, 1),
                                   "smallest increment before the path is declared stuck");
  nw.max_iterations = solver.integer("max_newton_iterations", nw.max_iterations, Range::closed(1, 1000),
                                     "Newton iterations per step before a cut-back");
  nw.residual_tolerance = solver.number("residual_tolerance", nw.residual_tolerance, Range::open(0, 1),
                                        "‖r‖ / max(‖r₀‖, ‖f_load‖) at convergence");
  nw.update_tolerance = solver.number("update_tolerance", nw.update_tolerance, Range::open(0, 1),
                                      "‖δx‖ / ‖u‖ at convergence, or the bound on the error left that the "
                                      "last two full steps' contraction gives");
  nw.shift_indefinite_tangent =
      solver.choice("indefinite_tangent", nw.shift_indefinite_tangent ? "shifted_cholesky" : "lu",
                    {"shifted_cholesky", "lu"},
                    "how Newton solves with a tangent that is not positive definite: shifted_cholesky (K + σI, a "
                    "descent step; the 3D scenes' default) or lu (exact UMFPACK LU; the axisymmetric default)") ==
      "shifted_cholesky";
  nw.reuse_factor = solver.boolean(
      "reuse_factor", nw.reuse_factor,
      "solve Newton steps by conjugate gradients preconditioned with the last Cholesky factor, factorising only where "
      "that fails or would cost more than half a factorisation (the 3D scenes' default; off: factorise every iteration)");
  nw.max_indefinite_iterations = solver.integer(
      "max_indefinite_iterations", nw.max_indefinite_iterations, Range::closed(0, 1000),
      "a Newton step gives up (and the load step is cut back) after this many iterations on an indefinite tangent "
      "that did not halve the best residual so far, with none between that did, or where it converges on an indefinite "
      "tangent: no stable equilibrium near that load; 0: never (the default is 4)");
  nw.rotate_stiff_parts = solver.boolean(
      "rotate_stiff_parts", nw.rotate_stiff_parts,
      "Newton's update applies each stiff part's (ABS ring's, connector's) best-fit rotation as a finite rotation, so "
      "a step that bends the actuator does not stretch its rings (the 3D scenes' default; off: the plain update x + dx)");
  st.verbose = solver.boolean("print_convergence_tables", false, "print a Newton convergence table for every step");
  limit.stiffness_fraction =
      solver.number("limit_point_stiffness_fraction", limit.stiffness_fraction, Range::open(0, 1),
                    "a failed step with dp/dV below this fraction of its initial value is reported as a limit point");
  limit.volume_control_fraction = solver.number(
      "volume_control_stiffness_fraction", limit.volume_control_fraction, Range::closed(0, 1),
      "where pressure control fails with dp/dV below this fraction of its initial value, chamber-volume control "
      "follows the path from there to find a pressure maximum (ballooning); 1: at every stall");
  limit.hand_over_ahead = solver.boolean(
      "volume_control_ahead_of_limit", limit.hand_over_ahead,
      "hand the path to chamber-volume control before a step past the pressure where dp/dV, extrapolated linearly "
      "from the last two states, falls to zero, rather than try steps past a maximum; where volume control finds none "
      "before the next output pressure, pressure control goes on (off: volume control only at a stall)");
  limit.hand_over_after_failure = solver.boolean(
      "volume_control_after_failed_step", limit.hand_over_after_failure,
      "where volume_control_ahead_of_limit is off: the same hand-over, once a step past the last converged state "
      "has failed from every start (off: volume control only at a stall)");
  limit.lowest_mode_fraction = solver.number(
      "lowest_mode_fraction", limit.lowest_mode_fraction, Range::closed(0, 1),
      "at a stall with dp/dV above the threshold, the tangent's lowest eigenvalue below this fraction of its value at "
      "rest is reported as a (local) limit point; 0 skips the check (two factorisations and a few dozen solves)");
  limit.check_lowest_mode = limit.lowest_mode_fraction > 0;
  limit.fold_margin = solver.number(
      "fold_margin", limit.fold_margin, Range::closed(0, 1),
      "at a stall none of the above explains, one of the tangent's four lowest eigenvalues extrapolated to zero "
      "within this fraction of the last converged pressure is a fold (a limit point, fem/solver/fold_estimate.hpp); "
      "0: a stall stays a stall");
  limit.volume_control_by_cg = solver.boolean(
      "volume_control_by_cg", limit.volume_control_by_cg,
      "volume control solves by CG on K + a*dV*dV^T preconditioned with the starting tangent's Cholesky factor, "
      "factorising K (an LU past the maximum) only where CG fails (the 3D scenes' default; off: every iteration "
      "factorises, the axisymmetric default)");
  solver.finish();
}

fem::PressurePathSpec read_load(JsonReader load, JsonReader solver) {
  fem::PressurePathSpec path;
  path.max_pressure_kPa = load.number("max_pressure_kPa", Range::positive(), "final chamber pressure, kPa");
  path.output_pressures_kPa = read_output_pressures(load, path.max_pressure_kPa);
  load.finish();
  read_solver(std::move(solver), path.newton, path.steps, path.limit);
  return path;
}

/// A material by part: a built-in name or a material object.
fem::Material read_material(JsonReader& materials, const std::string& key, const char* default_name) {
  static const std::string names = [] {
    std::string s;
    for (const auto& n : fem::builtin_material_names()) s += (s.empty() ? "" : ", ") + n;
    return s;
  }();
  const nlohmann::json& given = materials.raw(key, "name or object",
                                              "the " + key + " material: a built-in name (" + names +
                                                  ") or a material object (docs/materials.md)",
                                              std::string("\"") + default_name + "\"");
  return fem::material_from_json(given.is_null() ? nlohmann::json(default_name) : given, materials.field(key));
}

/// Mesh level and element order; `max_level` bounds what this machine can hold.
void read_mesh(JsonReader& mesh, int& level, int& order, int max_level, const std::string& order_doc) {
  level = mesh.integer("level", level, Range::closed(1, max_level), "refinement level (each level halves the element size)");
  order = mesh.integer("element_order", order, Range::closed(1, 2), order_doc);
}

/// The "model" object: symmetry (3D scenes) and the fidelity request (every scene).
struct ModelRequest {
  bool allow_symmetry = true;
  std::optional<double> target_error_percent;  // from fidelity or target_error_percent
  std::string asked;                           // the request in the user's words
};

ModelRequest read_model(JsonReader& root, bool three_dimensional) {
  ModelRequest r;
  auto model = root.object("model", "model choice: symmetry and fidelity");
  if (three_dimensional)
    r.allow_symmetry = model.choice("symmetry", "auto", {"auto", "off"},
                                    "auto: solve a half model when pressures and gravity are mirror-symmetric") == "auto";
  const std::string fidelity =
      model.choice("fidelity", "", {"", "fast", "balanced", "accurate"},
                   "pick the model by the fidelity ladder (softarm fidelity): fast (the cheapest model, its measured error "
                   "printed), balanced (within 2 %), accurate (within 0.5 %: the cheapest measured level that meets "
                   "it); empty: mesh.level as given");
  const auto target = model.optional_number("target_error_percent", Range::open(0, 100),
                                            "pick the cheapest model whose measured error is within this (%)");
  if (!fidelity.empty() && target)
    throw InputError(model.field("target_error_percent"), "give model.fidelity or model.target_error_percent, not both");
  if (!fidelity.empty()) r.target_error_percent = fidelity_target_percent(fidelity), r.asked = "fidelity '" + fidelity + "'";
  if (target) r.target_error_percent = *target, r.asked = "target error " + std::to_string(*target) + " %";
  model.finish();
  return r;
}

/// The mesh and model objects of a 3D scene (levels up to `max_level` fit this machine).
void read_3d_discretisation(JsonReader& root, int& level, int& axial_level, int& order, bool& serendipity,
                            ElementIntegration& integration, bool& allow_symmetry, ModelRequest& request, int max_level,
                            const std::string& order_doc) {
  auto mesh = root.object("mesh", "discretisation");
  read_mesh(mesh, level, order, max_level, order_doc);
  axial_level = mesh.optional_integer("axial_level", Range::closed(1, 4),
                                      "element layers along the axis as at this level (absent: mesh.level), the "
                                      "cross-section as at mesh.level: the thesis 3CA's level-1 error lies along its "
                                      "axis (docs/mesh-convergence.md, One direction at a time), and level 1 with "
                                      "axial_level 4 is the fidelity ladder's 3CA reference "
                                      "(docs/mesh-convergence.md, Layers to level 4: the whole 3CA)")
                    .value_or(0);
  serendipity = mesh.boolean("serendipity", serendipity,
                             "with element_order 2: 20-node serendipity hexahedra (Hex20/P1, the C3D20 of CalculiX) "
                             "instead of Hex27: about 45 % fewer unknowns on the same mesh");
  if (serendipity && order != 2)
    throw InputError(mesh.field("serendipity"), "true needs mesh.element_order 2 (got " + std::to_string(order) + ")");
  const bool reduced = mesh.boolean("reduced_integration", integration == ElementIntegration::reduced,
                                    "with serendipity: integrate Hex20 at 2x2x2 Gauss points (CalculiX's C3D20R) "
                                    "instead of 3x3x3: element assembly about 2x cheaper, and at level 1 the thesis 3CA bends within 3.5 % of level 2 (3x3x3: up to 6 % short)");
  if (reduced && !serendipity)
    throw InputError(mesh.field("reduced_integration"), "true needs mesh.serendipity true (a 20-node hexahedron)");
  integration = reduced ? ElementIntegration::reduced : ElementIntegration::full;
  mesh.finish();
  request = read_model(root, true);
  allow_symmetry = request.allow_symmetry;
}

RraSceneSpec read_rra(JsonReader& root, ModelRequest& model_request) {
  RraSceneSpec spec;
  auto geometry = root.object("geometry", "RRA geometry (physical or normalised sizes)");
  spec.design = fem::read_rra_design(geometry);
  geometry.finish();
  fem::validate(spec.design);

  auto materials = root.object("materials", "materials by part: a built-in name or a material object");
  spec.tube_material = read_material(materials, "tube", "dragon_skin_30");
  spec.ring_material = read_material(materials, "rings", "digital_abs");
  materials.finish();

  auto mesh = root.object("mesh", "discretisation");
  read_mesh(mesh, spec.mesh_level, spec.element_order, 6,
            "1: bilinear Q1/P0 (mean dilatation); 2: biquadratic Q2/P1 (converges next to rigid rings)");
  const auto treatment = mesh.choice("volumetric_treatment", "projected_dilatation", {"projected_dilatation", "pointwise"},
                                     "projected_dilatation avoids locking; pointwise is kept for comparison only");
  spec.treatment = treatment == "pointwise" ? fem::VolumetricTreatment::pointwise : fem::VolumetricTreatment::projected_dilatation;
  spec.peak_averaging_radius_mm =
      mesh.number("peak_averaging_radius_mm", kDefaultPeakAveragingRadius_mm, Range::closed(0.05, 20),
                  "the tube's peak stretch, stress and log strain (burst criteria a, b; durability) are averages "
                  "over a ball of this radius where they are largest: a point value at the groove lip is singular "
                  "(docs/definitions.md, Peak averaging radius)");
  mesh.finish();

  model_request = read_model(root, false);
  spec.path = read_load(root.object("load", "loading"), root.object("solver", "nonlinear solver controls"));
  return spec;
}

/// load.chamber_pressures_kPa: exactly `count` peaks (kPa), ramped together.
std::vector<double> read_chamber_pressures(JsonReader& load, std::size_t count, const std::string& which) {
  const auto p = load.required_number_list("chamber_pressures_kPa", Range::non_negative(),
                                           "peak pressure of chambers " + which + " (kPa), ramped together from 0",
                                           std::to_string(count) + " pressures (kPa), chambers " + which);
  if (p.size() != count)
    throw InputError(load.field("chamber_pressures_kPa"), "needs " + std::to_string(count) + " pressures (chambers " +
                                                               which + "), got " + std::to_string(p.size()));
  return p;
}

/// The silicone and ABS parts every 3D actuator has.
void read_actuator_materials(JsonReader& materials, fem::Material& tube, fem::Material& rings, fem::Material& sheath) {
  tube = read_material(materials, "tube", "dragon_skin_30");
  rings = read_material(materials, "rings", "digital_abs");
  sheath = read_material(materials, "sheath", "dragon_skin_30");
}

std::optional<Eigen::Vector3d> read_vector3(JsonReader& r, const std::string& key, const std::string& doc);

TcaSceneSpec read_tca(JsonReader& root, ModelRequest& model_request) {
  TcaSceneSpec spec;
  auto geometry = root.object("geometry", "3CA geometry: the RRA keys plus spacing, sheath and centre hole");
  spec.design = fem::read_tca_design(geometry);

  auto materials = root.object("materials", "materials by part: a built-in name or a material object");
  read_actuator_materials(materials, spec.tube_material, spec.ring_material, spec.sheath_material);
  materials.finish();

  read_3d_discretisation(root, spec.mesh_level, spec.axial_level, spec.element_order, spec.serendipity,
                         spec.integration, spec.allow_symmetry, model_request, 3,
                         "1: trilinear Hex8/P0 (mean dilatation; locks in bending at coarse levels); 2: triquadratic Hex27/P1");

  auto load = root.object("load", "loading");
  const auto pressures = read_chamber_pressures(load, 3, "1, 2, 3");
  if (*std::max_element(pressures.begin(), pressures.end()) <= 0)
    throw InputError(load.field("chamber_pressures_kPa"), "at least one chamber pressure must be > 0");
  std::copy(pressures.begin(), pressures.end(), spec.chamber_pressure_kPa.begin());
  const double p_max = *std::max_element(pressures.begin(), pressures.end());
  spec.output_pressures_kPa = read_output_pressures(load, p_max);
  if (auto g = read_vector3(load, "gravity_m_s2", "gravity vector (m/s²) in the 3CA frame: z along the axis towards "
                                                  "the fixed top, chamber 1 on +x; absent or [0, 0, 0]: off"))
    spec.gravity_m_s2 = *g;
  spec.target_bending_deg = load.number("target_bending_deg", 90, Range::open(0, 180),
                                        "bending angle whose pressure is reported (deg)");
  load.finish();
  read_solver(root.object("solver", "nonlinear solver controls"), spec.newton, spec.steps, spec.limit);
  return spec;
}

/// An optional 3-vector (m/s²).
std::optional<Eigen::Vector3d> read_vector3(JsonReader& r, const std::string& key, const std::string& doc) {
  const auto v = r.number_list(key, Range{}, doc);
  if (v.empty()) return std::nullopt;
  if (v.size() != 3) throw InputError(r.field(key), "needs three components (x, y, z), got " + std::to_string(v.size()));
  return Eigen::Vector3d(v[0], v[1], v[2]);
}

SplSceneSpec read_spl(JsonReader& root, ModelRequest& model_request) {
  SplSceneSpec spec;
  auto geometry = root.object("geometry", "SPL geometry: taper ratio, distal radius, connectors, 3CA and RRA keys");
  spec.design = fem::read_spl_design(geometry);
  geometry.finish();

  auto materials = root.object("materials", "materials by part: a built-in name or a material object");
  read_actuator_materials(materials, spec.tube_material, spec.ring_material, spec.sheath_material);
  spec.connector_material = read_material(materials, "connector", "digital_abs");
  materials.finish();

  read_3d_discretisation(root, spec.mesh_level, spec.axial_level, spec.element_order, spec.serendipity,
                         spec.integration, spec.allow_symmetry, model_request, 2,
                         "1: trilinear Hex8/P0 (a quick preview: locks in bending); 2: triquadratic Hex27/P1");

  auto load = root.object("load", "loading");
  const auto pressures = read_chamber_pressures(load, 9, "1–9; segment n holds 3n−2 … 3n");
  std::copy(pressures.begin(), pressures.end(), spec.chamber_pressure_kPa.begin());
  if (auto g = read_vector3(load, "gravity_m_s2", "gravity vector (m/s²): z along the arm towards the shoulder; "
                                                  "default [0, 0, -9.80665], the arm hanging"))
    spec.gravity_m_s2 = *g;
  spec.tip_mass_kg = load.number("tip_mass_kg", 0, Range::non_negative(), "payload carried by the tip face (kg)");
  const int count = load.integer("output_count", 10, Range::closed(1, 10000), "evenly spaced output load levels");
  for (int i = 1; i <= count; ++i) spec.output_levels.push_back(static_cast<double>(i) / count);
  load.finish();
  read_solver(root.object("solver", "nonlinear solver controls"), spec.newton, spec.steps, spec.limit);
  return spec;
}

}  // namespace

SceneConfig read_scene_config(const nlohmann::json& document) {
  JsonReader root(document, "");
  SceneConfig config;
  config.scene = root.choice("scene", "rra", {"rra", "tca", "spl"},
                             "which assembly to simulate: rra (ring-reinforced actuator), tca (three-chambered "
                             "actuator), spl (the Soft Poly-Limb arm)");
  ModelRequest request;
  if (config.scene == "tca")
    config.tca = read_tca(root, request);
  else if (config.scene == "spl")
    config.spl = read_spl(root, request);
  else
    config.rra = read_rra(root, request);
  if (request.target_error_percent) {
    // The ladder sets the mesh: a level given by hand as well would be ambiguous.
    const nlohmann::json& mesh = document.contains("mesh") ? document["mesh"] : nlohmann::json::object();
    for (const char* key : {"level", "axial_level", "element_order", "serendipity", "reduced_integration"})
      if (mesh.contains(key))
        throw InputError("model.fidelity", "the fidelity ladder picks mesh.level, mesh.axial_level, mesh.element_order, "
                                           "mesh.serendipity and mesh.reduced_integration: give either those "
                                           "or model.fidelity / model.target_error_percent");
    apply_fidelity(config, *request.target_error_percent, request.asked);
  }
  auto output = root.object("output", "where results go");
  config.output.directory = output.string("directory", "out/" + config.scene, "output directory (created if absent)");
  config.output.vtu = output.boolean("vtu", true, "write the deformed mesh as VTU for ParaView");
  output.finish();
  root.string("description", "", "free text");
  root.finish();
  return config;
}

int SceneConfig::layers_level() const {
  if (scene == "tca") return fem::layers_level(tca.mesh_level, tca.axial_level);
  if (scene == "spl") return fem::layers_level(spl.mesh_level, spl.axial_level);
  return rra.mesh_level;
}

void apply_fidelity(SceneConfig& config, double target_error_percent, const std::string& asked) {
  config.selection = select_model(config.scene, target_error_percent);
  config.selection->reason = asked + ": " + config.selection->reason;
  config.reduced = config.selection->level.reduced;
  config.cell_rod = config.selection->level.cell_rod;
  if (!config.reduced || config.cell_rod) {
    config.mesh_level() = config.selection->level.mesh_level;
    config.tca.axial_level = config.spl.axial_level = config.selection->level.axial_level;
    config.element_order() = config.selection->level.element_order;
    config.tca.serendipity = config.spl.serendipity = config.selection->level.serendipity;
    config.tca.integration = config.spl.integration =
        config.selection->level.reduced_integration ? ElementIntegration::reduced : ElementIntegration::full;
    config.tca.cell_rod_end_rings = config.selection->level.end_rings;
  }
}

SceneConfig load_scene_config(const std::string& file_name) { return read_scene_config(fem::load_json_file(file_name)); }

}  // namespace softarm::engine

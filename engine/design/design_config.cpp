#include "engine/design/design_config.hpp"

#include "engine/design/design_measures.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "fem/core/input_error.hpp"
#include "fem/core/json_reader.hpp"
#include "fem/materials/material.hpp"
#include "fem/mesh/spl_design.hpp"

namespace softarm::engine {
namespace {
using fem::Range;

struct VariableInfo {
  const char* name;
  optimise::VariableKind kind;
  double baseline, lo, hi;  // baseline = thesis value; [lo, hi] = what the model accepts
  const char* unit;
  const char* doc;
};

// Baselines: the thesis design (Tables 7 and 11).
const std::vector<VariableInfo>& infos() {
  using K = optimise::VariableKind;
  static const std::vector<VariableInfo> v = {
      {"wall_thickness_normalised", K::continuous, 0.466, 0.1, 0.8, "1", "t_w / r_b of every RRA"},
      {"wall_thickness_mm", K::continuous, 0.466 * 9, 0.5, 10, "mm", "t_w, the same in every segment (physical twin of the normalised wall)"},
      {"end_cap_thickness_normalised", K::continuous, 0.25, 0.05, 1.0, "1", "t_c / r_b"},
      {"end_cap_thickness_mm", K::continuous, 0.25 * 9, 0.3, 15, "mm", "t_c, the same in every segment"},
      {"ring_count", K::integer, 30, 0, 80, "rings", "n_r per RRA (eq 8 with d_ref = 2 mm: r̂ = n_r·2/160)"},
      {"ring_thickness_normalised", K::continuous, 0.4, 0.05, 0.95, "1", "d_r / (l / n_r); 1 = rings touch"},
      {"ring_diameter_mm", K::continuous, 0.4 * 160.0 / 30, 0.2, 10, "mm", "d_r, the ring's section diameter"},
      {"actuator_spacing_mm", K::continuous, 3, 0.5, 10, "mm", "gap between neighbouring RRAs' outer surfaces"},
      {"taper_ratio", K::continuous, 0.5, 0.25, 1.0, "1", "t_r = (r_b)_3 / (r_t)_1 (eq 6)"},
      {"tube_material", K::categorical, 2, 0, 0, "", "RRA tube silicone"},
      {"sheath_material", K::categorical, 2, 0, 0, "", "3CA core and sheath silicone"},
  };
  return v;
}

std::string show(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

objectives::EvaluationSettings read_model(fem::JsonReader& m, const objectives::EvaluationSettings& defaults,
                                          const std::string& what) {
  objectives::EvaluationSettings s = defaults;
  s.rra_mesh_level = m.integer("rra_mesh_level", defaults.rra_mesh_level, Range::closed(1, 4),
                               what + ": mesh level of each segment's axisymmetric RRA FEM");
  s.pressure_steps = m.integer("pressure_steps", defaults.pressure_steps, Range::closed(2, 200),
                               what + ": rod continuation steps to the working pressure");
  s.rod_nodes_per_segment = m.integer("rod_nodes_per_segment", defaults.rod_nodes_per_segment, Range::closed(5, 400),
                                      what + ": rod nodes per 3CA segment");
  s.ring_confinement = m.boolean("ring_confinement", defaults.ring_confinement,
                                 what + ": the rod's 3CA sections let the rings hold the tube wall (confined wall "
                                        "law, chamber force on the rings' inner area; docs/reduced-model.md, "
                                        "Ring-confined walls)");
  m.finish();
  return s;
}
}  // namespace

double Requirements::allowed_strain_ratio() const {
  if (strain_life_exponent <= 0) return 1.0;  // only the measured point: no more strain than it had
  return std::pow(durability_reference_cycles / durability_cycles, 1.0 / strain_life_exponent);
}

const std::vector<std::string>& design_variable_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const auto& i : infos()) n.push_back(i.name);
    return n;
  }();
  return names;
}

// Extra constraints that no design can meet together, or that contradict a requirement, are refused
// before any work: a lower bound above an upper bound on the same measure (two constraints, or a
// constraint and the requirement on that measure). Their `g` would be infeasible everywhere and the
// whole search would run to say so.
static void check_constraints_consistent(const DesignConfig& c) {
  struct Bound {
    double value;
    std::string where;
  };
  const Requirements& q = c.requirements;
  std::map<std::string, Bound> lowest_max = {
      {"mass_kg", {q.max_mass_kg, "requirements.max_mass_kg"}}};
  std::map<std::string, Bound> highest_min = {
      {"payload_kg", {q.min_payload_kg, "requirements.min_payload_kg"}},
      {"min_bending_deg", {q.bending_per_segment_deg, "requirements.bending_per_segment_deg"}}};
  for (std::size_t i = 0; i < c.extra_constraints.size(); ++i) {
    const MeasureBound& b = c.extra_constraints[i];
    const std::string field = "constraints[" + std::to_string(i) + "]." + (b.is_min ? "min" : "max");
    auto& mine = b.is_min ? highest_min : lowest_max;
    const auto& other = b.is_min ? lowest_max : highest_min;
    if (const auto o = other.find(b.measure); o != other.end() && (b.is_min ? b.limit > o->second.value
                                                                             : b.limit < o->second.value))
      throw fem::InputError(field, "= " + show(b.limit) + " on " + b.measure + (b.is_min ? " exceeds " : " is below ") +
                                       o->second.where + " = " + show(o->second.value) +
                                       ": no design can meet both; valid: " + (b.is_min ? "<= " : ">= ") +
                                       show(o->second.value));
    const auto m = mine.find(b.measure);
    if (m == mine.end() || (b.is_min ? b.limit > m->second.value : b.limit < m->second.value))
      mine[b.measure] = {b.limit, field};
  }
}

namespace {
/// requirements: what the arm must achieve (spec §3).
void read_requirements(fem::JsonReader& root, Requirements& q) {
  auto r = root.object("requirements", "what the arm must achieve (spec §3)");
  q.max_mass_kg = r.number("max_mass_kg", 2.0, Range::positive(), "weight limit, connectors included (kg)");
  q.length_m = r.number("length_m", 0.6, Range::positive(), "arm length, shoulder to tip (m): fixes the segment length");
  q.min_payload_kg = r.number("min_payload_kg", 0.5, Range::non_negative(),
                              "payload capacity at the tip (kg; definition: docs/definitions.md, The "
                              "definitions; spec §4)");
  q.bending_per_segment_deg = r.number("bending_per_segment_deg", 90, Range::open(0, 360),
                                       "bending angle each segment must reach at the working pressure (deg)");
  q.max_pressure_kPa = r.number("max_pressure_kPa", fem::thesis::kWorkingPressure_kPa, Range::open(0, 2000),
                                "supply (working) pressure of every chamber (kPa)");
  q.durability_cycles = r.number("durability_cycles", 1e6, Range::positive(), "required RRA life (cycles)");
  q.durability_reference_pressure_kPa =
      r.number("durability_reference_pressure_kPa", fem::thesis::kRraTestPressure_kPa, Range::positive(),
               "pressure of the measured fatigue point: the thesis RRA cycled 0 <-> this (kPa)");
  q.durability_reference_cycles = r.number("durability_reference_cycles", 1.1e6, Range::positive(),
                                           "cycles the thesis RRA lasted at that pressure");
  q.strain_life_exponent =
      r.number("strain_life_exponent", 0, Range::non_negative(),
               "optional strain-life curve N = N_ref (eps_ref/eps)^b through the measured point; 0: none");
  r.finish();
  if (q.strain_life_exponent == 0 && q.durability_cycles > q.durability_reference_cycles)
    throw fem::InputError("requirements.durability_cycles",
                          "value " + show(q.durability_cycles) + " exceeds the only measured fatigue point (" +
                              show(q.durability_reference_cycles) +
                              " cycles): without a strain-life curve (requirements.strain_life_exponent) softarm "
                              "cannot show it; valid: <= " +
                              show(q.durability_reference_cycles));
}

/// objective: a name, or an object naming any measure to minimise or maximise.
void read_objective(fem::JsonReader& root, DesignConfig& c) {
  // "minimise_mass" / "maximise_payload", or {"minimise": measure} / {"maximise": measure}.
  if (root.has("objective") && root.raw("objective").is_object()) {
    auto o = root.object("objective", "{\"minimise\": measure} or {\"maximise\": measure} (softarm schema: measures)");
    const std::string key = o.has("maximise") ? "maximise" : "minimise";
    c.maximise = key == "maximise";
    c.objective_measure = o.string(key, "the measure to optimise");
    o.finish();
    design_measure(c.objective_measure, o.field(key));
    c.objective = key + "_" + c.objective_measure;
  } else {
    c.objective = root.choice("objective", "minimise_mass", {"minimise_mass", "maximise_payload"},
                              "what the optimiser minimises (or an object naming any measure); the requirements are "
                              "constraints");
    c.maximise = c.objective == "maximise_payload";
    c.objective_measure = c.maximise ? "payload_kg" : "mass_kg";
  }
}

/// constraints: bounds on any measure besides the requirements, consistent with each other.
void read_constraints(fem::JsonReader& root, DesignConfig& c) {
  if (root.has("constraints")) {
    const auto& list = root.raw("constraints");
    if (!list.is_array()) throw fem::InputError("constraints", "expected a list of {\"measure\": name, \"min\"|\"max\": value}");
    for (std::size_t i = 0; i < list.size(); ++i) {
      fem::JsonReader k(list[i], "constraints[" + std::to_string(i) + "]");
      MeasureBound b;
      b.measure = k.string("measure", "a measure (design_measures.hpp)");
      design_measure(b.measure, k.field("measure"));
      if (k.has("min") == k.has("max"))
        throw fem::InputError(k.field("min"), "give exactly one of 'min' or 'max'");
      b.is_min = k.has("min");
      b.limit = k.number(b.is_min ? "min" : "max", Range::closed(-1e12, 1e12), "the bound, in the measure's unit");
      k.finish();
      c.extra_constraints.push_back(b);
    }
    check_constraints_consistent(c);
  }
}

/// materials: the baseline tube and sheath (built-in names).
void read_baseline_materials(fem::JsonReader& root, DesignConfig& c) {
  auto m = root.object("materials", "baseline materials");
  c.baseline_tube = m.string("tube", "dragon_skin_30", "RRA tube material (built-in name)");
  c.baseline_sheath = m.string("sheath", "dragon_skin_30", "core and sheath material (built-in name)");
  m.finish();
  fem::builtin_material(c.baseline_tube, "materials.tube");
  fem::builtin_material(c.baseline_sheath, "materials.sheath");
}

/// design_space: each variable's bounds (or choices) and its start, the baseline's value.
void read_design_space(fem::JsonReader& root, const nlohmann::json& baseline_json, DesignConfig& c) {
  auto space = root.object("design_space", "the variables: {\"min\": .., \"max\": ..} or {\"choices\": [..]}");
  for (const auto& info : infos()) {
    if (!space.has(info.name)) continue;
    const std::string field = space.field(info.name);
    auto v = space.object(info.name, info.doc);
    DesignVariable d;
    d.variable.name = info.name;
    d.variable.kind = info.kind;
    d.variable.unit = info.unit;
    if (info.kind == optimise::VariableKind::categorical) {
      if (!v.has("choices")) throw fem::InputError(field + ".choices", "required list of built-in material names is missing");
      const auto& list = v.raw("choices");
      if (!list.is_array() || list.empty())
        throw fem::InputError(field + ".choices", "expected a non-empty list of built-in material names");
      for (std::size_t i = 0; i < list.size(); ++i) {
        const std::string name = list[i].is_string() ? list[i].get<std::string>() : std::string("?");
        fem::builtin_material(name, field + ".choices[" + std::to_string(i) + "]");
        d.variable.choices.push_back(name);
      }
      const std::string base = std::string(info.name) == "tube_material" ? c.baseline_tube : c.baseline_sheath;
      const auto it = std::find(d.variable.choices.begin(), d.variable.choices.end(), base);
      d.baseline = it == d.variable.choices.end() ? 0 : static_cast<double>(it - d.variable.choices.begin());
    } else {
      d.variable.lower = v.number("min", Range::closed(info.lo, info.hi), std::string("lower bound of ") + info.name);
      d.variable.upper = v.number("max", Range::closed(info.lo, info.hi), std::string("upper bound of ") + info.name);
      if (!(d.variable.upper > d.variable.lower))
        throw fem::InputError(field + ".max", "value " + show(d.variable.upper) + " must exceed min = " +
                                                  show(d.variable.lower) + " (impossible bounds)");
      if (info.kind == optimise::VariableKind::integer &&
          (d.variable.lower != std::round(d.variable.lower) || d.variable.upper != std::round(d.variable.upper)))
        throw fem::InputError(field, "integer variable: min and max must be whole numbers");
      // The search starts from the baseline: the value baseline_geometry gives this variable (in the
      // same unit), which must lie within its bounds, else the thesis value brought within them.
      const auto given = baseline_json.find(info.name);
      if (given != baseline_json.end() && given->is_number()) {
        const double b = given->get<double>();
        if (!(b >= d.variable.lower && b <= d.variable.upper))
          throw fem::InputError(std::string("baseline_geometry.") + info.name,
                                "= " + show(b) + " is outside " + field + " [" + show(d.variable.lower) + ", " +
                                    show(d.variable.upper) + "]: the search starts from the baseline; move it "
                                    "inside the bounds or widen them");
        d.baseline = b;
      } else {
        d.baseline = std::clamp(info.baseline, d.variable.lower, d.variable.upper);
      }
    }
    v.finish();
    c.variables.push_back(d);
  }
  for (const auto& [a, b] : {std::pair{"wall_thickness_normalised", "wall_thickness_mm"},
                             std::pair{"end_cap_thickness_normalised", "end_cap_thickness_mm"},
                             std::pair{"ring_thickness_normalised", "ring_diameter_mm"}})
    if (space.has(a) && space.has(b))
      throw fem::InputError(space.field(b), std::string("give the variable in one unit only: '") + a + "' or '" + b + "'");
  space.finish();
  if (c.variables.empty()) throw fem::InputError("design_space", "no variable given; valid names: ring_count, ...");
}

/// model and check: the search's and the check's fidelity, the verification, the correction and
/// improvement rounds.
void read_fidelity(fem::JsonReader& root, DesignConfig& c) {
  auto m = root.object("model", "search fidelity (the reduced rod model + each segment's RRA FEM)");
  c.model = read_model(m, objectives::EvaluationSettings{}, "search");
  objectives::EvaluationSettings fine;
  // The local peaks' definition (docs/definitions.md, Peak averaging radius); level + 1 is reported
  // as a sensitivity.
  fine.rra_mesh_level = c.model.rra_mesh_level;
  fine.pressure_steps = 24;
  fine.rod_nodes_per_segment = 49;
  fine.ring_confinement = c.model.ring_confinement;  // the same rod, finer
  auto k = root.object("check", "fidelity of the final design's re-check");
  c.solid_check_segment = k.integer("solid_segment", 0, Range::closed(0, 3),
                                    "bend this segment (1 proximal … 3 distal) of the optimum by the 3D FEM "
                                    "(check.solid_model) and report the rod's bending error against it; 0: no 3D "
                                    "check");
  const std::string solid_model = k.choice(
      "solid_model", "cell_rod", {"cell_rod", "hex20_2x2x2"},
      "the check's model: cell_rod, the cell rod on ring-pitch cells of Hex20/P1 at 27 points with level 4's layers "
      "(~1 min; against the fidelity ladder's reference mesh: within 3.3 % on the thesis 3CA and the round-0 "
      "optimum, +7.9 % on round 1's at the working pressure), or hex20_2x2x2, the whole segment by Hex20/P1 at "
      "2x2x2 points, level 1 (4-8 min; 0.85 % on the thesis 3CA by a cancellation, 17 and 16 % short on the "
      "round-0 and round-1 optima)");
  c.solid_check_model = solid_model == "cell_rod" ? objectives::SolidCheckModel::cell_rod
                                                  : objectives::SolidCheckModel::hex20_reduced;
  const std::string verification = k.choice(
      "verification", "cell_rod", {"cell_rod", "none"},
      "cell_rod: every optimum is verified on the cell rod of the whole arm (ring-pitch cells and end cells of "
      "each segment, ~3-10 min a design on 2 cores): each segment's bending, the hanging arm's payload, burst "
      "(the cells' limit points; peaks from the cells' chamber stretch), durability, mass; the verification "
      "decides feasibility and corrects the search model (check.corrections). none: the search model's verdict "
      "stands (a first look in minutes; its measured error is printed)");
  c.verify_on_cells = verification == "cell_rod";
  c.cell_levels = k.integer("cell_levels", 16, Range::closed(4, 64),
                            "the verification's cells report every 1/cell_levels of the working pressure");
  c.mesh_sensitivity = k.boolean("mesh_sensitivity", true,
                                 "evaluate the optimum's local peaks one RRA mesh level finer and report how the burst "
                                 "and durability measures move (four RRA FEM paths at that level, about a minute); "
                                 "false skips it (the answer is unchanged)");
  c.cell_layers_level = k.integer("cell_layers_level", 0, Range::closed(0, 4),
                                  "the verification's cells' element layers along the axis as at this mesh level; 0: "
                                  "the fidelity ladder's cell-rod rung (level 4's layers, within 1.4 % of the 3D "
                                  "reference on the thesis 3CA); 1: about a sixth of the cost, coarser (a quick look, "
                                  "a test), its error not measured on the ladder");
  c.trust_radius = k.number("trust_radius", 0.25, Range::closed(0.01, 1),
                            "the first search corrected by verified designs stays within this fraction of each "
                            "variable's range of the best verified design (1: the whole range); each correction "
                            "round halves it");
  c.solid_corrections = k.integer("corrections", 0, Range::closed(0, 5),
                                  "check and correct: while the verification (or, without one, the 3D check of "
                                  "check.solid_segment) finds a requirement not met, correct the search model by it "
                                  "(each requirement it measures matched at the verified design) and search again "
                                  "from the last optimum, at most this many times; each round costs a search and a "
                                  "verification");
  if (c.solid_corrections > 0 && c.solid_check_segment == 0 && !c.verify_on_cells)
    throw fem::InputError(k.field("corrections"), "= " + std::to_string(c.solid_corrections) +
                                                       " needs a check to correct by: set check.verification to "
                                                       "cell_rod or check.solid_segment to 1, 2 or 3");
  c.improvement_rounds = k.integer("improvement_rounds", 0, Range::closed(0, 5),
                                   "trust-region model management past feasibility: when a verified design meets "
                                   "every requirement, correct the search model by it too and search again about "
                                   "it, at most this many times; a round whose search predicts an objective better "
                                   "by less than check.improvement_tolerance_percent stops without a verification, "
                                   "one whose verified design is not better keeps the best; each round costs a "
                                   "search and a verification (cell_rod verification only)");
  c.improvement_tolerance = 0.01 * k.number("improvement_tolerance_percent", 0.5, Range::closed(0, 50),
                                            "an improvement round stops when its search predicts the objective "
                                            "better than the best verified design's by less than this (% of it)");
  c.improvement_evaluations = k.integer("improvement_evaluations", 0, Range::closed(0, 100000),
                                        "real evaluations of an improvement round's search, which starts at a "
                                        "verified design, at most optimiser.max_evaluations (0: that)");
  if (c.improvement_rounds > 0 && !c.verify_on_cells)
    throw fem::InputError(k.field("improvement_rounds"), "= " + std::to_string(c.improvement_rounds) +
                                                             " needs the verification on the cell rod: set "
                                                             "check.verification to cell_rod");
  c.check = read_model(k, fine, "check");
  for (auto* s : {&c.model, &c.check}) {
    s->working_pressure_kPa = c.requirements.max_pressure_kPa;
    s->target_bending_deg = c.requirements.bending_per_segment_deg;
  }
}

/// criteria: the burst criteria's safety factor and peak averaging (spec §4), and the search's margin.
void read_criteria(fem::JsonReader& root, DesignConfig& c) {
  auto sf = root.object("criteria", "burst criteria (spec §4) and the search's design margin");
  const double factor = sf.number("safety_factor", 1.5, Range::at_least(1), "divides strength and elongation at break");
  c.search_margin = 0.01 * sf.number("search_margin_percent", 1.0, Range::closed(0, 50),
                                     "every constraint must hold with this margin (% of its limit) on the search "
                                     "model, so that the re-check at the check fidelity still meets it");
  const double radius = sf.number("peak_averaging_radius_mm", fem::kDefaultPeakAveragingRadius_mm,
                                  Range::closed(0.05, 20),
                                  "criteria (a), (b) and the durability strain read the tube's peaks as averages over a "
                                  "ball of this radius where they are largest (a point value at the groove lip is "
                                  "singular: docs/definitions.md, Peak averaging radius)");
  sf.finish();
  c.model.safety_factor = c.check.safety_factor = factor;
  c.model.peak_averaging_radius_mm = c.check.peak_averaging_radius_mm = radius;
}

/// optimiser: algorithm and budget.
void read_optimiser(fem::JsonReader& root, optimise::Options& p) {
  auto o = root.object("optimiser", "algorithm and budget");
  p.algorithm = o.choice("algorithm", "nlopt:cobyla", optimise::algorithm_names(), "NLopt or Ipopt algorithm");
  p.max_evaluations = o.integer("max_evaluations", 100, Range::closed(1, 100000), "real model evaluations, in all");
  p.starts = o.integer("starts", 1, Range::closed(1, 1000), "multi-start: local searches from a Latin-hypercube sample");
  p.seed = static_cast<unsigned>(o.integer("seed", 1, Range::closed(0, 1e9), "random seed of starts and ISRES"));
  p.relative_tolerance = o.number("relative_tolerance", 1e-3, Range::open(0, 1), "stop tolerance on x and f");
  p.finite_difference_step = o.number("finite_difference_step", 1e-2, Range::open(0, 0.5),
                                      "forward-difference step, fraction of each variable's range");
  p.categorical_keep = o.integer("categorical_keep", 2, Range::closed(1, 100),
                                 "material combinations optimised in full after screening");
  o.finish();
}

/// baseline_geometry, parsed once as the SPL scene's keys; the segment length follows from the
/// arm's length.
void read_baseline_geometry(const nlohmann::json& baseline_json, DesignConfig& c) {
  // Parsed once, here: the keys and ranges are the SPL scene's. The segment length follows from the
  // arm's length and the connectors (spec §1: 3·l + 3 connectors), whatever the geometry says. The
  // baseline must be an arm that can be built: checked before any work rather than where the search
  // first builds it.
  nlohmann::json g = baseline_json;
  g["length_mm"] = 1.0;  // a placeholder within range, set below
  fem::JsonReader reader(g, "baseline_geometry");
  c.baseline_geometry = fem::read_spl_parameters(reader);
  reader.finish();
  const double arm_mm = c.requirements.length_m * 1000, connector_mm = c.baseline_geometry.connector_thickness_mm;
  if (!(3 * connector_mm < arm_mm)) {
    std::ostringstream why;
    why << connector_mm << " mm: three connectors of it leave no length for the segments of the " << arm_mm
        << " mm arm (requirements.length_m); valid: < " << arm_mm / 3 << " mm";
    throw fem::InputError("baseline_geometry.connector_thickness_mm", why.str());
  }
  c.baseline_geometry.set("length_mm", (arm_mm - 3 * connector_mm) / 3);
  fem::build_spl_design(c.baseline_geometry);
}
}  // namespace

DesignConfig read_design_config(const nlohmann::json& document) {
  DesignConfig c;
  fem::JsonReader root(document, "");
  read_requirements(root, c.requirements);
  read_objective(root, c);
  read_constraints(root, c);
  {
    auto g = root.object("baseline_geometry",
                         "SPL geometry keys (softarm schema --scene spl) held fixed, and the start of the optimised ones");
    (void)g;  // its keys are the SPL scene's, read by read_baseline_geometry
  }
  // Read for the variables' starts; parsed once into c.baseline_geometry.
  const nlohmann::json baseline_json =
      document.contains("baseline_geometry") ? document["baseline_geometry"] : nlohmann::json::object();
  read_baseline_materials(root, c);
  read_design_space(root, baseline_json, c);
  read_fidelity(root, c);
  read_criteria(root, c);
  read_optimiser(root, c.optimiser);
  {
    auto o = root.object("output", "where the report goes");
    c.output_directory = o.string("directory", "out/design", "output directory");
    o.finish();
  }
  read_baseline_geometry(baseline_json, c);
  root.finish();
  return c;
}

}  // namespace softarm::engine

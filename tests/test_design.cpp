// The requirements config and the design problem of `softarm design`: the
// thesis requirements load, every kind of bad input names its field (also
// through the command line, exit code 2), the baseline is the thesis design,
// a geometry that cannot be built is an infeasible evaluation with a reason,
// and the finite-difference gradients the optimiser uses agree with the
// Richardson-extrapolated derivative.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

#include "fem/core/angles.hpp"
#include "engine/design/design_config.hpp"
#include "engine/design/design_measures.hpp"
#include "engine/design/design_problem.hpp"
#include "engine/design/measures_memo.hpp"
#include "fem/scenes/rra_scene.hpp"
#include "objectives/payload_capacity.hpp"
#include "fem/core/input_error.hpp"
#include "fem/core/json_reader.hpp"

using namespace softarm;

namespace {
nlohmann::json thesis_requirements() {
  return fem::load_json_file(std::string(SOFTARM_SOURCE_DIR) + "/configs/thesis_requirements.json");
}

std::string error_field(const nlohmann::json& doc) {
  try {
    engine::read_design_config(doc);
  } catch (const fem::InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

// Segment 1's bending angle at the working pressure as a function of one geometry value.
double segment_bending(const engine::DesignConfig& config, const std::string& variable, double value) {
  std::vector<double> x = engine::baseline_values(config);
  for (std::size_t i = 0; i < config.variables.size(); ++i)
    if (config.variables[i].variable.name == variable) x[i] = value;
  const objectives::ArmCandidate c = engine::make_candidate(config, x);
  const fem::ArmRod rod = objectives::segment_rod(c, config.model, 0);
  fem::RodLoad load;
  load.chamber_pressure_kPa = {{0, config.model.working_pressure_kPa, config.model.working_pressure_kPa}};
  load.gravity_m_s2 = {-9.80665, 0};
  const fem::RodState st = rod.follow(load, config.model.pressure_steps);
  REQUIRE(st.converged);
  return rod.tip_rotation(st, load) * softarm::fem::kDeg;
}
}  // namespace

TEST_CASE("the thesis requirements config loads with the thesis design as its baseline", "[design]") {
  const engine::DesignConfig c = engine::read_design_config(thesis_requirements());
  CHECK(c.requirements.max_mass_kg == 2.0);
  CHECK(c.requirements.min_payload_kg == 0.5);
  CHECK(c.variables.size() == 8);
  const objectives::ArmCandidate thesis = engine::make_candidate(c, engine::baseline_values(c));
  CHECK(thesis.design.segments[0].actuator.top_radius_mm == Approx(18));
  CHECK(thesis.design.segments[2].actuator.bottom_radius_mm == Approx(9));
  CHECK(thesis.design.segments[1].actuator.ring_count == 30);
  CHECK(thesis.design.segments[0].actuator.length_mm == Approx(160));
  CHECK(thesis.design.total_length_mm() == Approx(600));
  CHECK(thesis.tube.name == "dragon_skin_30");
}

TEST_CASE("bad requirements name the field", "[design]") {
  auto doc = thesis_requirements();
  SECTION("typo'd key") {
    doc["requirements"]["max_mas_kg"] = 2;
    CHECK_THAT(error_field(doc), Catch::Contains("requirements.max_mas_kg"));
  }
  SECTION("unknown variable") {
    doc["design_space"]["ring_cout"] = {{"min", 10}, {"max", 20}};
    CHECK_THAT(error_field(doc), Catch::Contains("design_space.ring_cout"));
  }
  SECTION("impossible bounds") {
    doc["design_space"]["taper_ratio"] = {{"min", 0.6}, {"max", 0.4}};
    CHECK_THAT(error_field(doc), Catch::Contains("design_space.taper_ratio.max"));
  }
  SECTION("bound outside what the model accepts") {
    doc["design_space"]["wall_thickness_normalised"]["max"] = 0.95;
    CHECK_THAT(error_field(doc), Catch::Contains("design_space.wall_thickness_normalised.max"));
  }
  SECTION("fractional integer bounds") {
    doc["design_space"]["ring_count"]["min"] = 20.5;
    CHECK_THAT(error_field(doc), Catch::Contains("design_space.ring_count"));
  }
  SECTION("unknown material") {
    doc["design_space"]["tube_material"]["choices"][1] = "dragon_skin_99";
    CHECK_THAT(error_field(doc), Catch::Contains("design_space.tube_material.choices[1]"));
  }
  SECTION("correction rounds without a check to correct by") {
    doc["check"]["solid_segment"] = 0;
    doc["check"]["verification"] = "none";
    doc["check"]["corrections"] = 1;
    CHECK_THAT(error_field(doc), Catch::Contains("check.corrections") && Catch::Contains("check.solid_segment"));
  }
  SECTION("improvement rounds without the verification") {
    doc["check"]["verification"] = "none";
    doc["check"]["corrections"] = 0;
    doc["check"]["improvement_rounds"] = 1;
    CHECK_THAT(error_field(doc), Catch::Contains("check.improvement_rounds") && Catch::Contains("cell_rod"));
  }
  SECTION("too many correction rounds") {
    doc["check"]["corrections"] = 7;
    CHECK_THAT(error_field(doc), Catch::Contains("check.corrections") && Catch::Contains("7"));
  }
  SECTION("unknown algorithm") {
    doc["optimiser"]["algorithm"] = "nlopt:magic";
    CHECK_THAT(error_field(doc), Catch::Contains("optimiser.algorithm"));
  }
  SECTION("durability beyond the only measured point") {
    doc["requirements"]["durability_cycles"] = 5e6;
    CHECK_THAT(error_field(doc), Catch::Contains("requirements.durability_cycles"));
  }
  SECTION("negative payload") {
    doc["requirements"]["min_payload_kg"] = -1;
    CHECK_THAT(error_field(doc), Catch::Contains("requirements.min_payload_kg"));
  }
  SECTION("3D check of a segment the arm does not have") {
    doc["check"]["solid_segment"] = 4;
    CHECK_THAT(error_field(doc), Catch::Contains("check.solid_segment"));
  }
  SECTION("a check model softarm does not have") {
    doc["check"]["solid_model"] = "hex27";
    CHECK_THAT(error_field(doc), Catch::Contains("check.solid_model") && Catch::Contains("hex27"));
  }
  SECTION("contradictory constraints: a minimum above a maximum on the same measure") {
    doc["constraints"] = {{{"measure", "rra_extension_mm"}, {"max", 50}}, {{"measure", "rra_extension_mm"}, {"min", 60}}};
    CHECK_THAT(error_field(doc), Catch::Contains("constraints[1].min") && Catch::Contains("constraints[0].max"));
  }
  SECTION("a constraint contradicting a requirement") {
    doc["constraints"] = {{{"measure", "mass_kg"}, {"min", 2.5}}};
    CHECK_THAT(error_field(doc), Catch::Contains("constraints[0].min") && Catch::Contains("requirements.max_mass_kg"));
    doc["constraints"] = {{{"measure", "payload_kg"}, {"max", 0.2}}};
    CHECK_THAT(error_field(doc), Catch::Contains("constraints[0].max") && Catch::Contains("requirements.min_payload_kg"));
  }
  SECTION("a baseline the search cannot start from: outside its variable's bounds") {
    doc["baseline_geometry"]["taper_ratio"] = 1.5;
    CHECK_THAT(error_field(doc), Catch::Contains("baseline_geometry.taper_ratio") && Catch::Contains("1.5") &&
                                     Catch::Contains("[0.35, 0.7]"));
  }
  SECTION("connectors that leave the segments no length are named, not the length they imply") {
    doc["baseline_geometry"]["connector_thickness_mm"] = 250;
    CHECK_THAT(error_field(doc), Catch::Contains("baseline_geometry.connector_thickness_mm") &&
                                     Catch::Contains("250 mm") && Catch::Contains("< 200 mm"));
  }
  SECTION("a baseline that cannot be built, where no variable replaces it") {
    doc["design_space"].erase("wall_thickness_normalised");
    doc["baseline_geometry"]["wall_thickness_normalised"] = 5;
    CHECK_THAT(error_field(doc), Catch::Contains("baseline_geometry.wall_thickness_normalised"));
  }
}

TEST_CASE("the search starts from the baseline geometry's values of its variables", "[design]") {
  auto doc = thesis_requirements();
  doc["baseline_geometry"]["taper_ratio"] = 0.6;
  const engine::DesignConfig config = engine::read_design_config(doc);
  const std::vector<double> x = engine::baseline_values(config);
  bool found = false;
  for (std::size_t i = 0; i < config.variables.size(); ++i)
    if (config.variables[i].variable.name == "taper_ratio") {
      CHECK(x[i] == 0.6);
      found = true;
    }
  CHECK(found);
}

TEST_CASE("the design check's model: the cell rod unless the config asks for the 8-point 3D segment", "[design]") {
  auto doc = thesis_requirements();
  CHECK(engine::read_design_config(doc).solid_check_model == objectives::SolidCheckModel::cell_rod);
  doc["check"]["solid_model"] = "hex20_2x2x2";
  CHECK(engine::read_design_config(doc).solid_check_model == objectives::SolidCheckModel::hex20_reduced);
}

TEST_CASE("softarm design exits 2 naming the field of a bad requirements file", "[design][cli]") {
  auto doc = thesis_requirements();
  doc["requirements"]["max_mas_kg"] = 2;
  const auto dir = std::filesystem::temp_directory_path() / "softarm_design_test";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "bad_requirements.json") << doc.dump();
  const std::string cmd = std::string(SOFTARM_BINARY) + " design " + (dir / "bad_requirements.json").string() + " > " +
                          (dir / "log.txt").string() + " 2>&1";
  const int status = std::system(cmd.c_str());
  std::ifstream in(dir / "log.txt");
  std::stringstream s;
  s << in.rdbuf();
  INFO(s.str());
  CHECK(WEXITSTATUS(status) == 2);
  CHECK(s.str().find("requirements.max_mas_kg") != std::string::npos);
}

TEST_CASE("a design that cannot be built is an infeasible evaluation with its reason", "[design]") {
  const engine::DesignConfig c = engine::read_design_config(thesis_requirements());
  const optimise::Problem p = engine::design_problem(c, 1.0, {}, nullptr);
  std::vector<double> x = engine::baseline_values(c);
  for (std::size_t i = 0; i < c.variables.size(); ++i)
    if (c.variables[i].variable.name == "actuator_spacing_mm") x[i] = 0.6;  // less than the rings' protrusion
  const optimise::Evaluation e = p.evaluate(x);
  CHECK_FALSE(e.ok);
  CHECK_THAT(e.failure_reason, Catch::Contains("actuator_spacing_mm"));
}

TEST_CASE("finite-difference gradients of the bending objective converge to the extrapolated derivative", "[design]") {
  const engine::DesignConfig c = engine::read_design_config(thesis_requirements());
  for (const std::string var : {"wall_thickness_normalised", "taper_ratio"}) {
    const double x0 = var == "taper_ratio" ? 0.5 : 0.466;
    const auto central = [&](double h) {
      return (segment_bending(c, var, x0 + h) - segment_bending(c, var, x0 - h)) / (2 * h);
    };
    const double d1 = central(0.02), d2 = central(0.01), d3 = central(0.005);
    const double reference = d3 + (d3 - d2) / 3;  // Richardson: central differences are O(h²)
    INFO(var << ": " << d1 << " " << d2 << " " << d3);
    CHECK(std::abs(d3 - d2) < std::abs(d2 - d1) / 2.5 + 1e-9 * std::abs(reference));
    CHECK(d3 == Approx(reference).epsilon(2e-3));
    // The optimiser's forward difference (step 1e-2 of a 0.3-wide range).
    const double forward = (segment_bending(c, var, x0 + 0.003) - segment_bending(c, var, x0)) / 0.003;
    CHECK(forward == Approx(reference).epsilon(0.02));
  }
}

namespace {
objectives::PayloadResult thesis_payload(const engine::DesignConfig& config, const std::string& variable, double value,
                                         fem::ArmRod* keep = nullptr) {
  std::vector<double> x = engine::baseline_values(config);
  for (std::size_t i = 0; i < config.variables.size(); ++i)
    if (config.variables[i].variable.name == variable) x[i] = value;
  const objectives::ArmCandidate c = engine::make_candidate(config, x);
  const fem::ArmRod arm = objectives::arm_rod(c, config.model);
  objectives::PayloadSettings s;
  s.working_pressure_kPa = config.model.working_pressure_kPa;
  s.sheath_allowable_stretch = (1 + c.sheath.elongation_at_break) / config.model.safety_factor;
  if (keep) *keep = arm;
  return objectives::payload_capacity(arm, s);
}
}  // namespace

TEST_CASE("the payload capacity is a lift to horizontal, and the thesis arm's is near the prototype's", "[design]") {
  const engine::DesignConfig c = engine::read_design_config(thesis_requirements());
  fem::ArmRod arm = objectives::arm_rod(engine::make_candidate(c, engine::baseline_values(c)), c.model);
  const objectives::PayloadResult r = thesis_payload(c, "taper_ratio", 0.5, &arm);
  INFO(r.limited_by);
  // Thesis Table 13: the prototype lifted 0.3 kg (it missed the 0.5 kg target).
  CHECK(r.capacity_kg == Approx(0.3).epsilon(0.25));
  // At the capacity and its lift pressure, the tip is at 90 deg and the payload held out.
  fem::RodLoad load;
  load.chamber_pressure_kPa.assign(6, {0.0, 0.0, 0.0});
  for (int piece : {1, 3, 5}) load.chamber_pressure_kPa[piece] = {0.0, r.lift_pressure_kPa, r.lift_pressure_kPa};
  load.gravity_m_s2 = {0.0, -9.80665};
  load.tip_mass_kg = r.capacity_kg;
  const fem::RodState st = arm.follow(load, 24);
  REQUIRE(st.converged);
  CHECK(arm.tip_rotation(st, load) * softarm::fem::kDeg == Approx(90).margin(0.05));
  CHECK(std::abs(st.x.back()) > 0.25 * arm.length_mm());
  // 5 % more mass at the full working pressure no longer reaches 90 deg.
  load.tip_mass_kg = 1.05 * r.capacity_kg;
  for (int piece : {1, 3, 5}) load.chamber_pressure_kPa[piece] = {0.0, 344.7, 344.7};
  const fem::RodState heavier = arm.follow(load, 24);
  REQUIRE(heavier.converged);
  CHECK(arm.tip_rotation(heavier, load) * softarm::fem::kDeg < 90);
}

TEST_CASE("finite differences of the payload capacity converge", "[design]") {
  const engine::DesignConfig c = engine::read_design_config(thesis_requirements());
  const double x0 = 0.42;
  const auto central = [&](double h) {
    return (thesis_payload(c, "wall_thickness_normalised", x0 + h).capacity_kg -
            thesis_payload(c, "wall_thickness_normalised", x0 - h).capacity_kg) / (2 * h);
  };
  const double d1 = central(0.02), d2 = central(0.01);
  INFO(d1 << " " << d2);
  CHECK(d2 < 0);  // thicker walls: stiffer, smaller chambers, less payload
  CHECK(d2 == Approx(d1).epsilon(0.03));
}

TEST_CASE("the payload capacity is continuous in the design near the working pressure", "[design][long]") {
  // A design of the main job's improvement round (DS20 tube, DS10 sheath), whose capacity is set
  // by the working pressure. Before the shooting root kept a bracket (fem/reduced/shooting_root.hpp),
  // walls 1e-4 apart gave 0.280 to 0.334 kg here: the capacity fell wherever the rod's solve failed.
  const engine::DesignConfig c = engine::read_design_config(thesis_requirements());
  std::vector<double> x = engine::baseline_values(c);
  const std::map<std::string, double> values = {{"wall_thickness_normalised", 0.419062},
                                                {"end_cap_thickness_normalised", 0.229171},
                                                {"ring_count", 30},
                                                {"ring_thickness_normalised", 0.371729},
                                                {"actuator_spacing_mm", 2.88998},
                                                {"taper_ratio", 0.669449}};
  std::size_t wall = 0;
  for (std::size_t i = 0; i < c.variables.size(); ++i) {
    const optimise::Variable& v = c.variables[i].variable;
    if (values.count(v.name)) x[i] = values.at(v.name);
    if (v.name == "wall_thickness_normalised") wall = i;
    if (v.name == "tube_material" || v.name == "sheath_material") {
      const std::string wanted = v.name == "tube_material" ? "dragon_skin_20" : "dragon_skin_10";
      x[i] = static_cast<double>(std::find(v.choices.begin(), v.choices.end(), wanted) - v.choices.begin());
    }
  }
  std::vector<double> capacity;
  for (int k = 0; k < 5; ++k) {
    std::vector<double> y = x;
    y[wall] += 1e-4 * (2 * k - 4);
    const objectives::ArmCandidate candidate = engine::make_candidate(c, y);
    objectives::PayloadSettings s;
    s.working_pressure_kPa = c.model.working_pressure_kPa;
    s.sheath_allowable_stretch = (1 + candidate.sheath.elongation_at_break) / c.model.safety_factor;
    const objectives::PayloadResult r = objectives::payload_capacity(objectives::arm_rod(candidate, c.model), s);
    INFO("wall " << y[wall] << ": " << r.capacity_kg << " kg, " << r.limited_by);
    CHECK(r.limited_by == "the lift angle needs more than the working pressure");
    capacity.push_back(r.capacity_kg);
  }
  // Thicker walls lift less: steps of 2e-4 in the wall lower the capacity by ≈ 0.1 %, to within the
  // bisection's tolerance on the mass (1e-3 of it), never by a jump.
  for (std::size_t k = 1; k < capacity.size(); ++k) {
    INFO("k " << k << ": " << capacity[k - 1] << " -> " << capacity[k]);
    CHECK(capacity[k] <= capacity[k - 1] + 1e-3 * capacity[0]);
    CHECK(capacity[k - 1] - capacity[k] < 3e-3 * capacity[0]);
  }
}

TEST_CASE("a candidate is the arm its geometry keys describe, in either unit of each variable", "[design]") {
  // make_candidate sets the variables on the typed baseline (fem::SplParameters) and builds once;
  // the same arm must come from the scene's JSON reader given the same keys (one twin replaced).
  for (const bool physical : {false, true}) {
    auto doc = thesis_requirements();
    if (physical) {
      doc["design_space"].erase("wall_thickness_normalised");
      doc["design_space"]["wall_thickness_mm"] = {{"min", 2.5}, {"max", 6}};
      doc["design_space"].erase("ring_thickness_normalised");
      doc["design_space"]["ring_diameter_mm"] = {{"min", 1}, {"max", 2.5}};
    }
    const engine::DesignConfig c = engine::read_design_config(doc);
    std::mt19937 random(7);
    for (int trial = 0; trial < 5; ++trial) {
      std::vector<double> x = engine::baseline_values(c);
      nlohmann::json geometry = doc["baseline_geometry"];
      for (std::size_t i = 0; i < c.variables.size(); ++i) {
        const optimise::Variable& v = c.variables[i].variable;
        if (v.kind == optimise::VariableKind::categorical) continue;
        x[i] = std::uniform_real_distribution<double>(v.lower, v.upper)(random);
        if (v.kind == optimise::VariableKind::integer) x[i] = std::round(x[i]);
        for (const auto& [a, b] : {std::pair{"wall_thickness_normalised", "wall_thickness_mm"},
                                   std::pair{"ring_thickness_normalised", "ring_diameter_mm"},
                                   std::pair{"ring_count", "ring_count_normalised"}})
          if (v.name == a) geometry.erase(b);
          else if (v.name == b) geometry.erase(a);
        if (v.kind == optimise::VariableKind::integer) geometry[v.name] = static_cast<int>(x[i]);
        else geometry[v.name] = x[i];
      }
      geometry["length_mm"] = (600.0 - 3 * 40) / 3;
      fem::JsonReader reader(geometry, "baseline_geometry");
      nlohmann::json expected;
      try {
        expected = fem::to_json(fem::read_spl_design(reader));
      } catch (const fem::InputError& e) {  // rings that touch: both ways refuse it, naming the same key
        INFO(e.what());
        CHECK_THROWS_WITH(engine::make_candidate(c, x), Catch::Equals(e.what()));
        continue;
      }
      CHECK(fem::to_json(engine::make_candidate(c, x).design) == expected);
    }
  }
}

TEST_CASE("a design variable may be given in physical units instead of normalised ones", "[design]") {
  auto doc = thesis_requirements();
  doc["design_space"].erase("wall_thickness_normalised");
  doc["design_space"]["wall_thickness_mm"] = {{"min", 2.5}, {"max", 6}};
  const engine::DesignConfig c = engine::read_design_config(doc);
  std::vector<double> x = engine::baseline_values(c);
  for (std::size_t i = 0; i < c.variables.size(); ++i)
    if (c.variables[i].variable.name == "wall_thickness_mm") x[i] = 5.0;
  const objectives::ArmCandidate arm = engine::make_candidate(c, x);
  for (const auto& segment : arm.design.segments) CHECK(segment.actuator.wall_thickness_mm == Approx(5.0));
  doc["design_space"]["wall_thickness_normalised"] = {{"min", 0.3}, {"max", 0.6}};
  CHECK_THAT(error_field(doc), Catch::Contains("design_space.wall_thickness_mm"));
}

TEST_CASE("any measure may be the objective or an extra constraint, and unknown measures are named", "[design]") {
  auto doc = thesis_requirements();
  doc["objective"] = {{"maximise", "payload_kg"}};
  doc["constraints"] = nlohmann::json::array({{{"measure", "safe_working_pressure_kPa"}, {"min", 400}},
                                              {{"measure", "pressure_for_target_bending_kPa"}, {"max", 300}}});
  const engine::DesignConfig c = engine::read_design_config(doc);
  CHECK(c.maximise);
  CHECK(c.objective_measure == "payload_kg");
  REQUIRE(c.extra_constraints.size() == 2);
  // On the thesis design's measures: objective −payload, the extra constraints appended.
  objectives::ArmMeasures m;
  m.mass_kg = 1.5;
  m.payload_kg = 0.3;
  m.min_bending_deg = 80;
  m.burst_utilisation = 0.9;
  m.durability_log_strain = 1.0;
  for (auto& s : m.segments) {
    s.bending_deg_at_working = 80;
    s.burst_utilisation = 0.9;
  }
  m.segments[2].pressure_for_target_kPa = 290;
  m.segments[2].bending_deg_at_working = 100;
  CHECK(engine::objective_of(c, m, 1.0) == Approx(-0.3));
  const auto g = engine::constraints_of(c, m, 1.0);
  REQUIRE(g.values.size() == 7);
  // Safe pressure extrapolated as p_w / utilisation = 344.7 / 0.9 = 383 kPa < 400: violated by 17/400.
  CHECK(g.values[5] == Approx((400 - 344.7 / 0.9) / 400).epsilon(1e-9));
  // 90° pressure: the slowest segment extrapolated, 344.7 · 90/80 = 387.8 kPa > 300.
  CHECK(g.values[6] == Approx((344.7 * 90 / 80 - 300) / 300).epsilon(1e-9));

  doc["objective"] = {{"minimise", "weight_kg"}};
  CHECK_THAT(error_field(doc), Catch::Contains("objective.minimise"));
  doc["objective"] = "minimise_mass";
  doc["constraints"] = nlohmann::json::array({{{"measure", "payload_kg"}, {"min", 0.1}, {"max", 1}}});
  CHECK_THAT(error_field(doc), Catch::Contains("constraints[0]"));
}

TEST_CASE("the RRA extension measure is the thesis RRA's FEM extension on the thesis design", "[design]") {
  const engine::DesignConfig c = engine::read_design_config(thesis_requirements());
  const objectives::ArmMeasures m = objectives::evaluate_arm(engine::make_candidate(c, engine::baseline_values(c)), c.model);
  // The distal segment's RRA is the thesis RRA (Table 7); its axisymmetric FEM (level 1) extends
  // 76.67 mm at 206.8 kPa (docs/validation.md, The thesis RRA). The calibrated rod interpolates the
  // factor between the FEM's output pressures, so it matches to the interpolation's accuracy.
  fem::RraSceneSpec rra;
  rra.tube_material = fem::builtin_material("dragon_skin_30", "test");
  rra.ring_material = fem::builtin_material("digital_abs", "test");
  rra.path.max_pressure_kPa = 206.8;
  rra.path.output_pressures_kPa = {206.8};
  const double fem_mm = fem::run_rra_scene(rra).curve.back().extension_mm;
  CHECK(engine::design_measure("rra_extension_mm", "test").value(m, c.model, 1.0) == Approx(fem_mm).epsilon(0.02));
}

TEST_CASE("an optional strain-life curve sets the allowed strain for the required life", "[design]") {
  auto doc = thesis_requirements();
  doc["requirements"]["durability_cycles"] = 2.2e6;  // twice the measured 1.1 M cycles
  CHECK_THAT(error_field(doc), Catch::Contains("requirements.durability_cycles"));
  doc["requirements"]["strain_life_exponent"] = 4;
  const engine::DesignConfig c = engine::read_design_config(doc);
  // N = N_ref (ε_ref/ε)^b: twice the life at b = 4 allows ε/ε_ref = 0.5^(1/4).
  CHECK(c.requirements.allowed_strain_ratio() == Approx(std::pow(0.5, 0.25)));
  objectives::ArmMeasures m;
  m.mass_kg = 1;
  m.min_bending_deg = 90;
  m.durability_log_strain = 0.8;
  CHECK(engine::constraints_of(c, m, 1.0).values[4] == Approx(0.8 / std::pow(0.5, 0.25) - 1));
}

TEST_CASE("a design run measures each design once per search model, and again for another model", "[design]") {
  engine::DesignConfig c = engine::read_design_config(thesis_requirements());
  c.model.working_pressure_kPa = 50;  // a cheap evaluation: the RRA FEMs and the rod to 50 kPa
  c.model.pressure_steps = 4;
  const std::vector<double> x = engine::baseline_values(c);
  engine::MeasuresMemo memo;
  const objectives::ArmMeasures first = memo.measures(x, engine::make_candidate(c, x), c.model);
  CHECK(memo.computed() == 1);
  // The same design under settings equal field by field (the check model where the config sets it as
  // the search model): served, the same bits.
  const objectives::EvaluationSettings same = c.model;
  const objectives::ArmMeasures again = memo.measures(x, engine::make_candidate(c, x), same);
  CHECK(memo.computed() == 1);
  CHECK(memo.served() == 1);
  CHECK(again.mass_kg == first.mass_kg);
  CHECK(again.payload_kg == first.payload_kg);
  CHECK(again.min_bending_deg == first.min_bending_deg);
  CHECK(again.burst_utilisation == first.burst_utilisation);
  // Another model, or another design: measured anew.
  objectives::EvaluationSettings other = c.model;
  other.pressure_steps = 5;
  const objectives::ArmMeasures finer = memo.measures(x, engine::make_candidate(c, x), other);
  CHECK(memo.computed() == 2);
  CHECK(finer.min_bending_deg != first.min_bending_deg);
  std::vector<double> y = x;
  y[0] = std::nextafter(y[0], 1e300);
  (void)memo.measures(y, engine::make_candidate(c, y), c.model);
  CHECK(memo.computed() == 3);
  CHECK(memo.served() == 1);
}

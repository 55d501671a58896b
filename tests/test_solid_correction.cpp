// Check and correct (engine/design/solid_correction.hpp): a 3D check of one
// segment becomes a multiplicative correction of the search model's bending
// and burst utilisation, and the design problem searches with it.
//
// The numbers are hand-made: a segment whose search-model path is the polyline
// (0, 0), (150, 50), (300, 120), (344.7, 140) kPa/deg, burst utilisation 0.9 at
// the working pressure 344.7 kPa. A 3D path that balloons at 300 kPa having
// bent 80 deg gives β_θ = 80/120 and β_u = (344.7/300)/0.9.
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "engine/design/design_problem.hpp"
#include "engine/design/solid_correction.hpp"
#include "fem/core/json_reader.hpp"

using namespace softarm;
namespace fs = std::filesystem;

namespace {
constexpr double working_kPa = 344.7;

nlohmann::json thesis_requirements() {
  return fem::load_json_file(std::string(SOFTARM_SOURCE_DIR) + "/configs/thesis_requirements.json");
}

objectives::ArmMeasures searched() {
  objectives::ArmMeasures m;
  for (auto& s : m.segments) {
    s.pressure_kPa = {0, 150, 300, working_kPa};
    s.bending_deg = {0, 50, 120, 140};
    s.bending_deg_at_working = 140;
    s.burst_utilisation = 0.9;
  }
  m.min_bending_deg = 140, m.burst_utilisation = 0.9;
  m.mass_kg = 1.2, m.payload_kg = 0.6;
  return m;
}

objectives::SolidSegmentCheck check_of_segment_3(fem::PathOutcome path, double reached_kPa, double bending_deg) {
  objectives::SolidSegmentCheck c;
  c.segment = 3;
  c.path = path;
  c.reached_pressure_kPa = reached_kPa;
  c.bending_deg = bending_deg;
  return c;
}
}  // namespace

TEST_CASE("a 3D limit point below the working pressure corrects bending and burst of the search model", "[design][correction]") {
  const auto check = check_of_segment_3(fem::PathOutcome::limit_point, 300, 80);
  const engine::SolidCorrection c = engine::updated_correction({}, check, searched(), working_kPa);
  CHECK(c.checks == 1);
  CHECK(c.bending_factor == Approx(80.0 / 120.0));
  CHECK(c.burst_factor == Approx(working_kPa / 300.0 / 0.9));
  const objectives::ArmMeasures m = engine::corrected(searched(), c);
  CHECK(m.min_bending_deg == Approx(140 * 80.0 / 120.0));
  CHECK(m.segments[1].bending_deg_at_working == Approx(140 * 80.0 / 120.0));
  CHECK(m.burst_utilisation == Approx(working_kPa / 300.0));  // the 3D utilisation at the checked design
  CHECK(m.segments[2].burst_utilisation == Approx(working_kPa / 300.0));
  CHECK(m.mass_kg == 1.2);     // exact in both models
  CHECK(m.payload_kg == 0.6);  // not checked in 3D
  CHECK(m.segments[2].bending_deg == searched().segments[2].bending_deg);  // the path itself stays the search model's
}

TEST_CASE("a 3D check that holds the working pressure keeps the burst correction and renews the bending one", "[design][correction]") {
  const auto balloons = check_of_segment_3(fem::PathOutcome::limit_point, 300, 80);
  const engine::SolidCorrection first = engine::updated_correction({}, balloons, searched(), working_kPa);
  // The next optimum holds the working pressure and bends 112 deg where the search model says 140.
  const auto holds = check_of_segment_3(fem::PathOutcome::completed, working_kPa, 112);
  const engine::SolidCorrection second = engine::updated_correction(first, holds, searched(), working_kPa);
  CHECK(second.checks == 2);
  CHECK(second.bending_factor == Approx(0.8));
  CHECK(second.burst_factor == Approx(first.burst_factor));  // a held pressure does not say how far the limit is
  CHECK(second.describe() == "bending x0.800, burst utilisation x1.277 (from 2 3D checks)");
}

TEST_CASE("a stalled 3D path measures nothing and leaves the correction as it was", "[design][correction]") {
  const auto stalled = check_of_segment_3(fem::PathOutcome::stalled, 250, 70);
  const engine::SolidCorrection c = engine::updated_correction({}, stalled, searched(), working_kPa);
  CHECK(c.checks == 0);
  CHECK(c.bending_factor == 1);
  CHECK(c.burst_factor == 1);
  CHECK(c.describe() == "none");
}

TEST_CASE("corrected constraints are the constraints of the corrected measures", "[design][correction]") {
  const engine::DesignConfig config = engine::read_design_config(thesis_requirements());
  engine::SolidCorrection c;
  c.bending_factor = 0.7, c.burst_factor = 1.2, c.checks = 1;
  const auto direct = engine::constraints_of(config, engine::corrected(searched(), c), 1.0);
  const auto transformed = engine::corrected_constraints(engine::constraints_of(config, searched(), 1.0), c);
  REQUIRE(direct.names == transformed.names);
  for (std::size_t i = 0; i < direct.values.size(); ++i) CHECK(transformed.values[i] == Approx(direct.values[i]));
  CHECK(direct.values[2] == Approx(1 - 0.7 * 140 / 90.0));
  CHECK(direct.values[3] == Approx(1.2 * 0.9 - 1));
}

TEST_CASE("a 3D check reads back from JSON exactly", "[design][correction]") {
  auto c = check_of_segment_3(fem::PathOutcome::limit_point, 305.8123456789, 84.4);
  c.element = "H2s/P1", c.dofs = 51384, c.outcome = "limit point", c.rod_bending_deg = 122.4, c.seconds = 950.25;
  c.rod_pressure_for_target_kPa = 1.0 / 3.0;
  const auto back = objectives::solid_check_from_json(nlohmann::json::parse(objectives::to_json(c).dump()));
  CHECK(back.path == c.path);
  CHECK(back.reached_pressure_kPa == c.reached_pressure_kPa);
  CHECK(back.rod_pressure_for_target_kPa == c.rod_pressure_for_target_kPa);
  CHECK_FALSE(back.pressure_for_target_kPa.has_value());
  CHECK(objectives::to_json(back) == objectives::to_json(c));
}

TEST_CASE("the design problem keeps its measurements in the checkpoint and a corrected search reads them back", "[design][correction]") {
  const fs::path dir = fs::temp_directory_path() / ("softarm_checkpoint_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const nlohmann::json document = thesis_requirements();
  const engine::DesignConfig config = engine::read_design_config(document);
  const std::vector<double> x = engine::baseline_values(config);
  optimise::Evaluation plain;
  {
    engine::DesignCheckpoint checkpoint(dir, document, false);
    plain = engine::design_problem(config, 1.0, {}, &checkpoint).evaluate(x);
    REQUIRE(plain.ok);
  }
  const auto lines = [&dir] {
    std::ifstream in(dir / "checkpoint.jsonl");
    return std::count(std::istreambuf_iterator<char>(in), {}, '\n');
  };
  REQUIRE(lines() == 2);  // the header and the evaluation
  engine::DesignCheckpoint resumed(dir, document, false);
  CHECK(resumed.resumed_evaluations() == 1);
  engine::SolidCorrection half;
  half.bending_factor = 0.5, half.checks = 1;
  const optimise::Evaluation corrected = engine::design_problem(config, 1.0, half, &resumed).evaluate(x);
  REQUIRE(corrected.ok);
  CHECK(lines() == 2);  // read back, not measured again
  CHECK(corrected.objective == plain.objective);
  // g_bending = 1 − β_θ·θ_min/θ_target + margin (design_problem.hpp)
  const double m = config.search_margin;
  const double theta_over_target = 1 + m - plain.constraints[2];
  CHECK(corrected.constraints[2] == Approx(1 + m - 0.5 * theta_over_target));
  CHECK(corrected.constraints[3] == plain.constraints[3]);  // burst uncorrected (β_u = 1)
  // The optimiser's settings are not in the fingerprint; the model's are.
  nlohmann::json other_budget = document, other_model = document;
  other_budget["optimiser"]["max_evaluations"] = 7;
  CHECK(engine::DesignCheckpoint(dir, other_budget, false).resumed_evaluations() == 1);
  other_model["model"]["pressure_steps"] = 13;
  CHECK_THROWS_WITH(engine::DesignCheckpoint(dir, other_model, false), Catch::Contains("--fresh"));
  CHECK(engine::DesignCheckpoint(dir, other_model, true).resumed_evaluations() == 0);
  fs::remove_all(dir);
}

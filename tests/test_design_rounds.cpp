// `softarm design`'s rounds past feasibility (check.improvement_rounds, engine/design/design_command.cpp):
// when the verified design meets every requirement, the search model is corrected by it too and the
// search runs again about it; the answer is the best verified design, never an unverified one.
// Model: the thesis requirements at 100 kPa (bending 15 deg, no payload: what the arm does there) with the
// wall thickness the only variable, 2 evaluations a search, the cells' layers as at level 1 and 4
// outputs along their ramp; one improvement round with no tolerance, so that it verifies whatever
// gain its search predicts.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>

#include "fem/core/json_reader.hpp"
#include "support/text_file.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

TEST_CASE("an improvement round searches about the verified design and the answer is the best verified one",
          "[design][cli][rounds][long]") {
  const fs::path dir = fs::temp_directory_path() / ("softarm_design_rounds_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  auto doc = softarm::fem::load_json_file(std::string(SOFTARM_SOURCE_DIR) + "/configs/thesis_requirements.json");
  doc["requirements"]["max_pressure_kPa"] = 100.0;
  doc["requirements"]["bending_per_segment_deg"] = 15.0;
  doc["requirements"]["min_payload_kg"] = 0.0;  // at 100 kPa the arm does not lift its own tip to horizontal
  doc["check"]["corrections"] = 0;
  doc["check"]["improvement_rounds"] = 1;
  doc["check"]["improvement_tolerance_percent"] = 0.0;
  doc["check"]["solid_segment"] = 0;
  doc["check"]["cell_layers_level"] = 1;
  doc["check"]["cell_levels"] = 4;
  doc["check"]["mesh_sensitivity"] = false;
  doc["check"]["pressure_steps"] = doc["model"]["pressure_steps"];
  doc["check"]["rod_nodes_per_segment"] = doc["model"]["rod_nodes_per_segment"];
  doc["design_space"] = {{"wall_thickness_normalised", {{"min", 0.4}, {"max", 0.5}}}};
  std::ofstream(dir / "requirements.json") << doc.dump();
  const std::string args = "design " + (dir / "requirements.json").string() + " --max-evaluations 2 --threads 1 -o " +
                           (dir / "out").string();
  REQUIRE(softarm::test::run_softarm_logged("", args, dir / "run.log") == 0);
  const std::string log = softarm::test::read_text(dir / "run.log");
  INFO(log);
  CHECK_THAT(log, Catch::Contains("the start design on the accurate model"));

  const json s = json::parse(softarm::test::read_text(dir / "out" / "summary.json"));
  const json& rounds = s["check_and_correct"];
  REQUIRE(rounds.size() >= 1);
  CHECK(rounds[0]["purpose"] == "first search");
  REQUIRE(rounds[0]["verification"]["all_met"] == true);  // the premise: the first optimum meets every requirement
  CHECK_THAT(log, Catch::Contains("improvement round 1 of at most 1: search again about the best verified design"));
  if (rounds.size() == 1) {
    // The round's search predicted no gain: it stopped without a verification, by the stopping test.
    CHECK_THAT(s["rounds_stop_reason"].get<std::string>(), Catch::Contains("improvement_tolerance_percent"));
  } else {
    REQUIRE(rounds.size() == 2);
    CHECK(rounds[1]["purpose"] == "improvement");
    CHECK(rounds[1]["verification"]["ok"] == true);
    CHECK_THAT(s["rounds_stop_reason"].get<std::string>(), Catch::Contains("every improvement round has run"));
  }
  // The answer is the verified design with the least mass among those that meet every requirement.
  const json* best = nullptr;
  for (const json& r : rounds)
    if (r["verification"]["all_met"] == true &&
        (!best || r["verification"]["measures"]["mass_kg"] < (*best)["verification"]["measures"]["mass_kg"]))
      best = &r;
  REQUIRE(best);
  CHECK(s["optimum"] == (*best)["optimum"]);
  CHECK(s["verification"]["measures"]["mass_kg"] == (*best)["verification"]["measures"]["mass_kg"]);
  CHECK(s["verification"]["all_met"] == true);
  // What the verification's cells cost is kept and said: a path for each cell and end cell, at least
  // a Newton iteration and the factorisation its first step needs each.
  const json& solver = s["verification"]["cell_solver"];
  INFO("cells' solves: " << solver.dump());
  const int paths = s["verification"]["cells"].get<int>() + s["verification"]["end_cells"].get<int>();
  CHECK(solver["cell_paths"].get<int>() == paths);
  CHECK(solver["newton_iterations"].get<int>() >= paths);
  CHECK(solver["factorizations"].get<int>() >= paths);
  CHECK_THAT(log, Catch::Contains("s (" + std::to_string(solver["newton_iterations"].get<int>()) + " Newton iterations, " +
                                  std::to_string(solver["factorizations"].get<int>()) + " factorisations"));
  fs::remove_all(dir);
}

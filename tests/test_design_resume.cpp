// `softarm design` resumes a stopped run (engine/design/design_checkpoint.hpp):
// a run with a budget of 3 evaluations stands for one stopped after 3, and a
// rerun with a budget of 5 must read those 3 back from checkpoint.jsonl
// (saying so), compute only 2 more, and log the same first 3 evaluations.
// Model: the thesis requirements with the 3D check and the verification off (seconds per run).
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "fem/core/json_reader.hpp"
#include "support/csv_fields.hpp"
#include "support/text_file.hpp"

namespace fs = std::filesystem;

namespace {
using softarm::test::csv_fields;
using softarm::test::read_text;

std::vector<std::string> lines_of(const fs::path& file) {
  std::vector<std::string> lines;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

int run_design(const fs::path& config, const fs::path& out, int budget, const fs::path& log) {
  return softarm::test::run_softarm_logged(
      "", "design " + config.string() + " -o " + out.string() + " --max-evaluations " + std::to_string(budget), log);
}
}  // namespace

TEST_CASE("softarm design resumes from its checkpoint and computes only what is new", "[design][cli][resume][long]") {
  const fs::path dir = fs::temp_directory_path() / ("softarm_design_resume_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  auto doc = softarm::fem::load_json_file(std::string(SOFTARM_SOURCE_DIR) + "/configs/thesis_requirements.json");
  doc["check"]["solid_segment"] = 0;
  doc["check"]["corrections"] = 0;
  doc["check"]["improvement_rounds"] = 0;
  doc["check"]["verification"] = "none";
  // What is compared does not need the optimum's peaks one RRA level finer, nor a finer re-check.
  doc["check"]["mesh_sensitivity"] = false;
  doc["check"]["pressure_steps"] = doc["model"]["pressure_steps"];
  doc["check"]["rod_nodes_per_segment"] = doc["model"]["rod_nodes_per_segment"];
  // A lower working pressure shortens every RRA path (16 s a run instead of 27 s, idle); what is
  // checked, the checkpoint's bookkeeping, is the same at any pressure.
  doc["requirements"]["max_pressure_kPa"] = 200.0;
  std::ofstream(dir / "requirements.json") << doc.dump();
  const fs::path out = dir / "out";

  REQUIRE(run_design(dir / "requirements.json", out, 3, dir / "first.log") == 0);
  const std::vector<std::string> first_history = lines_of(out / "history.csv");
  REQUIRE(first_history.size() == 4);  // header and 3 evaluations
  // Every record parses, as a spreadsheet reads it, into the header's columns (the phase holds a
  // comma: "tube_material=…, sheath_material=…: start 1"), and the materials are named.
  const std::vector<std::string> header = csv_fields(first_history[0]);
  const auto tube = std::find(header.begin(), header.end(), "tube_material") - header.begin();
  REQUIRE(tube < static_cast<std::ptrdiff_t>(header.size()));
  for (std::size_t i = 1; i < first_history.size(); ++i) {
    INFO(first_history[i]);
    const std::vector<std::string> fields = csv_fields(first_history[i]);
    CHECK(fields.size() == header.size());
    if (fields.size() == header.size()) CHECK_THAT(fields[tube], Catch::StartsWith("dragon_skin_"));
  }
  CHECK(lines_of(out / "checkpoint.jsonl").size() == 4);  // header and 3 evaluations

  REQUIRE(run_design(dir / "requirements.json", out, 5, dir / "second.log") == 0);
  const std::string second = read_text(dir / "second.log");
  INFO(second);
  CHECK_THAT(second, Catch::Contains("resuming: 3 evaluations, 0 3D check(s) and 0 verification(s)"));
  const std::vector<std::string> history = lines_of(out / "history.csv");
  REQUIRE(history.size() == 6);
  CHECK(std::equal(first_history.begin(), first_history.end(), history.begin()));
  CHECK(lines_of(out / "checkpoint.jsonl").size() == 6);  // only the 2 new evaluations were added

  // A changed model is refused by name rather than mixed in.
  doc["model"]["pressure_steps"] = 13;
  std::ofstream(dir / "changed.json") << doc.dump();
  CHECK(run_design(dir / "changed.json", out, 3, dir / "changed.log") != 0);
  CHECK_THAT(read_text(dir / "changed.log"), Catch::Contains("--fresh"));
  fs::remove_all(dir);
}

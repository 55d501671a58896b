// Bad input through the real command line: each case must exit with code 2
// and a message that names the offending JSON field — never crash, hang or
// print NaN.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <iterator>
#include <sstream>
#include <string>
#include <unistd.h>

#include <nlohmann/json.hpp>
#include "engine/workspace/arm_input.hpp"
#include "fem/mesh/tca_design.hpp"

namespace {

struct RunResult {
  int exit_code;
  std::string output;
};

RunResult run_softarm(const std::string& args) {
  const auto dir = std::filesystem::temp_directory_path() / "softarm_cli_test";
  std::filesystem::create_directories(dir);
  // One log per call and process: ctest -j runs several of these tests at once.
  static int calls = 0;
  const auto log = dir / ("log_" + std::to_string(::getpid()) + "_" + std::to_string(++calls) + ".txt");
  const std::string cmd = std::string(SOFTARM_BINARY) + " " + args + " > " + log.string() + " 2>&1";
  const int status = std::system(cmd.c_str());
  std::stringstream s;
  s << std::ifstream(log).rdbuf();
  std::filesystem::remove(log);
  return {WEXITSTATUS(status), s.str()};
}

std::string write_config(const std::string& name, const std::string& text) {
  const auto dir = std::filesystem::temp_directory_path() / "softarm_cli_test";
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::ofstream(path) << text;
  return path.string();
}

// The thesis RRA with one geometry entry replaced.
std::string rra_config(const std::string& geometry_override, const std::string& extra = "") {
  std::string geometry = R"("length_mm": 160, "bottom_radius_mm": 9, "top_radius_mm": 12,
    "end_cap_thickness_normalised": 0.25, "ring_count_normalised": 0.375)";
  if (geometry_override.find("wall_thickness") == std::string::npos) geometry += R"(, "wall_thickness_normalised": 0.466)";
  if (geometry_override.find("ring_thickness") == std::string::npos && geometry_override.find("ring_diameter") == std::string::npos)
    geometry += R"(, "ring_thickness_normalised": 0.4)";
  if (!geometry_override.empty()) geometry += ", " + geometry_override;
  return R"({"scene": "rra", "geometry": {)" + geometry + R"(}, "load": {"max_pressure_kPa": 206.8})" + extra + "}";
}

/// `simulate` of `config_text` exits 2 with every one of `words` (the field first) in its message and no nan.
void expect_input_error(const std::string& config_text, std::initializer_list<std::string> words) {
  const auto file = write_config("bad_" + std::to_string(::getpid()) + ".json", config_text);  // tests run side by side
  const auto r = run_softarm("simulate " + file + " -o /tmp/softarm_cli_test/out");
  INFO("config: " << config_text << "\noutput: " << r.output);
  CHECK(r.exit_code == 2);
  for (const auto& word : words) CHECK_THAT(r.output, Catch::Contains(word));
  CHECK(r.output.find("nan") == std::string::npos);
}

void expect_input_error(const std::string& config_text, const std::string& field) {
  expect_input_error(config_text, {field});
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

}  // namespace

TEST_CASE("softarm rejects bad scene input with the field named", "[cli]") {
  SECTION("malformed JSON") {
    const auto file = write_config("malformed.json", "{\"scene\": \"rra\",\n \"geometry\": {\"length_mm\": 160,,}}");
    const auto r = run_softarm("simulate " + file);
    INFO(r.output);
    CHECK(r.exit_code == 2);
    CHECK(r.output.find("line 2") != std::string::npos);
  }
  SECTION("unknown key") { expect_input_error(rra_config(R"("lenght_mm": 150)"), "geometry.lenght_mm"); }
  SECTION("negative dimension") { expect_input_error(rra_config(R"("wall_thickness_mm": -1)"), "geometry.wall_thickness_mm"); }
  SECTION("wall thicker than the radius") {
    expect_input_error(rra_config(R"("wall_thickness_normalised": 1.2)"), "wall_thickness");
  }
  SECTION("rings that do not fit") {
    expect_input_error(rra_config(R"("ring_thickness_normalised": 1.5)"), "ring_thickness_normalised");
  }
  SECTION("a ring count past the meshing bound") {
    expect_input_error(rra_config(R"("ring_count": 1000000)"), "geometry.ring_count");
  }
  SECTION("unknown material") {
    expect_input_error(rra_config("", R"(, "materials": {"tube": "dragon_skin_40"})"), "materials.tube");
  }
  SECTION("missing required field") {
    expect_input_error(R"({"scene": "rra", "geometry": {}, "load": {}})", "geometry.");
  }
  SECTION("unwritable output directory") {
    const auto file = write_config("good.json", rra_config(""));
    const auto r = run_softarm("simulate " + file + " -o /proc/softarm_cannot_write_here");
    INFO(r.output);
    CHECK(r.exit_code == 2);
    CHECK(r.output.find("output.directory") != std::string::npos);
  }
    SECTION("missing file") {
    const auto r = run_softarm("simulate /nonexistent/scene.json");
    CHECK(r.exit_code == 2);
    CHECK(r.output.find("/nonexistent/scene.json") != std::string::npos);
  }
  SECTION("a key given twice: refused, naming it (JSON would take the last silently)") {
    expect_input_error(rra_config(R"("length_mm": 150, "length_mm": 160)"), "geometry.length_mm");
  }
  SECTION("a directory given as the config") {
    const auto r = run_softarm("simulate " + std::string(SOFTARM_SOURCE_DIR) + "/configs");
    INFO(r.output);
    CHECK(r.exit_code == 2);
    CHECK(r.output.find("is a directory") != std::string::npos);
  }
}

TEST_CASE("the schema marks the lists a config must give as required, as the reader does", "[cli]") {
  // Issue 35: the schema listed load.chamber_pressures_kPa as optional while omitting it was refused.
  const auto tca = run_softarm("schema --scene tca");
  REQUIRE(tca.exit_code == 0);
  const auto line_of = [](const std::string& text, const std::string& key) {
    const auto at = text.find("\n" + key + "  (");
    return at == std::string::npos ? std::string() : text.substr(at + 1, text.find('\n', at + 1) - at - 1);
  };
  CHECK_THAT(line_of(tca.output, "load.chamber_pressures_kPa"), Catch::Contains("(required)"));
  CHECK_THAT(line_of(tca.output, "load.output_pressures_kPa"), Catch::Contains("(optional)"));
}

TEST_CASE("the schema of every config kind prints, with the keys each reader takes", "[cli]") {
  // `schema --scene design` once exited 2: its probe document lacked a complete start design.
  const std::vector<std::pair<std::string, std::vector<std::string>>> kinds = {
      {"rra", {"geometry.wall_thickness_normalised", "load.max_pressure_kPa", "materials.tube", "materials.rings"}},
      {"tca", {"load.chamber_pressures_kPa", "materials.sheath"}},
      {"spl", {"load.chamber_pressures_kPa", "materials.connector"}},
      {"design", {"requirements.max_mass_kg", "check.corrections", "check.improvement_rounds",
                  "check.improvement_tolerance_percent", "optimiser.categorical_keep"}},
      {"study", {"sweep[].parameter", "sweep[].values", "sweep[].range.from", "rule.limits", "rule.limits[].max",
                 "thesis.choice", "thesis.order", "scene", "scene_changes"}}};
  for (const auto& [kind, keys] : kinds) {
    const auto r = run_softarm("schema --scene " + kind);
    INFO(kind << ":\n" << r.output);
    REQUIRE(r.exit_code == 0);
    for (const auto& key : keys) CHECK(r.output.find("\n" + key + "  (") != std::string::npos);
  }
}

TEST_CASE("the study schema lists every key the shipped study configs use", "[cli]") {
  // Issue 36: keys read whole (sweep[].values, rule.limits, thesis.choice) were missing from it.
  const auto schema = run_softarm("schema --scene study");
  REQUIRE(schema.exit_code == 0);
  std::vector<std::string> used;  // dotted paths, list items as "[]"; the scene's own keys are the scene schema's
  const std::function<void(const nlohmann::json&, const std::string&)> collect = [&](const nlohmann::json& v,
                                                                                     const std::string& path) {
    if (v.is_array())
      for (const auto& item : v) collect(item, path + "[]");
    if (!v.is_object()) return;
    for (const auto& [key, value] : v.items()) {
      const std::string p = path.empty() ? key : path + "." + key;
      used.push_back(p);
      if (p != "scene" && p != "scene_changes") collect(value, p);
    }
  };
  int configs = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(SOFTARM_SOURCE_DIR) + "/configs/studies")) {
    std::ifstream in(entry.path());
    collect(nlohmann::json::parse(in, nullptr, true, true), "");
    ++configs;
  }
  CHECK(configs >= 10);
  for (const auto& key : used) {
    INFO(key);
    CHECK(schema.output.find("\n" + key + "  (") != std::string::npos);
  }
}

TEST_CASE("softarm bare prints its help, --version its version, an unknown command the nearest name", "[cli]") {
  const auto bare = run_softarm("");
  CHECK(bare.exit_code == 0);
  CHECK(bare.output.find("simulate") != std::string::npos);
  CHECK(bare.output.find("design") != std::string::npos);
  const auto version = run_softarm("--version");
  CHECK(version.exit_code == 0);
  CHECK(version.output.find("softarm 0.") != std::string::npos);
  const auto typo = run_softarm("simulat configs/rra_thesis.json");
  INFO(typo.output);
  CHECK(typo.exit_code == 2);
  CHECK(typo.output.find("unknown command 'simulat'; did you mean 'simulate'?") != std::string::npos);
}

TEST_CASE("softarm refuses non-finite and out-of-range options, naming the option", "[cli]") {
  const std::string rra = std::string(SOFTARM_SOURCE_DIR) + "/configs/rra_thesis.json";
  for (const std::string& args : {"export " + rra + " --pressure-kPa nan -o /tmp/softarm_cli_test/nan.inp",
                                 "export " + rra + " --pressure-kPa inf -o /tmp/softarm_cli_test/inf.inp",
                                 "export " + rra + " --pressure-kPa -5 -o /tmp/softarm_cli_test/neg.inp",
                                 "simulate " + rra + " --mesh-level 0 -o /tmp/softarm_cli_test/l0",
                                 "--threads 100000 simulate " + rra + " -o /tmp/softarm_cli_test/t",
                                 "--threads -1 simulate " + rra + " -o /tmp/softarm_cli_test/t"}) {
    const auto r = run_softarm(args);
    INFO(args << "\n" << r.output);
    CHECK(r.exit_code == 2);
    CHECK((r.output.find("--pressure-kPa") != std::string::npos || r.output.find("--mesh-level") != std::string::npos ||
           r.output.find("--threads") != std::string::npos));
  }
  CHECK_FALSE(std::filesystem::exists("/tmp/softarm_cli_test/nan.inp"));
}

TEST_CASE("an output path that is a file or cannot be made is exit 2 naming the option, before any work", "[cli]") {
  const std::string file = write_config("not_a_directory", "x");
  const std::string source = std::string(SOFTARM_SOURCE_DIR);
  for (const std::string& args : {"design " + source + "/configs/thesis_requirements.json --fidelity fast -o " + file,
                                 "design " + source + "/configs/thesis_requirements.json --fidelity fast -o " + file + "/sub",
                                 "study " + source + "/configs/studies/end_cap_thickness.json -o " + file}) {
    const auto r = run_softarm(args);
    INFO(args << "\n" << r.output);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.output, Catch::Contains("'-o/--output'") && Catch::Contains("cannot write to"));
    CHECK_THAT(r.output, !Catch::Contains("evaluation") && !Catch::Contains("softarm study:"));
  }
}

TEST_CASE("softarm refuses JSON nested without bound in every command that reads JSON, without a crash", "[cli]") {
  // 100,000 nested arrays once killed every JSON-reading command with a segmentation fault (issue 35).
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  const auto file = write_config("deep.json", deep);
  for (const std::string command : {"simulate ", "design ", "study ", "material check ", "export "}) {
    const auto r = run_softarm(command + file);
    INFO(command << ": " << r.output.substr(0, 400));
    CHECK(r.exit_code == 2);
    CHECK(r.output.find("nested deeper than 64 levels") != std::string::npos);
  }
}

TEST_CASE("a number beyond a double, a huge one and a misspelt section are named, exit 2", "[cli]") {
  SECTION("1e400 overflows a double while parsing: named, not an internal error") {
    expect_input_error(replaced(rra_config(""), R"("length_mm": 160)", R"("length_mm": 1e400)"), "geometry.length_mm");
  }
  SECTION("1e308 is refused with the range that excludes it") {
    expect_input_error(replaced(rra_config(""), R"("length_mm": 160)", R"("length_mm": 1e308)"),
                       {"geometry.length_mm", "<= 1e300"});
  }
  SECTION("a misspelt top-level section is named as the typo, with the section meant") {
    expect_input_error(replaced(rra_config(""), R"("geometry")", R"("geomtry")"), {"'geomtry'", "did you mean 'geometry'"});
  }
}

TEST_CASE("material check of a law without a volumetric term says incompressible, no inf", "[cli]") {
  const auto file = write_config("incompressible.json",
                                 R"({"name": "soft", "law": "neo_hookean", "C10_MPa": 0.1, "D_per_MPa": [0], "density_g_cm3": 1.07})");
  const auto r = run_softarm("material check " + file);
  INFO(r.output);
  CHECK(r.exit_code == 0);
  CHECK_THAT(r.output, Catch::Contains("incompressible (no volumetric term)"));
  CHECK(r.output.find("inf") == std::string::npos);
}

TEST_CASE("softarm rejects bad 3CA and SPL input with the field named", "[cli]") {
  const std::string sizes = R"("wall_thickness_normalised": 0.466, "end_cap_thickness_normalised": 0.25,
    "ring_count_normalised": 0.375, "ring_thickness_normalised": 0.4)";
  const auto tca = [&](const std::string& geometry, const std::string& load, const std::string& materials = "") {
    return R"({"scene": "tca", "geometry": {)" + sizes + geometry + R"(}, "load": {)" + load + "}" +
           (materials.empty() ? "" : R"(, "materials": {)" + materials + "}") + "}";
  };
  const std::string pressures = R"("chamber_pressures_kPa": [0, 40, 40])";
  expect_input_error(tca(R"(, "actuator_spacing_mm": 1)", pressures), "geometry.actuator_spacing_mm");
  expect_input_error(tca(R"(, "sheath_thickness_mm": 0.5)", pressures), "geometry.sheath_thickness_mm");
  expect_input_error(tca(R"(, "centre_hole_diameter_mm": 30)", pressures), "geometry.centre_hole_diameter_mm");
  expect_input_error(tca("", R"("chamber_pressures_kPa": [1, 2])"), "load.chamber_pressures_kPa");
  expect_input_error(tca("", R"("chamber_pressures_kPa": [0, 0, 0])"), "load.chamber_pressures_kPa");
  expect_input_error(tca("", ""), {"load.chamber_pressures_kPa", "required list is missing", "3 pressures (kPa)"});
  expect_input_error(tca("", pressures + R"(, "gravity_m_s2": [0, 1])"), "load.gravity_m_s2");
  expect_input_error(tca("", pressures, R"("sheath": "dragon_skin_99")"), "materials.sheath");
  const std::string tca_reduced_hex27 = tca("", pressures);
  expect_input_error(tca_reduced_hex27.substr(0, tca_reduced_hex27.size() - 1) +
                         R"(, "mesh": {"element_order": 2, "reduced_integration": true}})",
                     "mesh.reduced_integration");
  expect_input_error(tca_reduced_hex27.substr(0, tca_reduced_hex27.size() - 1) + R"(, "mesh": {"axial_level": 5}})",
                     "mesh.axial_level");
  expect_input_error(R"({"scene": "spl", "geometry": {)" + sizes + R"(, "bottom_radius_mm": 9}, "load": {"chamber_pressures_kPa": [0, 1, 1, 0, 0, 0, 0, 0, 0]}})",
                     "bottom_radius_mm");
  expect_input_error(R"({"scene": "spl", "geometry": {)" + sizes + R"(}, "load": {"chamber_pressures_kPa": [1, 2, 3]}})",
                     "load.chamber_pressures_kPa");
}

TEST_CASE("simulate on the SPL config's own model: the cell rod, its cells and joints, no NaN", "[cli][cell][long]") {
  // The thesis pose config asks for 5 %: the cell rod. A light load (chamber 9 at 30 kPa) keeps the
  // cells short; the upper segments' cells are unloaded (their rest state).
  std::ifstream in(std::string(SOFTARM_SOURCE_DIR) + "/configs/spl_thesis_pose.json");
  std::stringstream text;
  text << in.rdbuf();
  std::string config = text.str();
  const std::string pressures = "[0, 345, 345, 0, 86, 345, 0, 0, 59]";
  REQUIRE(config.find(pressures) != std::string::npos);
  config.replace(config.find(pressures), pressures.size(), "[0, 0, 0, 0, 0, 0, 0, 0, 30]");
  const auto file = write_config("spl_cell.json", config);
  const auto r = run_softarm("simulate " + file + " -o /tmp/softarm_cli_test/spl_cell");
  INFO(r.output);
  CHECK(r.exit_code == 0);
  CHECK(r.output.find("cell rod: 3 ring-pitch cells per segment") != std::string::npos);
  CHECK(r.output.find("segment 3: rings 1 15 30, half model") != std::string::npos);
  CHECK(r.output.find("twist at rest") != std::string::npos);  // each segment's, with its bonded ends'
  CHECK(r.output.find("fixed_point") != std::string::npos);
  CHECK(r.output.find("segment 3 bottom (tip)") != std::string::npos);
  CHECK(r.output.find("outcome: completed") != std::string::npos);
  CHECK(r.output.find("nan") == std::string::npos);
  std::ifstream summary("/tmp/softarm_cli_test/spl_cell/summary.json");
  REQUIRE(summary.good());
  // Every segment's top is bonded, and so are the bottoms but the tip's: each bonded end twists less
  // than its cells over the same length (its face cannot warp, its cap is solid).
  const nlohmann::json j = nlohmann::json::parse(summary);
  // The cells' solves, summed: nine ring-pitch cells and the end cells; segment 3's three cells
  // alone take a Newton iteration at each of their 16 output levels at least, and factorise.
  const nlohmann::json& solver = j.at("solver");
  INFO(solver.dump());
  CHECK(solver.at("cell_paths").get<int>() == 9 + j.at("end_cells").get<int>());
  CHECK(solver.at("newton_iterations").get<int>() >= 3 * 16);
  CHECK(solver.at("factorizations").get<int>() >= 3);
  CHECK(solver.at("cell_dofs_summed").get<long long>() >=
        j.at("largest_cell_dofs").get<long long>() + j.at("largest_end_cell_dofs").get<long long>());
  // The slowest cell: one of them, so more than their mean and no more than their sum.
  const double longest = solver.at("longest_cell_seconds").get<double>();
  const double summed = solver.at("cell_seconds_summed").get<double>();
  CHECK(longest >= summed / solver.at("cell_paths").get<int>());
  CHECK(longest <= summed);
  REQUIRE(j.at("cells").size() == 3);
  for (const auto& segment : j.at("cells")) {
    INFO("segment " << segment.at("segment"));
    const double with_ends = segment.at("twist_compliance_at_rest_rad_per_Nmm");
    CHECK(with_ends > 0);
    CHECK(with_ends < segment.at("twist_compliance_cells_alone_rad_per_Nmm").get<double>());
  }
}

TEST_CASE("simulate --fidelity fast poses the thesis SPL by the spatial rod", "[cli]") {
  const std::string config = std::string(SOFTARM_SOURCE_DIR) + "/configs/spl_thesis_pose.json";
  const auto r = run_softarm("simulate " + config + " --fidelity fast -o /tmp/softarm_cli_test/spl_rod");
  INFO(r.output);
  CHECK(r.exit_code == 0);
  CHECK(r.output.find("reduced spatial rod") != std::string::npos);
  CHECK(r.output.find("segment 3 bottom (tip)") != std::string::npos);
  CHECK(r.output.find("outcome: completed") != std::string::npos);
  CHECK(r.output.find("nan") == std::string::npos);
  std::ifstream summary("/tmp/softarm_cli_test/spl_rod/summary.json");
  CHECK(summary.good());
  // The rod's centreline at every output, for ParaView: one poly-line per curve.csv row.
  std::ifstream curve("/tmp/softarm_cli_test/spl_rod/curve.csv"), centreline("/tmp/softarm_cli_test/spl_rod/centreline.vtu");
  const long rows = std::count(std::istreambuf_iterator<char>(curve), std::istreambuf_iterator<char>(), '\n') - 1;
  std::stringstream vtu;
  vtu << centreline.rdbuf();
  CHECK(rows >= 2);
  CHECK_THAT(vtu.str(), Catch::Contains("NumberOfCells=\"" + std::to_string(rows) + "\""));
  CHECK_THAT(vtu.str(), Catch::Contains("Name=\"load_fraction\""));
  // The ladder picks the mesh: a hand-set one as well is refused, naming the option.
  const auto both = run_softarm("simulate " + config + " --fidelity fast --mesh-level 2");
  CHECK(both.exit_code == 2);
  CHECK(both.output.find("--fidelity") != std::string::npos);
}

TEST_CASE("simulate keeps a 3D path as it goes: a rerun resumes it, a changed scene or --fresh starts over", "[cli][checkpoint]") {
  const auto config = [](int pressure_kPa) {
    return R"({"scene": "tca", "geometry": {"length_mm": 32, "bottom_radius_mm": 9, "top_radius_mm": 9.6,
      "wall_thickness_normalised": 0.466, "end_cap_thickness_normalised": 0.25, "ring_count_normalised": 0.375,
      "ring_thickness_normalised": 0.4}, "mesh": {"level": 1, "element_order": 1},
      "load": {"chamber_pressures_kPa": [0, )" + std::to_string(pressure_kPa) + ", " + std::to_string(pressure_kPa) +
           R"(], "output_count": 3}})";
  };
  const std::string dir = "/tmp/softarm_cli_test/checkpoint";
  const auto curve = [&] {
    std::ifstream in(dir + "/curve.csv");
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  };
  const auto file = write_config("checkpoint.json", config(60));
  const auto first = run_softarm("simulate " + file + " -o " + dir + " --fresh");
  INFO(first.output);
  REQUIRE(first.exit_code == 0);
  CHECK(first.output.find("checkpoint: " + dir + "/path_checkpoint.bin") != std::string::npos);
  CHECK(first.output.find("resumed") == std::string::npos);
  const std::string first_curve = curve();
  REQUIRE(std::count(first_curve.begin(), first_curve.end(), '\n') >= 4);  // a header, rest and 3 outputs

  // deformed.pvd: a frame per curve row, in order of pressure, each frame's VTU written.
  const auto pvd_frames = [&] {
    std::ifstream in(dir + "/deformed.pvd");
    std::vector<std::string> files;
    for (std::string line; std::getline(in, line);)
      if (const auto at = line.find("file=\""); at != std::string::npos)
        files.push_back(line.substr(at + 6, line.find('"', at + 6) - at - 6));
    return files;
  };
  const auto frames = pvd_frames();
  CHECK(static_cast<long>(frames.size()) == std::count(first_curve.begin(), first_curve.end(), '\n') - 1);
  for (const auto& frame : frames) CHECK(std::filesystem::is_regular_file(dir + "/" + frame));

  const auto again = run_softarm("simulate " + file + " -o " + dir);
  INFO(again.output);
  CHECK(again.exit_code == 0);
  CHECK(again.output.find("resumed ") != std::string::npos);
  CHECK(curve() == first_curve);  // the same states, replayed
  CHECK(pvd_frames() == frames);  // and the same frames
  std::ifstream summary(dir + "/summary.json");
  CHECK(nlohmann::json::parse(summary).at("solver").at("resumed_states").get<int>() > 4);

  write_config("checkpoint.json", config(50));
  const auto changed = run_softarm("simulate " + file + " -o " + dir);
  INFO(changed.output);
  CHECK(changed.exit_code == 0);
  CHECK(changed.output.find("started over") != std::string::npos);
  CHECK(curve() != first_curve);
  const auto fresh = run_softarm("simulate " + file + " -o " + dir + " --fresh");
  CHECK(fresh.output.find("resumed") == std::string::npos);
  CHECK(fresh.output.find("started over") == std::string::npos);
  // A checkpoint that cannot be written is bad input, before the run.
  const auto unwritable = run_softarm("simulate " + file + " -o /proc/softarm_cannot_write_here --fresh");
  INFO(unwritable.output);
  CHECK(unwritable.exit_code == 2);
  CHECK(unwritable.output.find("output.directory") != std::string::npos);
}

TEST_CASE("workspace and reach refuse bad input with the option or field named, before any cells", "[cli][workspace]") {
  const std::string spl = std::string(SOFTARM_SOURCE_DIR) + "/configs/spl_thesis_pose.json";
  const std::string out = (std::filesystem::temp_directory_path() / "softarm_cli_test" / "ws_refused").string();
  std::filesystem::remove_all(out);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"workspace " + spl + " -o " + out + " --samples 0", "--samples"},
      {"workspace " + spl + " -o " + out + " --max-pressure-kPa nan", "--max-pressure-kPa"},
      {"workspace " + spl + " -o " + out + " --directions 9", "--directions"},
      {"workspace " + std::string(SOFTARM_SOURCE_DIR) + "/configs/tca_thesis.json -o " + out, "'scene'"},
      {"reach " + spl + " -o " + out, "--target"},
      {"reach " + spl + " -o " + out + " --target 1,2", "--target"},
      {"reach " + spl + " -o " + out + " --target 0,0,inf", "--target"},
      {"reach " + spl + " -o " + out + " --target 0,0,100 --axis 0,0,0", "--axis"},
      {"reach " + spl + " -o " + out + " --target 0,0,100 --payload-kg -1", "--payload-kg"},
      {"reach -o " + out + " --tasks " + write_config("tasks_bad.json", R"({"scene": "x.json", "targets": [{"name": "cup", "position_mm": [1, 2]}]})"),
       "targets[0].position_mm"},
      {"reach -o " + out + " --tasks " + write_config("tasks_typo.json", R"({"scene": "x.json", "targetz": []})"), "targetz"},
      {"workspace " + spl + " -o " + out + " --design " + spl, "--design"},  // a design's optimum with a scene
      {"workspace " + std::string(SOFTARM_SOURCE_DIR) + "/configs/thesis_requirements.json -o " + out + " --design " +
           write_config("summary_bad.json", R"({"optimum": {"ring_count": 300}})"),
       "optimum"},
  };
  for (const auto& [args, field] : cases) {
    const auto r = run_softarm(args);
    INFO(args << "\n" << r.output);
    CHECK(r.exit_code == 2);
    CHECK(r.output.find(field) != std::string::npos);
  }
  CHECK_FALSE(std::filesystem::exists(out));  // nothing written
}

TEST_CASE("workspace and reach pose a requirements file's arm: its baseline, or a design run's optimum", "[cli][workspace]") {
  const std::string requirements = std::string(SOFTARM_SOURCE_DIR) + "/configs/thesis_requirements.json";
  const softarm::engine::ArmInput baseline = softarm::engine::read_arm_input(requirements);
  // The requirements' bound and payload; the arm hanging under gravity, as the design judges it.
  CHECK(baseline.max_pressure_kPa == Approx(344.7));
  CHECK(baseline.payload_kg == Approx(0.5));
  CHECK(baseline.spl.gravity_m_s2.z() == Approx(-9.80665));
  // The baseline is the thesis arm: the same design as the thesis' pose scene.
  const softarm::engine::ArmInput thesis =
      softarm::engine::read_arm_input(std::string(SOFTARM_SOURCE_DIR) + "/configs/spl_thesis_pose.json");
  CHECK(nlohmann::json(softarm::fem::to_json(baseline.spl.design.segments[2])) ==
        nlohmann::json(softarm::fem::to_json(thesis.spl.design.segments[2])));
  // A design run's optimum (its summary's variables by name) replaces the baseline, and keys the cells apart.
  nlohmann::json summary = {{"optimum",
                             {{"wall_thickness_normalised", 0.5}, {"end_cap_thickness_normalised", 0.3}, {"ring_count", 30},
                              {"ring_thickness_normalised", 0.45}, {"actuator_spacing_mm", 4}, {"taper_ratio", 0.6},
                              {"tube_material", "dragon_skin_20"}, {"sheath_material", "dragon_skin_30"}}}};
  const softarm::engine::ArmInput optimum =
      softarm::engine::read_arm_input(requirements, write_config("summary_optimum.json", summary.dump()));
  CHECK(optimum.spl.design.segments[0].actuator.ring_count == 30);
  CHECK(optimum.spl.design.taper_ratio == Approx(0.6));
  CHECK(optimum.spl.design.segments[0].actuator_spacing_mm == Approx(4));
  CHECK(optimum.spl.tube_material.name == "dragon_skin_20");
  CHECK(optimum.cells_key != baseline.cells_key);
  summary["optimum"].erase("taper_ratio");
  CHECK_THROWS_WITH(softarm::engine::read_arm_input(requirements, write_config("summary_short.json", summary.dump())),
                    Catch::Contains("optimum.taper_ratio"));
}

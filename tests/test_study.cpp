// `softarm study` (issue 5): a study killed midway (even mid-write) and rerun ends with
// the results of an uninterrupted run, nothing lost or duplicated; two MPI ranks give the
// serial run's results; the reports show their plots and shapes in a real browser; the
// design rule and its words on hand-made records; the results file drops a torn line and
// refuses another config's results; the process pool turns a crash or a hang into a
// failure; bad study configs exit 2 naming the field. Tiny studies (FEM mesh level 1,
// 3 output pressures; rod 3CAs) keep the whole file under a minute on two cores.
#include <catch2/catch.hpp>
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "fem/core/json_reader.hpp"
#include "studies/cluster.hpp"
#include "studies/design_rule.hpp"
#include "studies/process_pool.hpp"
#include "studies/results_store.hpp"
#include "studies/study_points.hpp"
#include "studies/study_spec.hpp"
#include "support/browser_render.hpp"
#include "support/time_limit.hpp"
#include "support/external_tool.hpp"
#include "support/text_file.hpp"

using nlohmann::json;
namespace fs = std::filesystem;
namespace studies = softarm::studies;

namespace {

struct TempDir {  // one per test case and process: ctest runs test cases in parallel
  inline static int count = 0;
  fs::path path = fs::temp_directory_path() /
                  ("softarm_test_study_" + std::to_string(::getpid()) + "_" + std::to_string(count++));
  TempDir() {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() {
    if (!std::getenv("SOFTARM_KEEP_STUDY_TEST")) fs::remove_all(path);
  }
};

using softarm::test::read_text;

fs::path write_json(const fs::path& file, const json& document) {
  std::ofstream(file) << document.dump(2) << "\n";
  return file;
}

struct RunResult {
  int exit_code;
  std::string output;
};

/// `softarm <args>` (or `<prefix> softarm <args>`), one assembly thread so the FEM is deterministic.
RunResult run_softarm(const std::string& args, const fs::path& log, const std::string& prefix = "") {
  const int code = softarm::test::run_softarm_logged("SOFTARM_THREADS=1 " + prefix, args, log);
  return {code, read_text(log)};
}

// The thesis RRA at mesh level 1 with 3 output pressures (about 0.5 s a point).
json rra_scene() {
  return {{"scene", "rra"},
          {"geometry",
           {{"length_mm", 160}, {"bottom_radius_mm", 9}, {"top_radius_mm", 12}, {"wall_thickness_normalised", 0.466},
            {"end_cap_thickness_normalised", 0.25}, {"ring_count_normalised", 0.375},
            {"ring_reference_diameter_mm", 2}, {"ring_thickness_normalised", 0.4}, {"fixed_end", "top"}}},
          {"materials", {{"tube", "dragon_skin_30"}, {"rings", "digital_abs"}}},
          {"mesh", {{"level", 1}, {"element_order", 2}}},
          {"load", {{"max_pressure_kPa", 206.8}, {"output_count", 3}}}};
}

json rra_study(const std::string& name, const json& ring_counts, const json& tubes) {
  json sweep = json::array({{{"parameter", "geometry.ring_count_normalised"}, {"label", "normalised ring count"},
                             {"values", ring_counts}}});
  if (!tubes.is_null()) sweep.push_back({{"parameter", "materials.tube"}, {"label", "tube"}, {"values", tubes}});
  return {{"study", name},
          {"title", "Test study " + name},
          {"scene", rra_scene()},
          {"model", "fem"},
          {"safety_factor", 1.0},
          {"sweep", sweep},
          {"plot", {{"x", "parameter"}, {"y", "extension_mm"}}},
          {"rule",
           {{"goal", "max"}, {"output", "extension_mm"}, {"keep_percent", 99}, {"then_minimise", "mass_g"},
            {"limits", json::array({{{"output", "burst_utilisation"}, {"max", 1}}})}}},
          {"thesis", {{"choice", 0.375}, {"trend", "peak"}, {"peak_at", 0.5}, {"figure", "Fig 26"}}}};
}

// The thesis 3CA (configs/tca_thesis.json) for the rod model (milliseconds a point).
json tca_scene() {
  json scene = softarm::fem::load_json_file(std::string(SOFTARM_SOURCE_DIR) + "/configs/tca_thesis.json");
  scene.erase("output");
  scene.erase("description");
  return scene;
}

struct ResultsFile {
  json header;
  std::vector<json> records;  // in file order
  std::map<std::string, json> by_key;
  std::vector<std::string> duplicate_keys;
  std::vector<std::string> bad_lines;  // not a complete JSON object line
};

ResultsFile read_results(const fs::path& file) {
  ResultsFile r;
  const std::string text = read_text(file);
  std::size_t start = 0;
  bool first = true;
  while (start < text.size()) {
    const std::size_t end = text.find('\n', start);
    const std::string line = text.substr(start, end == std::string::npos ? std::string::npos : end - start);
    const json record = json::parse(line, nullptr, false);
    if (end == std::string::npos || record.is_discarded() || !record.is_object()) {
      r.bad_lines.push_back(line);
    } else if (first) {
      r.header = record;
      first = false;
    } else {
      const std::string key = record.value("key", std::string("(no key)"));
      if (r.by_key.count(key)) r.duplicate_keys.push_back(key);
      r.by_key[key] = record;
      r.records.push_back(record);
    }
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return r;
}

int result_lines(const fs::path& file) {
  const std::string text = read_text(file);
  int lines = 0;
  for (char c : text) lines += c == '\n';
  return std::max(0, lines - 1);  // less the header
}

/// Differences between two records, "seconds" aside: numbers to 1e-12 relative, the rest exactly.
void differences(const json& a, const json& b, const std::string& path, std::vector<std::string>& out) {
  if (out.size() > 20) return;
  if (a.is_number() && b.is_number()) {
    const double x = a.get<double>(), y = b.get<double>();
    if (!(x == y || std::abs(x - y) <= 1e-12 * std::max(std::abs(x), std::abs(y))))
      out.push_back(path + ": " + a.dump() + " vs " + b.dump());
  } else if (a.is_object() && b.is_object()) {
    for (const auto& [k, v] : a.items()) {
      if (k == "seconds") continue;
      if (!b.contains(k)) out.push_back(path + "." + k + ": only in the first");
      else differences(v, b[k], path + "." + k, out);
    }
    for (const auto& [k, v] : b.items())
      if (k != "seconds" && !a.contains(k)) out.push_back(path + "." + k + ": only in the second");
  } else if (a.is_array() && b.is_array()) {
    if (a.size() != b.size()) out.push_back(path + ": " + std::to_string(a.size()) + " vs " + std::to_string(b.size()) + " entries");
    else
      for (std::size_t i = 0; i < a.size(); ++i) differences(a[i], b[i], path + "[" + std::to_string(i) + "]", out);
  } else if (a != b) {
    out.push_back(path + ": " + a.dump().substr(0, 200) + " vs " + b.dump().substr(0, 200));
  }
}

/// Both results files complete, without duplicates, with the same keys and the same outputs.
void require_same_results(const fs::path& first, const fs::path& second, std::size_t expected_points) {
  const ResultsFile a = read_results(first), b = read_results(second);
  INFO(first.string() << " vs " << second.string());
  CHECK(a.bad_lines.empty());
  CHECK(b.bad_lines.empty());
  CHECK(a.duplicate_keys.empty());
  CHECK(b.duplicate_keys.empty());
  CHECK(a.records.size() == expected_points);
  CHECK(b.records.size() == expected_points);
  std::set<std::string> keys_a, keys_b;
  for (const auto& [k, r] : a.by_key) keys_a.insert(k);
  for (const auto& [k, r] : b.by_key) keys_b.insert(k);
  REQUIRE(keys_a == keys_b);
  REQUIRE(keys_a.size() == expected_points);
  CHECK(a.header == b.header);
  for (const auto& [key, record] : a.by_key) {
    INFO("point " << key);
    CHECK(record.value("status", std::string()) == "ok");
    CHECK(record.contains("extension_mm"));
    std::vector<std::string> diff;
    differences(record, b.by_key.at(key), "", diff);
    std::string text;
    for (const auto& d : diff) text += d + "\n";
    INFO(text);
    CHECK(diff.empty());
  }
}

/// Starts `softarm <args>` in a process group of its own (so that a kill reaches its point solvers too).
pid_t start_softarm(const std::vector<std::string>& args, const fs::path& log) {
  std::vector<std::string> argv_strings{SOFTARM_BINARY};
  argv_strings.insert(argv_strings.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& s : argv_strings) argv.push_back(s.data());
  argv.push_back(nullptr);
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    ::setpgid(0, 0);
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      ::dup2(fd, 1);
      ::dup2(fd, 2);
      ::close(fd);
    }
    ::setenv("SOFTARM_THREADS", "1", 1);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  ::setpgid(pid, pid);  // also here, so the group exists before we might kill it
  return pid;
}

const std::string kMpirun = softarm::test::mpirun_two_ranks(120);

}  // namespace

TEST_CASE("a study killed midway and rerun ends with the results of an uninterrupted run", "[study][long]") {
  TempDir tmp;
  const json ring_counts = {0.25, 0.375, 0.5}, tubes = {"dragon_skin_20", "dragon_skin_30"};
  const std::size_t n_points = 6;
  const fs::path config = write_json(tmp.path / "resume.json", rra_study("resume", ring_counts, tubes));
  const fs::path killed_root = tmp.path / "killed", clean_root = tmp.path / "clean";
  const fs::path results = killed_root / "resume" / "results.jsonl";

  // Start it, wait for two finished points, kill the whole process group.
  const pid_t pid = start_softarm({"study", config.string(), "-o", killed_root.string(), "--jobs", "1"},
                                  tmp.path / "killed.log");
  const auto t0 = std::chrono::steady_clock::now();
  bool exited_early = false;
  while (result_lines(results) < 2) {
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) == pid) {
      exited_early = true;
      break;
    }
    if (std::chrono::steady_clock::now() - t0 > std::chrono::seconds(60)) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (!exited_early) {
    ::kill(-pid, SIGKILL);
    ::waitpid(pid, nullptr, 0);
  }
  INFO("first run's output:\n" << read_text(tmp.path / "killed.log"));
  REQUIRE_FALSE(exited_early);
  const int done_before_kill = result_lines(results);
  REQUIRE(done_before_kill >= 2);
  REQUIRE(done_before_kill < static_cast<int>(n_points));  // the kill landed midway

  // As if the kill had come in the middle of writing a line.
  std::ofstream(results, std::ios::app) << R"({"status": "ok", "key": "[0.5,\"dragon_)";
  CHECK(read_results(results).bad_lines.size() == 1);

  const RunResult resumed =
      run_softarm("study " + config.string() + " -o " + killed_root.string() + " --jobs 1", tmp.path / "resumed.log");
  INFO("rerun's output:\n" << resumed.output);
  REQUIRE(resumed.exit_code == 0);
  // Every point finished before the kill is taken from the file, not recomputed.
  CHECK(resumed.output.find(std::to_string(n_points) + " points, " + std::to_string(done_before_kill) +
                            " from earlier runs") != std::string::npos);

  const RunResult clean =
      run_softarm("study " + config.string() + " -o " + clean_root.string() + " --jobs 1", tmp.path / "clean.log");
  INFO("uninterrupted run's output:\n" << clean.output);
  REQUIRE(clean.exit_code == 0);
  require_same_results(results, clean_root / "resume" / "results.jsonl", n_points);
  CHECK_FALSE(fs::exists(killed_root / "resume" / ".running-rank0"));  // the rerun cleaned the killed run's scratch

  // A third run has nothing left to do and leaves the file as it is.
  const std::string before = read_text(results);
  const RunResult again =
      run_softarm("study " + config.string() + " -o " + killed_root.string() + " --jobs 1", tmp.path / "again.log");
  INFO("third run's output:\n" << again.output);
  CHECK(again.exit_code == 0);
  CHECK(again.output.find(std::to_string(n_points) + " from earlier runs, 0 computed") != std::string::npos);
  CHECK(read_text(results) == before);
}

TEST_CASE("two MPI ranks give the results of a serial run", "[study][mpi][long]") {
  // The test process was not started by mpirun: MPI is not initialised, one rank.
  const studies::Cluster& local = studies::Cluster::instance();
  CHECK(local.size() == 1);
  CHECK(local.rank() == 0);
  CHECK(local.root());
  if (softarm::test::skip_without(studies::Cluster::available(), "Open MPI in this build",
                                  "Debian package libopenmpi-dev, then reconfigure; scripts/setup.sh installs it") ||
      softarm::test::skip_without_command("mpirun", "Open MPI, Debian package openmpi-bin"))
    return;

  TempDir tmp;
  const std::size_t n_points = 4;
  const fs::path config =
      write_json(tmp.path / "mpi.json", rra_study("mpi", json{0.25, 0.375, 0.5, 0.625}, json()));
  const fs::path mpi_root = tmp.path / "mpi", serial_root = tmp.path / "serial";

  const RunResult mpi = run_softarm("study " + config.string() + " -o " + mpi_root.string(), tmp.path / "mpi.log",
                                    kMpirun + "-x SOFTARM_THREADS ");
  INFO("mpirun output:\n" << mpi.output);
  REQUIRE(mpi.exit_code == 0);
  CHECK(mpi.output.find("2 ranks") != std::string::npos);  // both ranks took part in one study, not two
  CHECK(mpi.output.find(std::to_string(n_points) + " points, 0 from earlier runs, " + std::to_string(n_points) +
                        " computed (0 failed)") != std::string::npos);
  // Rank 0 alone writes: one report line, not one per rank.
  std::size_t reports = 0;
  for (std::size_t at = mpi.output.find("report: "); at != std::string::npos; at = mpi.output.find("report: ", at + 1))
    ++reports;
  CHECK(reports == 1);
  CHECK(fs::exists(mpi_root / "mpi" / "report.html"));
  CHECK_FALSE(fs::exists(mpi_root / "mpi" / ".running-rank1"));

  const RunResult serial =
      run_softarm("study " + config.string() + " -o " + serial_root.string() + " --jobs 1", tmp.path / "serial.log");
  INFO("serial output:\n" << serial.output);
  REQUIRE(serial.exit_code == 0);
  CHECK(serial.output.find("1 rank ") != std::string::npos);
  require_same_results(mpi_root / "mpi" / "results.jsonl", serial_root / "mpi" / "results.jsonl", n_points);
  // The same rule words and choice.
  const json s_mpi = json::parse(read_text(mpi_root / "mpi" / "summary.json"));
  const json s_serial = json::parse(read_text(serial_root / "mpi" / "summary.json"));
  CHECK(s_mpi["chosen"] == s_serial["chosen"]);
  CHECK(s_mpi["rule_words"] == s_serial["rule_words"]);

  // A rerun under mpirun resumes like a serial one: nothing left to compute.
  const RunResult again = run_softarm("study " + config.string() + " -o " + serial_root.string(),
                                      tmp.path / "again.log", kMpirun + "-x SOFTARM_THREADS ");
  INFO("mpirun rerun output:\n" << again.output);
  CHECK(again.exit_code == 0);
  CHECK(again.output.find(std::to_string(n_points) + " from earlier runs, 0 computed") != std::string::npos);
  CHECK(read_results(serial_root / "mpi" / "results.jsonl").records.size() == n_points);
}

TEST_CASE("study reports show their plots and deformed shapes in a real browser", "[study][browser][long]") {
  if (softarm::test::skip_without(!softarm::test::find_chromium().empty(), "headless Chromium",
                                  "Debian package chromium; scripts/setup.sh installs it"))
    return;
  TempDir tmp;
  const fs::path configs = tmp.path / "configs", root = tmp.path / "out";
  fs::create_directories(configs);
  // An RRA study (FEM, one curve: plots of the rule's output, the minimised and the limited outputs) …
  write_json(configs / "a_rra.json", rra_study("rra_rings", json{0.25, 0.375, 0.5}, json()));
  // … and a 3CA study (rod model, two curves, curves vs pressure too).
  write_json(configs / "b_tca.json",
             {{"study", "tca_spacing"},
              {"title", "Spacing & sheath <3CA>"},
              {"scene", tca_scene()},
              {"model", "rod"},
              {"sweep",
               {{{"parameter", "geometry.actuator_spacing_mm"}, {"label", "actuator spacing (mm)"}, {"values", {2, 3, 4}}},
                {{"parameter", "materials.sheath"}, {"label", "sheath"}, {"values", {"dragon_skin_20", "dragon_skin_30"}}}}},
              {"plot", {{"x", "pressure"}, {"y", "bending_deg"}}},
              {"rule", {{"goal", "max"}, {"output", "bending_deg"}, {"keep_percent", 99}, {"then_minimise", "mass_g"}}},
              {"thesis", {{"choice", 3}, {"trend", "decreasing"}}}});
  const RunResult run = run_softarm("study " + configs.string() + " -o " + root.string() + " --jobs 2",
                                    tmp.path / "run.log");
  INFO("study output:\n" << run.output);
  REQUIRE(run.exit_code == 0);

  const auto check_report = [](const fs::path& html, std::size_t plots, std::size_t shapes) {
    INFO(html.string());
    REQUIRE(fs::exists(html));
    const auto r = softarm::test::render_in_chromium(html);
    INFO(r.error);
    REQUIRE(r.ok);
    std::string errors;
    for (const auto& e : r.js_errors) errors += e + "\n";
    INFO("script errors:\n" << errors);
    CHECK(r.js_errors.empty());
    CHECK_FALSE(r.quirks_mode);
    CHECK(r.page_width <= r.viewport_width + 1);  // nothing wider than the window
    std::size_t n_plots = 0, n_shapes = 0;
    for (const auto& svg : r.svgs) {
      INFO(svg.describe());
      if (svg.heading == "Deformed shapes of the chosen points") {
        ++n_shapes;
        CHECK(svg.width >= 150);
        CHECK(svg.height >= 300);
        CHECK(svg.marks_by_element.count("line"));
        CHECK(svg.marks > 20);
        CHECK(svg.inked > 0.005);
      } else {
        ++n_plots;
        CHECK(svg.heading == "Results");
        CHECK_FALSE(svg.svg_title.empty());
        CHECK(svg.width > 300);
        CHECK(svg.height > 200);
        CHECK(svg.marks > 10);
        CHECK(svg.inked > 0.01);
      }
      CHECK(svg.marks_outside == 0);
    }
    CHECK(n_plots == plots);
    CHECK(n_shapes == shapes);
    return r;
  };
  // RRA: extension, mass (then_minimise) and burst utilisation (limit) vs the ring count; one shape.
  const auto rra = check_report(root / "rra_rings" / "report.html", 3, 1);
  CHECK(rra.title == "Test study rra_rings");
  // 3CA: bending vs pressure and vs the spacing, mass; one shape per sheath.
  const auto tca = check_report(root / "tca_spacing" / "report.html", 3, 2);
  CHECK(tca.title == "Spacing & sheath <3CA>");

  const auto index = softarm::test::render_in_chromium(root / "index.html");
  INFO(index.error);
  REQUIRE(index.ok);
  CHECK(index.js_errors.empty());
  CHECK_FALSE(index.quirks_mode);
  const std::string index_html = read_text(root / "index.html");
  CHECK(index_html.find("rra_rings/report.html") != std::string::npos);
  CHECK(index_html.find("tca_spacing/report.html") != std::string::npos);
  CHECK(index_html.find("Spacing &amp; sheath &lt;3CA&gt;") != std::string::npos);
}

namespace {

// A five-point ring-count study over the RRA scene, read as a real config, for the rule on hand-made records.
studies::StudySpec ring_spec(const json& rule, const json& thesis) {
  json doc = {{"study", "rule_test"},
              {"scene", rra_scene()},
              {"sweep", {{{"parameter", "geometry.ring_count_normalised"}, {"label", "r"},
                          {"values", {0.125, 0.25, 0.375, 0.5, 0.625}}}}},
              {"rule", rule},
              {"thesis", thesis}};
  return studies::read_study(doc);
}

json record(const studies::StudyPoint& p, double extension, double mass, double utilisation = 0.5,
            double reached = 200) {
  return {{"key", p.key},       {"index", p.index},      {"status", "ok"},
          {"extension_mm", extension}, {"mass_g", mass}, {"burst_utilisation", utilisation},
          {"reached_pressure_kPa", reached}, {"max_pressure_kPa", 200.0}, {"limit_pressure_kPa", nullptr}};
}

std::map<std::string, json> records_of(const std::vector<studies::StudyPoint>& points, const std::vector<double>& ext,
                                       const std::vector<double>& mass) {
  std::map<std::string, json> out;
  for (std::size_t i = 0; i < points.size(); ++i) out[points[i].key] = record(points[i], ext[i], mass[i]);
  return out;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

const json kKeepRule = {{"goal", "max"}, {"output", "extension_mm"}, {"keep_percent", 99}, {"then_minimise", "mass_g"},
                        {"limits", {{{"output", "burst_utilisation"}, {"max", 1}}}}};
const json kThesisPeak = {{"choice", 0.375}, {"trend", "peak"}, {"peak_at", 0.5}};

}  // namespace

TEST_CASE("the design rule picks the lightest point within keep_percent of the best and says so", "[study]") {
  const auto spec = ring_spec(kKeepRule, kThesisPeak);
  const auto points = studies::study_points(spec);
  REQUIRE(points.size() == 5);
  // The thesis' ring-count shape: a peak at 0.5, 0.375 within 1 % of it and lighter.
  auto records = records_of(points, {70, 75, 76.5, 76.67, 76}, {30, 35, 40, 45, 50});

  SECTION("best and chosen") {
    const auto curves = studies::apply_rule(spec, points, records);
    REQUIRE(curves.size() == 1);
    const auto& c = curves[0];
    INFO(c.words);
    CHECK(c.label.empty());
    CHECK(c.best == 3);
    CHECK(c.chosen == 2);
    CHECK(c.excluded.empty());
    CHECK(c.trend == "peak");
    REQUIRE(c.extremum_at);
    CHECK(*c.extremum_at == Approx(0.5));
    CHECK(c.order == std::vector<int>{3, 2, 4, 1, 0});
    CHECK(contains(c.words, "largest at r = 0.5 (76.67 mm)"));
    CHECK(contains(c.words, "r = 0.375 keeps 99.78 % of it"));
    CHECK(contains(c.words, "The rule picks r = 0.375."));
    const auto t = studies::compare_with_thesis(spec, points, curves);
    INFO(t.words);
    CHECK(t.choice_agrees);
    CHECK(t.trend_agrees);
    CHECK(contains(t.words, "picks the same"));
    CHECK(contains(t.words, "peak at 0.5"));
  }
  SECTION("keep_percent 100: the best itself") {
    json rule = kKeepRule;
    rule["keep_percent"] = 100;
    const auto s = ring_spec(rule, kThesisPeak);
    const auto curves = studies::apply_rule(s, points, records);
    INFO(curves[0].words);
    CHECK(curves[0].chosen == 3);
    CHECK(contains(curves[0].words, "The rule picks r = 0.5."));
    const auto t = studies::compare_with_thesis(s, points, curves);
    INFO(t.words);
    CHECK_FALSE(t.choice_agrees);
    CHECK(t.trend_agrees);
    CHECK(contains(t.words, "a different value on 1 of 1 curve(s)"));
  }
  SECTION("goal min") {
    json rule = {{"goal", "min"}, {"output", "mass_g"}};
    const auto s = ring_spec(rule, json::object());
    const auto curves = studies::apply_rule(s, points, records);
    INFO(curves[0].words);
    CHECK(curves[0].chosen == 0);
    CHECK(curves[0].trend == "increasing");
    CHECK(contains(curves[0].words, "smallest at r = 0.125 (30 g)"));
  }
  SECTION("a point over a limit is not eligible") {
    records[points[2].key]["burst_utilisation"] = 1.2;  // 0.375 would burst
    const auto curves = studies::apply_rule(spec, points, records);
    const auto& c = curves[0];
    INFO(c.words);
    CHECK(c.best == 3);
    CHECK(c.chosen == 3);  // 0.625 is within 1 % but heavier than 0.5
    REQUIRE(c.excluded.size() == 1);
    CHECK(c.excluded[0].first == 2);
    CHECK(contains(c.excluded[0].second, "burst_utilisation 1.2 > 1"));
    CHECK(contains(c.words, "The rule picks r = 0.5."));
    CHECK(contains(c.words, "Not eligible: 0.375 (burst_utilisation 1.2 > 1)"));
    CHECK(c.trend == "peak");  // the limit excludes from the choice, not from the curve
  }
  SECTION("a point that stopped before the peak pressure is not compared") {
    json& stopped = records[points[3].key];
    stopped["extension_mm"] = 90;  // the largest, but at a lower pressure
    stopped["reached_pressure_kPa"] = 150;
    stopped["limit_pressure_kPa"] = 150;
    const auto curves = studies::apply_rule(spec, points, records);
    const auto& c = curves[0];
    INFO(c.words);
    CHECK(c.best == 2);
    CHECK(c.chosen == 2);
    REQUIRE(c.excluded.size() == 1);
    CHECK(c.excluded[0].first == 3);
    CHECK(contains(c.excluded[0].second, "stopped at 150 of 200 kPa (limit point: ballooning)"));
    CHECK(c.trend == "peak");
    REQUIRE(c.extremum_at);
    CHECK(*c.extremum_at == Approx(0.375));  // the curve leaves the point out too
    CHECK(std::find(c.order.begin(), c.order.end(), 3) == c.order.end());
    CHECK(contains(c.words, "The rule picks r = 0.375."));
  }
  SECTION("failed and missing points are listed, not chosen") {
    records[points[3].key] = {{"key", points[3].key}, {"index", 3}, {"status", "failed"},
                              {"diagnosis", "the solver process crashed (signal 11, Segmentation fault)"}};
    records.erase(points[4].key);
    const auto curves = studies::apply_rule(spec, points, records);
    const auto& c = curves[0];
    INFO(c.words);
    CHECK(c.chosen == 2);
    REQUIRE(c.excluded.size() == 2);
    CHECK(contains(c.excluded[0].second, "failed: the solver process crashed"));
    CHECK(c.excluded[1].second == "not run yet");
  }
  SECTION("no eligible point") {
    for (auto& [key, r] : records) r["burst_utilisation"] = 2.0;
    const auto curves = studies::apply_rule(spec, points, records);
    INFO(curves[0].words);
    CHECK(curves[0].chosen == -1);
    CHECK(contains(curves[0].words, "No point is eligible (burst_utilisation 2 > 1)"));
    const auto t = studies::compare_with_thesis(spec, points, curves);
    CHECK_FALSE(t.choice_agrees);
  }
}

TEST_CASE("the design rule classifies the trend along the parameter", "[study]") {
  const auto spec = ring_spec({{"output", "extension_mm"}}, kThesisPeak);
  const auto points = studies::study_points(spec);
  const std::vector<double> mass{1, 1, 1, 1, 1};
  const auto trend = [&](const std::vector<double>& ext) {
    const auto curves = studies::apply_rule(spec, points, records_of(points, ext, mass));
    return curves.at(0);
  };
  CHECK(trend({10, 20, 30, 40, 50}).trend == "increasing");
  CHECK(trend({10, 20, 20, 40, 50}).trend == "increasing");
  CHECK(trend({50, 40, 30, 20, 10}).trend == "decreasing");
  const auto peak = trend({10, 20, 30, 25, 15});
  CHECK(peak.trend == "peak");
  CHECK(*peak.extremum_at == Approx(0.375));
  CHECK(contains(peak.words, "extension_mm along r: peak at 0.375"));
  const auto valley = trend({50, 20, 30, 40, 45});
  CHECK(valley.trend == "valley");
  CHECK(*valley.extremum_at == Approx(0.25));
  CHECK(trend({100, 100.1, 100.2, 100.1, 100}).trend == "flat");  // within 0.5 %
  CHECK(trend({10, 30, 20, 40, 50}).trend == "mixed");

  // The thesis' trend: agrees only with the same shape (and, for a peak, at the same place).
  const auto compare = [&](const std::vector<double>& ext, const json& thesis) {
    const auto s = ring_spec({{"output", "extension_mm"}}, thesis);
    return studies::compare_with_thesis(s, points, studies::apply_rule(s, points, records_of(points, ext, mass)));
  };
  CHECK(compare({10, 20, 30, 40, 35}, kThesisPeak).trend_agrees);
  const auto elsewhere = compare({10, 20, 30, 25, 15}, kThesisPeak);
  INFO(elsewhere.words);
  CHECK_FALSE(elsewhere.trend_agrees);
  CHECK(contains(elsewhere.words, "softarm: peak at 0.375 — differs."));
  CHECK(compare({50, 40, 30, 20, 10}, {{"trend", "decreasing"}}).trend_agrees);
  CHECK_FALSE(compare({10, 20, 30, 40, 50}, {{"trend", "decreasing"}}).trend_agrees);
}

TEST_CASE("a categorical study compares the order of its values with the thesis", "[study]") {
  const json doc = {{"study", "tube_material"},
                    {"scene", rra_scene()},
                    {"sweep", {{{"parameter", "materials.tube"}, {"label", "tube"},
                                {"values", {"dragon_skin_20", "dragon_skin_30", "dragon_skin_10"}}}}},
                    {"rule", {{"output", "extension_mm"}}},
                    {"thesis", {{"choice", "dragon_skin_10"}, {"order", {"dragon_skin_10", "dragon_skin_20", "dragon_skin_30"}}}}};
  const auto spec = studies::read_study(doc);
  const auto points = studies::study_points(spec);
  REQUIRE(points.size() == 3);
  CHECK_FALSE(spec.axes[0].numeric());

  auto records = records_of(points, {80, 70, 95}, {40, 40, 40});
  auto curves = studies::apply_rule(spec, points, records);
  INFO(curves[0].words);
  CHECK(curves[0].trend.empty());  // no trend along names
  CHECK(curves[0].chosen == 2);
  CHECK(curves[0].order == std::vector<int>{2, 0, 1});
  CHECK(contains(curves[0].words, "The rule picks tube = dragon_skin_10."));
  auto t = studies::compare_with_thesis(spec, points, curves);
  INFO(t.words);
  CHECK(t.choice_agrees);
  CHECK(t.trend_agrees);
  CHECK(contains(t.words, "dragon_skin_10 > dragon_skin_20 > dragon_skin_30 — agrees."));

  records = records_of(points, {70, 80, 95}, {40, 40, 40});
  curves = studies::apply_rule(spec, points, records);
  t = studies::compare_with_thesis(spec, points, curves);
  INFO(t.words);
  CHECK(t.choice_agrees);
  CHECK_FALSE(t.trend_agrees);
  CHECK(contains(t.words, "softarm: dragon_skin_10 > dragon_skin_30 > dragon_skin_20 — differs."));
}

TEST_CASE("the results file drops a torn last line and refuses another config's results", "[study]") {
  TempDir tmp;
  const fs::path file = tmp.path / "sub" / "results.jsonl";
  {
    studies::ResultsStore store(file, "s", "fp-1", false);
    CHECK(store.records().empty());
    for (int i = 0; i < 3; ++i) store.append({{"key", "k" + std::to_string(i)}, {"status", "ok"}, {"value", i}});
    store.append({{"key", "k1"}, {"status", "ok"}, {"value", 10}});  // a recomputed point: the last record wins
    CHECK(store.records().size() == 3);
  }
  const auto complete_size = fs::file_size(file);

  SECTION("a line cut short by a kill is dropped and cut off the file") {
    std::ofstream(file, std::ios::app | std::ios::binary) << R"({"key": "k3", "status": "o)";
    studies::ResultsStore store(file, "s", "fp-1", false);
    CHECK(store.dropped_lines() == 1);
    CHECK(store.records().size() == 3);
    CHECK(store.records().at("k1")["value"] == 10);
    CHECK_FALSE(store.finished("k3"));
    CHECK(fs::file_size(file) == complete_size);
    store.append({{"key", "k3"}, {"status", "ok"}, {"value", 3}});
    const ResultsFile r = read_results(file);
    CHECK(r.bad_lines.empty());
    CHECK(r.records.size() == 5);
    CHECK(r.header["fingerprint"] == "fp-1");
    studies::ResultsStore reopened(file, "s", "fp-1", false);
    CHECK(reopened.dropped_lines() == 0);
    CHECK(reopened.records().size() == 4);
  }
  SECTION("a garbled line is dropped with everything after it") {
    std::ofstream(file, std::ios::app | std::ios::binary) << "{\"key\": \"k3\", \"sta\n{\"key\": \"k4\"}\n";
    studies::ResultsStore store(file, "s", "fp-1", false);
    CHECK(store.dropped_lines() == 1);
    CHECK(store.records().size() == 3);
    CHECK(fs::file_size(file) == complete_size);
  }
  SECTION("another fingerprint is refused, naming --fresh") {
    CHECK_THROWS_WITH(studies::ResultsStore(file, "s", "fp-2", false), Catch::Contains("--fresh"));
    CHECK(fs::file_size(file) == complete_size);  // untouched
  }
  SECTION("fresh discards earlier results") {
    studies::ResultsStore store(file, "s", "fp-2", true);
    CHECK(store.records().empty());
    const ResultsFile r = read_results(file);
    CHECK(r.records.empty());
    CHECK(r.header["fingerprint"] == "fp-2");
    CHECK(r.header["study"] == "s");
  }
  SECTION("an empty file gets a header") {
    std::ofstream(file, std::ios::trunc);
    studies::ResultsStore store(file, "s", "fp-1", false);
    CHECK(store.records().empty());
    CHECK(read_results(file).header["fingerprint"] == "fp-1");
  }
}

TEST_CASE("the process pool turns a crash or a hang into a failure and passes results through", "[study]") {
  TempDir tmp;
  const auto run_all = [](studies::ProcessPool& pool, double limit_s) {
    std::map<int, studies::ProcessPool::Finished> done;
    const auto t0 = std::chrono::steady_clock::now();
    while (!pool.idle() && std::chrono::steady_clock::now() - t0 < std::chrono::duration<double>(limit_s)) {
      for (auto& f : pool.collect()) done[f.task] = f;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return done;
  };
  studies::ProcessPool pool(2, 1.0, tmp.path / "scratch");
  CHECK(pool.idle());
  pool.start(0, [] { return std::string(100000, 'x') + "\n{\"status\": \"ok\"}"; });
  pool.start(1, [] {
    std::signal(SIGSEGV, SIG_DFL);  // the test framework's handler must not report from the child
    std::raise(SIGSEGV);
    return std::string("never");
  });
  CHECK_FALSE(pool.has_free_slot());
  auto done = run_all(pool, 20);
  REQUIRE(done.size() == 2);
  CHECK(done[0].ok);
  CHECK(done[0].output == std::string(100000, 'x') + "\n{\"status\": \"ok\"}");
  CHECK_FALSE(done[1].ok);
  INFO(done[1].failure);
  CHECK(contains(done[1].failure, "signal 11"));
  CHECK(contains(done[1].failure, "Segmentation fault"));

  const auto t0 = std::chrono::steady_clock::now();
  pool.start(2, [] {
    std::this_thread::sleep_for(std::chrono::seconds(30));
    return std::string("late");
  });
  pool.start(3, []() -> std::string { throw std::runtime_error("no"); });
  done = run_all(pool, 20);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  REQUIRE(done.size() == 2);
  CHECK_FALSE(done[2].ok);
  INFO(done[2].failure);
  CHECK(contains(done[2].failure, "stopped after 1 s (point_timeout_s)"));
  CHECK(done[2].seconds >= 1.0);
  CHECK(seconds < 10);
  CHECK_FALSE(done[3].ok);
  CHECK(contains(done[3].failure, "exited with code 1"));
  CHECK(pool.idle());
  // Nothing left behind in the scratch directory.
  CHECK(fs::is_empty(tmp.path / "scratch"));
}

TEST_CASE("bad study configs exit 2 naming the field", "[study]") {
  TempDir tmp;
  const auto expect_error = [&](const json& config, const std::string& field, const std::string& words = "") {
    const fs::path file = write_json(tmp.path / "bad.json", config);
    const RunResult r = run_softarm("study " + file.string() + " -o " + (tmp.path / "out").string(), tmp.path / "log");
    INFO("config: " << config.dump() << "\noutput: " << r.output);
    CHECK(r.exit_code == 2);
    CHECK(contains(r.output, "'" + field + "'"));
    if (!words.empty()) CHECK(contains(r.output, words));
    CHECK(contains(r.output, file.string()));  // which config
    CHECK_FALSE(fs::exists(tmp.path / "out"));  // nothing run
  };
  const json good = rra_study("bad", json{0.25, 0.5}, json());
  SECTION("unknown sweep parameter") {
    json c = good;
    c["sweep"][0]["parameter"] = "geometry.wal_thickness_normalised";
    expect_error(c, "sweep[0].parameter", "wal_thickness_normalised");
  }
  SECTION("unknown section") {
    json c = good;
    c["sweep"][0]["parameter"] = "geometri.wall_thickness_normalised";
    expect_error(c, "sweep[0].parameter", "geometri");
  }
  SECTION("a later value the scene cannot take") {
    json c = good;
    c["sweep"][0]["parameter"] = "taper_ratio";
    c["sweep"][0]["values"] = {0.5, 1.5};
    expect_error(c, "sweep[0].parameter", "taper ratio 1.5 is outside (0, 1]");
  }
  SECTION("a value outside the scene's range, named by its place in the sweep") {
    json c = good;
    c["sweep"][0]["values"] = {0.25, -0.5};
    expect_error(c, "sweep[0].values[1]", "geometry.");
  }
  SECTION("rule output not an output of the scene") {
    json c = good;
    c["rule"]["output"] = "bending_deg";
    expect_error(c, "rule.output", "bending_deg");
  }
  SECTION("limit output not an output of the scene") {
    json c = good;
    c["rule"]["limits"][0]["output"] = "sheath_max_stretch";
    expect_error(c, "rule.limits[0].output", "sheath_max_stretch");
  }
  SECTION("empty values list") {
    json c = good;
    c["sweep"][0]["values"] = json::array();
    expect_error(c, "sweep[0].values", "non-empty");
  }
  SECTION("repeated value") {
    json c = good;
    c["sweep"][0]["values"] = {0.25, 0.25};
    expect_error(c, "sweep[0].values[1]", "repeated");
  }
  SECTION("spl scene") {
    json scene = softarm::fem::load_json_file(std::string(SOFTARM_SOURCE_DIR) + "/configs/spl_thesis_pose.json");
    scene.erase("output");
    scene.erase("description");
    json c = good;
    c["scene"] = scene;
    c["sweep"][0]["parameter"] = "geometry.wall_thickness_normalised";
    c["sweep"][0]["values"] = {0.4, 0.466};
    expect_error(c, "scene.scene", "spl");
  }
  SECTION("unknown key in the study") {
    json c = good;
    c["rulle"] = c["rule"];
    expect_error(c, "rulle");
  }
}

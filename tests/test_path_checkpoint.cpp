// A 3D path keeps its converged states as it goes (fem/scenes/path_log.hpp): a run
// stopped midway and run again resumes from its last converged step and ends where an
// uninterrupted run ends; a torn record is dropped, a log of another model is not resumed.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "fem/scenes/path_log.hpp"
#include "fem/scenes/tca_scene.hpp"
#include "support/short_3ca.hpp"

using namespace softarm::fem;

namespace {
// A short 3CA (4 rings, 24 mm) of Hex20 bending under gravity across it, in four outputs: a
// weight preload, then several pressure steps, each a second or two on one thread.
TcaSceneSpec short_bending_3ca() {
  TcaSceneSpec s = softarm::test::short_3ca_scene(60, {15, 30, 45, 60});
  s.serendipity = true;
  return s;
}

struct StopAfter : std::runtime_error {
  StopAfter() : std::runtime_error("stopped") {}
};

std::filesystem::path scratch(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "softarm_path_checkpoint_test";
  std::filesystem::create_directories(dir);
  std::filesystem::remove(dir / name);
  return dir / name;
}
}  // namespace

TEST_CASE("A 3D path stopped midway resumes from its log and ends where an uninterrupted run does", "[checkpoint][long]") {
  const TcaSceneSpec plain = short_bending_3ca();
  const TcaResult uninterrupted = run_tca_scene(plain);
  REQUIRE(uninterrupted.path.outcome == PathOutcome::completed);
  REQUIRE(uninterrupted.path.path.stats.steps >= 5);

  TcaSceneSpec logged = plain;
  logged.checkpoint = {scratch("path.bin").string(), "short 3CA"};
  // Stopped at 45 kPa (as a kill would: that state's record is not written yet); the rest state
  // is the first output.
  int outputs = 0;
  CHECK_THROWS_AS(run_tca_scene(logged, [&](const TcaState&) {
                    if (++outputs == 4) throw StopAfter();
                  }),
                  StopAfter);
  const std::size_t logged_states = PathLog(logged.checkpoint.file, "short 3CA", uninterrupted.dofs).resumed().size();
  INFO("states logged before the stop: " << logged_states);
  REQUIRE(logged_states >= 3);  // rest, 15 and 30 kPa, and any steps between

  const TcaResult resumed = run_tca_scene(logged);
  CHECK(resumed.path.resumed_states == static_cast<int>(logged_states));
  CHECK(resumed.path.checkpoint_discarded.empty());
  REQUIRE(resumed.path.outcome == PathOutcome::completed);
  // Every state, the replayed ones too, as the uninterrupted run had them (Newton's 1e-8
  // tolerance: the resumed run starts without the last factor, so its iterates differ there).
  REQUIRE(resumed.curve.size() == uninterrupted.curve.size());
  for (std::size_t i = 0; i < resumed.curve.size(); ++i) {
    CHECK(resumed.curve[i].pressure_kPa == Approx(uninterrupted.curve[i].pressure_kPa));
    CHECK(resumed.curve[i].bending_angle_deg == Approx(uninterrupted.curve[i].bending_angle_deg).margin(1e-5));
    CHECK((resumed.curve[i].tip_position_mm - uninterrupted.curve[i].tip_position_mm).norm() < 1e-5);
  }
  CHECK((resumed.final_positions - uninterrupted.final_positions).lpNorm<Eigen::Infinity>() < 1e-5);
  // The step counts go on from the logged ones: the whole path's, not the resumed part's.
  CHECK(resumed.path.path.stats.steps == uninterrupted.path.path.stats.steps);

  // A rerun of the finished path replays it without a Newton step of its own.
  const TcaResult replayed = run_tca_scene(logged);
  CHECK(replayed.path.resumed_states == static_cast<int>(uninterrupted.states.size()));
  CHECK(replayed.path.path.stats.newton_iterations == resumed.path.path.stats.newton_iterations);
  CHECK(replayed.curve.back().bending_angle_deg == Approx(resumed.curve.back().bending_angle_deg).epsilon(1e-12));
}

TEST_CASE("A path log drops a torn record and does not resume another model's states", "[checkpoint]") {
  const auto file = scratch("log.bin").string();
  const auto record = [](double level) {
    PathLogRecord r;
    r.level = level;
    r.next_increment = 0.1;
    r.state.pressure_kPa = 100 * level;
    r.state.is_output = true;
    r.stats.steps = static_cast<int>(10 * level);
    r.x = Eigen::VectorXd::LinSpaced(30, level, 1 + level);
    return r;
  };
  {
    PathLog log(file, "model A", 30);
    CHECK(log.resumed().empty());
    CHECK(log.discarded_reason().empty());
    for (double level : {0.0, 0.1, 0.2}) log.append(record(level));
  }
  {
    const PathLog log(file, "model A", 30);
    REQUIRE(log.resumed().size() == 3);
    CHECK(log.resumed()[2].level == 0.2);
    CHECK(log.resumed()[2].stats.steps == 2);
    CHECK(log.resumed()[2].state.pressure_kPa == 20);
    CHECK(log.resumed()[2].state.is_output);
    CHECK(log.resumed()[2].x == record(0.2).x);
  }
  // A kill in the middle of writing the last record.
  std::filesystem::resize_file(file, std::filesystem::file_size(file) - 17);
  {
    PathLog log(file, "model A", 30);
    REQUIRE(log.resumed().size() == 2);
    log.append(record(0.3));  // after the last whole record, not after the torn bytes
  }
  {
    const PathLog log(file, "model A", 30);
    REQUIRE(log.resumed().size() == 3);
    CHECK(log.resumed()[2].level == 0.3);
  }
  // Another config, or another mesh with as many unknowns named the same: started over.
  for (const auto& [name, dofs] : {std::pair<std::string, int>{"model B", 30}, {"model A", 33}}) {
    const PathLog other(file, name, dofs);
    CHECK(other.resumed().empty());
    CHECK(other.discarded_reason().find("another model") != std::string::npos);
  }
}

// The progress lines of long phases (a run's cells, a study's points): one line per finished task
// in a log, counted and timed from when the work began, with an ETA while tasks are left.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "fem/core/parallel.hpp"
#include "studies/progress_bar.hpp"

namespace {
std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}
}  // namespace

TEST_CASE("task_progress prints a line per finished task, timed from the start of the tasks", "[progress]") {
  std::ostringstream out;  // not a terminal: line mode
  const int saved = softarm::fem::thread_count();
  softarm::fem::set_thread_count(1);  // in order: the slow first task ends first
  const softarm::fem::TaskProgress progress = softarm::studies::task_progress(out, "cells");
  // The first task ends after ~1.2 s: its line must say so (an ETA timed from the first task's end
  // would read 0 s there).
  softarm::fem::parallel_tasks(
      3, [](int i) { std::this_thread::sleep_for(std::chrono::milliseconds(i == 0 ? 1200 : 10)); }, progress);
  softarm::fem::set_thread_count(saved);
  const auto lines = lines_of(out.str());
  INFO(out.str());
  REQUIRE(lines.size() == 3);
  CHECK(lines[0].rfind("cells [", 0) == 0);
  CHECK(lines[0].find("] 1/3  1 s, ETA") != std::string::npos);
  CHECK(lines[2].find("] 3/3") != std::string::npos);
  CHECK(lines[2].find("ETA") == std::string::npos);  // nothing left
}

TEST_CASE("parallel_tasks tells its progress once per task, one call at a time, also when one throws", "[progress]") {
  const int saved = softarm::fem::thread_count();
  for (int threads : {1, 2}) {
    softarm::fem::set_thread_count(threads);
    std::vector<int> seen;
    int concurrent = 0, most = 0;
    const auto record = [&](int done, int total) {
      most = std::max(most, ++concurrent);
      seen.push_back(done);
      CHECK(total == 5);
      --concurrent;
    };
    CHECK_THROWS(softarm::fem::parallel_tasks(
        5, [](int i) { if (i == 3) throw std::runtime_error("task 3"); }, record));
    CHECK(seen == std::vector<int>{1, 2, 3, 4, 5});
    CHECK(most == 1);
  }
  softarm::fem::set_thread_count(saved);
}

TEST_CASE("With points side by side, the first to finish does not multiply the ETA by their number", "[progress]") {
  // 15 cells two at a time, the first done after 100 s: the second is about done too, so 14 left take
  // about 7 × 100 s, not the 14 × 100 s one at a time would.
  const auto hundred_seconds_ago = std::chrono::steady_clock::now() - std::chrono::seconds(100);
  std::ostringstream two, one;
  softarm::studies::ProgressBar side_by_side(two, "cells", 15, 0, hundred_seconds_ago, 2);
  side_by_side.advance(false, "");
  softarm::studies::ProgressBar alone(one, "cells", 15, 0, hundred_seconds_ago, 1);
  alone.advance(false, "");
  INFO(two.str() << one.str());
  CHECK(two.str().find("ETA 11 min 40 s") != std::string::npos);  // 14 × 100 s / 2
  CHECK(one.str().find("ETA 23 min 20 s") != std::string::npos);  // 14 × 100 s
  // Once as many have finished as run at once, the rate is the points finished over the time.
  side_by_side.advance(false, "");
  side_by_side.advance(false, "");
  CHECK(two.str().find("ETA 6 min 40 s") != std::string::npos);  // 12 × 100 s / 3
}

TEST_CASE("task_progress counts the threads the tasks run on, not the one its first call comes from", "[progress]") {
  // Four tasks of a second on two threads: the first line comes at ~1 s, with the second task about
  // done too, so ~1.5 s left (said "2 s"); counted as one at a time it would say 3 s.
  std::ostringstream out;
  const int saved = softarm::fem::thread_count();
  softarm::fem::set_thread_count(2);
  const softarm::fem::TaskProgress progress = softarm::studies::task_progress(out, "cells");
  softarm::fem::parallel_tasks(4, [](int) { std::this_thread::sleep_for(std::chrono::milliseconds(1000)); }, progress);
  softarm::fem::set_thread_count(saved);
  const auto lines = lines_of(out.str());
  INFO(out.str());
  REQUIRE(lines.size() == 4);
  CHECK(lines[0].find("] 1/4  1 s, ETA 2 s") != std::string::npos);
}

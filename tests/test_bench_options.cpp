// Every benchmark reads its command line through CLI11 (benchmarks/bench_options.hpp, issue 35):
// --help exits 0; a bad option, or a config that cannot be read, exits 2 with its message before
// any run, never an abort. Each binary is run as a user runs it; none gets far enough to work.
#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "support/text_file.hpp"

namespace {

struct Run {
  int exit_code;  // or 128 + the signal that killed it
  std::string output;
};

/// `binary args > log 2>&1`.
Run run(const std::string& binary, const std::string& args) {
  static int calls = 0;  // one log per call and process: ctest -j runs tests side by side
  const auto log = std::filesystem::temp_directory_path() /
                   ("softarm_bench_options_" + std::to_string(::getpid()) + "_" + std::to_string(++calls) + ".txt");
  const int status = std::system((binary + " " + args + " > " + log.string() + " 2>&1").c_str());
  Run r{WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), softarm::test::read_text(log)};
  std::filesystem::remove(log);
  return r;
}

/// The benchmarks' binaries: every benchmarks/bench_*.cpp (tests/CMakeLists.txt).
std::vector<std::string> benchmarks() {
  std::vector<std::string> all;
  std::stringstream list(SOFTARM_BENCHMARKS);
  for (std::string file; std::getline(list, file, ',');) all.push_back(file);
  return all;
}

}  // namespace

TEST_CASE("every benchmark: --help exits 0 and a bad option or unreadable config exits 2 before any run",
          "[cli][bench-options]") {
  const auto all = benchmarks();
  REQUIRE(all.size() >= 13);
  for (const std::string& binary : all) {
    INFO(binary);
    const Run help = run(binary, "--help");
    CHECK(help.exit_code == 0);
    CHECK(help.output.find("--help") != std::string::npos);

    const Run bogus = run(binary, "--bogus-option");
    CHECK(bogus.exit_code == 2);
    CHECK(bogus.output.find("--bogus-option") != std::string::npos);  // CLI11's message names it
    CHECK(bogus.output.find("terminate called") == std::string::npos);

    if (help.output.find("Positionals:") != std::string::npos) {  // a config file as its argument
      const Run missing = run(binary, "/nonexistent/softarm_bench_config.json");
      CHECK(missing.exit_code == 2);
      CHECK(missing.output.find("cannot open file '/nonexistent/softarm_bench_config.json'") != std::string::npos);
      CHECK(missing.output.find("terminate called") == std::string::npos);
    }
  }
}

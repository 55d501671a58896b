#pragma once
// The benchmarks' command lines, read through CLI11 (issue 35: bad input never crashes, and is
// refused before any run). Each benchmark declares its options on a CLI::App and calls
// parse_or_exit first thing: --help prints them with their defaults and exits 0; an unknown
// option, a missing value, or a value that is not a number or out of range is refused with
// CLI11's message and exit code 2 before any work starts. A config that cannot be read
// (fem::InputError from fem::load_json_file, load_scene_config, read_design_config) is caught by
// each main's function-try-block: its message on stderr and exit 2, not an abort.
// tests/test_bench_options.cpp runs every benchmark with --help, with a bad option and, where it
// takes a config, with one that is not there.
#include <CLI/CLI.hpp>

#include "fem/core/allocator.hpp"

#include <cmath>
#include <optional>
#include <string>

namespace softarm::bench {

/// A finite number (CLI::Range and CLI::PositiveNumber let NaN through).
inline const CLI::Validator Finite(
    [](std::string& text) {
      double v = 0;
      if (CLI::detail::lexical_cast(text, v) && std::isfinite(v)) return std::string();
      return "Value " + text + " is not a finite number";
    },
    "FINITE");

/// A finite number above 0: pressures, lengths, radii, tolerances, factors.
inline const CLI::Validator Positive(
    [](std::string& text) {
      double v = 0;
      if (CLI::detail::lexical_cast(text, v) && std::isfinite(v) && v > 0) return std::string();
      return "Value " + text + " is not a finite number above 0";
    },
    "POSITIVE");

/// Reads the command line. Nothing: go on with the run; else main's exit code: 0 after --help,
/// 2 after a bad option (CLI11's message printed). --help shows each option's default: the value
/// bound before parsing, or the words an option gave with ->default_str("the config's").
/// A run that goes on gets the process settings of softarm's own main (engine/main.cpp), so that
/// a benchmark times what the program runs: without them each 3D Newton iteration's large arrays
/// fault in afresh (fem/core/allocator.hpp; docs/performance.md, The processes the tests and
/// benchmarks run in).
inline std::optional<int> parse_or_exit(CLI::App& app, int argc, char** argv) {
  for (CLI::Option* option : app.get_options())
    if (option->get_type_size() != 0 && option->get_default_str().empty()) option->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  fem::restart_with_huge_pages(argv);
  fem::keep_freed_memory_mapped();
  return std::nullopt;
}

}  // namespace softarm::bench

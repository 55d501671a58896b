#pragma once
// Checks for command-line options shared by the subcommands: a folder of its own, which the
// subcommands' folders (engine/workspace) and engine/cli.cpp both use.
#include <CLI/CLI.hpp>
#include <string>

namespace softarm::engine {

/// A number option that must be finite and within [lo, hi] (CLI::Range lets NaN through: every
/// comparison with it is false); the message names the value, the range and `unit`.
CLI::Validator finite_in(double lo, double hi, const std::string& unit);

}  // namespace softarm::engine

#pragma once
// Tests that run an external tool (CalculiX's ccx, headless Chromium, Open MPI's mpirun) skip when
// it is missing, with a message that says which and how to install it. The message carries the
// marker ctest's SKIP_REGULAR_EXPRESSION looks for (tests/CMakeLists.txt), so ctest counts the test
// as skipped, not passed; run directly, Catch prints it as a warning. scripts/setup.sh installs every
// tool, so CI and the README's test command run every test.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <string>

namespace softarm::test {

/// The marker of a skipped test in its output.
inline constexpr const char* kSkippedMarker = "SOFTARM-TEST-SKIPPED";

/// True (after a warning with the marker) when `what` is not available; the test then returns.
inline bool skip_without(bool available, const std::string& what, const std::string& how) {
  if (available) return false;
  WARN(kSkippedMarker << ": " << what << " is not available (" << how << "): this test did not run");
  return true;
}

/// True when `command` is on PATH.
inline bool on_path(const std::string& command) {
  return std::system(("command -v " + command + " > /dev/null 2>&1").c_str()) == 0;
}

/// skip_without for a command on PATH: `what` names its Debian package.
inline bool skip_without_command(const std::string& command, const std::string& what) {
  return skip_without(on_path(command), what + " (" + command + " on PATH)", "scripts/setup.sh installs it");
}

}  // namespace softarm::test

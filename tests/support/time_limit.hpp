#pragma once
// Wall-clock limits that tests put on the commands they start (`timeout N mpirun …`), scaled by
// SOFTARM_TEST_TIME_SCALE (default 1): under the sanitizers (scripts/sanitize.sh sets it) the same
// work takes several times longer, and a limit sized for build/ would fail a test that is correct.
#include <cstdlib>
#include <string>

namespace softarm::test {

inline int scaled_seconds(int seconds) {
  const char* scale = std::getenv("SOFTARM_TEST_TIME_SCALE");
  const double s = scale ? std::atof(scale) : 1.0;
  return s > 1.0 ? static_cast<int>(seconds * s) : seconds;
}

/// "timeout -k 5 N mpirun … -np 2 ": two ranks on one machine, stopped after N (scaled) seconds.
inline std::string mpirun_two_ranks(int seconds) {
  return "timeout -k 5 " + std::to_string(scaled_seconds(seconds)) +
         " mpirun --allow-run-as-root --oversubscribe -np 2 ";
}

}  // namespace softarm::test

#pragma once
// Summaries the benchmarks print: this machine is shared and noisy, so runs are repeated and the
// median is quoted.
#include <algorithm>
#include <chrono>
#include <vector>

namespace softarm::bench {

/// The middle value (the mean of the two middle ones for an even count); 0 for none.
inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

/// Wall-clock seconds since `start` (the steady clock: a benchmark's intervals, not dates).
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace softarm::bench

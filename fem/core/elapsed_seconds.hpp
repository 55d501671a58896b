#pragma once
// Adds the seconds from its construction to its end of scope to a running total, on every exit path
// (the cost counters the benchmarks print).
#include <chrono>

namespace softarm::fem {

struct AddElapsedSeconds {
  explicit AddElapsedSeconds(double& total) : total_(total) {}
  AddElapsedSeconds(const AddElapsedSeconds&) = delete;
  AddElapsedSeconds& operator=(const AddElapsedSeconds&) = delete;
  ~AddElapsedSeconds() { total_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count(); }

 private:
  const std::chrono::steady_clock::time_point t0_ = std::chrono::steady_clock::now();
  double& total_;
};

}  // namespace softarm::fem

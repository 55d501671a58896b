#pragma once
// Runs study points in child processes, up to `jobs` at a time. A point's
// solver gets a process of its own: a crash (a signal inside a linear-algebra
// library) or a hang becomes that point's recorded failure instead of the
// study's end, and the points share no global state (thread counts, BLAS).
// Children die with their parent (PR_SET_PDEATHSIG), so a killed study leaves
// no stray solvers behind.
#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <sys/types.h>

namespace softarm::studies {

class ProcessPool {
 public:
  struct Finished {
    int task = 0;
    bool ok = false;       // the child wrote its output and exited 0
    std::string output;    // what the work returned (ok)
    std::string failure;   // why not (crash signal, exit code, time-out)
    double seconds = 0;
  };

  /// `scratch`: a directory for the children's outputs (created).
  ProcessPool(int jobs, double timeout_s, std::filesystem::path scratch);
  ~ProcessPool();  // kills running children
  ProcessPool(const ProcessPool&) = delete;
  ProcessPool& operator=(const ProcessPool&) = delete;

  bool has_free_slot() const { return static_cast<int>(running_.size()) < jobs_; }
  bool idle() const { return running_.empty(); }
  /// Forks a child that runs `work` and hands its string back.
  void start(int task, const std::function<std::string()>& work);
  /// Children that ended since the last call (never blocks); kills those past the time-out.
  std::vector<Finished> collect();

 private:
  struct Child {
    pid_t pid;
    int task;
    std::chrono::steady_clock::time_point started;
  };
  int jobs_;
  double timeout_s_;
  std::filesystem::path scratch_;
  std::vector<Child> running_;
  std::filesystem::path output_file(pid_t pid) const;
};

}  // namespace softarm::studies

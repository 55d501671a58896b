#pragma once
// "ring_count [#########-----------]  12/30  (1 failed)  41 s, ETA 62 s":
// redrawn in place on a terminal, one line per finished point otherwise (logs, CI).
// The ETA is the wall time per point finished in this run (parallel runs
// included) times the points left; while fewer points have finished than run
// side by side (`concurrency`), those in flight are taken to finish with them
// (so that the first of two cells on two threads does not double the ETA).
#include <chrono>
#include <iosfwd>
#include <string>

#include "fem/core/parallel.hpp"

namespace softarm::studies {

class ProgressBar {
 public:
  /// `start`: when the work began (the elapsed time and the ETA count from it); `concurrency`: the
  /// points run side by side.
  ProgressBar(std::ostream& out, std::string name, int total, int already_done,
              std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now(), int concurrency = 1);
  /// One more point finished (`failed`: not status ok); `what`: a short note for line mode.
  void advance(bool failed, const std::string& what);
  void finish();

 private:
  std::ostream& out_;
  std::string name_;
  int total_, done_, done_here_ = 0, failed_ = 0, concurrency_;
  bool terminal_;
  std::chrono::steady_clock::time_point start_;
  void draw(const std::string& what);
};

/// A fem::TaskProgress that draws a ProgressBar named `name` on `out` (e.g. a run's cells): one
/// line per finished task in a log, one line redrawn in place on a terminal; the tasks run
/// fem::thread_count() at a time.
fem::TaskProgress task_progress(std::ostream& out, std::string name);

}  // namespace softarm::studies

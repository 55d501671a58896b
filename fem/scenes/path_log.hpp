#pragma once
// A pressure path's converged states, kept on disk as they come, so that a run
// killed after hours (the SPL's 3D reference: 23 load steps in 96 minutes)
// resumes from its last converged step instead of from rest. Append-only, one
// record a converged state, each with its own checksum: a record torn by a kill
// is dropped with whatever follows it, never read as a state. The file's header
// holds the caller's fingerprint of the model and the number of unknowns; a
// file of another model is not resumed but started over.
//
// Every state is kept whole (x and its PressureState), not just the last:
// a resumed run hands the earlier ones to its callbacks again, so everything
// derived from them (a 3CA's bending at every step, the curve, the reports)
// is rebuilt exactly as the uninterrupted run built it. The thesis SPL at
// level 3's layers keeps 6.1 MB a state, ~150 MB for its path.
#include <cstdint>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "fem/scenes/pressure_state.hpp"
#include "fem/solver/load_stepper.hpp"

namespace softarm::fem {

struct PathLogRecord {
  double level = 0;           // load level λ of the state
  double next_increment = 0;  // the step controller's Δλ after it
  PressureState state;
  PathStatistics stats;       // of the path up to this state (failed_levels not kept)
  Vector x;
};

class PathLog {
 public:
  /// Opens the log at `file` for a model with `dofs` unknowns named by `fingerprint`. The
  /// records of an earlier run of the same model are read (up to the first torn one); a
  /// missing, empty or unreadable file, or one of another model, leaves none and is started anew.
  /// Throws std::runtime_error where the file cannot be written.
  PathLog(std::string file, std::string fingerprint, Eigen::Index dofs);

  const std::vector<PathLogRecord>& resumed() const { return resumed_; }
  /// The earlier run's records, moved out of the log (which then holds none).
  std::vector<PathLogRecord> take_resumed() {
    std::vector<PathLogRecord> records = std::move(resumed_);
    resumed_.clear();
    return records;
  }
  /// Why nothing was resumed from an existing file ("" when something was, or there was no file).
  const std::string& discarded_reason() const { return discarded_reason_; }
  const std::string& file() const { return file_; }

  /// Appends a record and flushes it to the file.
  void append(const PathLogRecord& record);

 private:
  std::string file_, fingerprint_;
  Eigen::Index dofs_ = 0;
  std::vector<PathLogRecord> resumed_;
  std::string discarded_reason_;
  std::ofstream out_;
};

}  // namespace softarm::fem

#pragma once
// Runs a study: the points not yet in the results file, in parallel child
// processes (ProcessPool) on this machine and, under mpirun, on every rank
// (Cluster); each result is appended to <dir>/results.jsonl the moment it
// arrives (ResultsStore), so a killed study resumes where it stopped and a
// failed point is a record with its diagnosis, never the end of the study.
#include <filesystem>
#include <iosfwd>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "studies/study_spec.hpp"

namespace softarm::studies {

struct RunOptions {
  int jobs = 1;               // points solved at once on this machine (per rank)
  bool fresh = false;         // discard earlier results
  bool retry_failed = false;  // recompute points recorded as failed
  std::ostream* progress = nullptr;  // progress bar (rank 0 only); null: silent
};

struct RunSummary {
  int total = 0, already_done = 0, computed = 0, failed = 0;
  double seconds = 0;
  std::map<std::string, nlohmann::json> records;  // every point's record by key (rank 0)
};

/// Runs (or resumes) the study with results under `directory`. On every rank;
/// only rank 0's summary holds the records.
RunSummary run_study(const StudySpec& spec, const std::filesystem::path& directory, const RunOptions& options);

}  // namespace softarm::studies

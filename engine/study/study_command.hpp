#pragma once
// `softarm study <config.json | directory>… [-o DIR] [--jobs N] [--fresh]
// [--retry-failed] [--report-only]`: runs each study config (a directory
// means every *.json in it), resuming from DIR/<study>/results.jsonl, then
// writes each study's report and DIR/index.html. Under `mpirun -np N` every
// rank takes a share of the points; rank 0 writes the files.
#include <string>
#include <vector>

namespace softarm::engine {

struct StudyOptions {
  std::vector<std::string> configs;
  std::string output_root = "out/studies";
  int jobs = 0;  // 0: every core of this machine (1 per rank under mpirun)
  bool fresh = false, retry_failed = false, report_only = false;
};

/// Returns the process exit code (0: every study ran; its points may have failed, as reported).
int run_study_command(const StudyOptions& options);

}  // namespace softarm::engine

#pragma once
// `softarm design <requirements.json>`: the main job. Evaluates the thesis
// design, searches the design space with the configured optimiser on the
// reduced model (printing every evaluation and appending it to history.csv as
// it goes), checks one segment of the optimum by the 3D FEM and, while that
// check finds a requirement not met, corrects the search model by it and
// searches again (check.corrections; solid_correction.hpp), re-checks the
// final optimum at the check fidelity, prints the optimal parameters and every
// constraint's margin, and writes report.html (SVG plots), summary.json and the
// optimum's payload pose as VTU. A rerun resumes from the checkpoint of a
// stopped one (design_checkpoint.hpp).
#include <string>

namespace softarm::engine {

/// Command-line overrides of the config (empty / 0: keep the config's).
struct DesignOverrides {
  std::string output_directory, algorithm;
  int max_evaluations = 0;
  std::string fidelity;  // "fast": the search model alone (no verification, no 3D check); "" or "accurate": the config's
  bool fresh = false;  // discard the checkpoint of an earlier run instead of resuming (design_checkpoint.hpp)
};

/// Returns the process exit code (0: a design was returned, feasible or not, as printed).
int run_design(const std::string& config_file, const DesignOverrides& overrides);

}  // namespace softarm::engine

#pragma once
// `softarm design` resumes where it stopped. Every evaluation of the search
// model (the design vector, its objective and uncorrected constraints, or why
// it could not be built) and every 3D check go to DIR/checkpoint.jsonl as they
// finish (studies::ResultsStore: one JSON line each, on disk before the run goes
// on; a line torn by a kill is dropped). A rerun with the same requirements,
// model, check and criteria replays them instead of computing them: the
// optimiser sees the same numbers, so it retraces its path in seconds up to
// where the run stopped, and a 3D check already made (minutes) is read back.
// The optimiser and output settings are not in the fingerprint, so another
// algorithm or budget reuses the evaluations; `--fresh` discards them (and
// should, after softarm itself changed: the fingerprint is the config's).
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "engine/optimiser/optimiser.hpp"
#include "objectives/cell_rod_evaluation.hpp"
#include "objectives/solid_segment_check.hpp"
#include "studies/results_store.hpp"

namespace softarm::engine {

class DesignCheckpoint {
 public:
  /// Opens (or starts) DIR/checkpoint.jsonl for a run whose evaluations depend on
  /// `config_document` minus its "optimiser" and "output" objects. Throws
  /// std::runtime_error when the file belongs to another configuration.
  DesignCheckpoint(const std::filesystem::path& directory, nlohmann::json config_document, bool fresh);

  /// These two may be called from several threads at once (the search's concurrent evaluations).
  std::optional<optimise::Evaluation> evaluation(const std::vector<double>& x) const;
  void add(const std::vector<double>& x, const optimise::Evaluation& e);
  std::optional<objectives::SolidSegmentCheck> solid_check(const std::vector<double>& x) const;
  void add(const std::vector<double>& x, const objectives::SolidSegmentCheck& check);

  std::optional<objectives::CellRodEvaluation> verification(const std::vector<double>& x) const;
  void add(const std::vector<double>& x, const objectives::CellRodEvaluation& verification);

  /// Records found on opening: evaluations, 3D checks and verifications on the cell rod.
  int resumed_evaluations() const { return resumed_evaluations_; }
  int resumed_solid_checks() const { return resumed_solid_checks_; }
  int resumed_verifications() const { return resumed_verifications_; }
  const std::filesystem::path& file() const { return store_.file(); }

 private:
  studies::ResultsStore store_;
  mutable std::mutex mutex_;  ///< guards store_ against concurrent evaluations
  int resumed_evaluations_ = 0, resumed_solid_checks_ = 0, resumed_verifications_ = 0;
};

}  // namespace softarm::engine

#pragma once
// The study's results on disk: one JSON object per line (JSON Lines), appended
// and flushed to the disk as each point finishes, so a study killed at any
// moment loses at most the points that were running. The first line is a
// header with the study's fingerprint: a rerun resumes only results of the
// same scene, model and parameters, and refuses to mix in others.
//
// A line cut short by a kill (no newline, or not valid JSON) is dropped when
// the file is opened again, and the file is truncated to its last complete
// line before anything is appended.
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

namespace softarm::studies {

/// The fingerprint of everything that changes a result's numbers: FNV-1a of its canonical JSON.
std::string fingerprint_of(const nlohmann::json& what);

class ResultsStore {
 public:
  /// Opens (or creates) `file` for a study with `fingerprint`; `fresh` discards
  /// earlier results. Throws std::runtime_error when the file belongs to another
  /// study config.
  ResultsStore(std::filesystem::path file, const std::string& study, const std::string& fingerprint, bool fresh);

  /// Finished points by key (the last record of a key wins; failed ones included).
  const std::map<std::string, nlohmann::json>& records() const { return records_; }
  bool finished(const std::string& key) const { return records_.count(key) > 0; }
  /// Appends one record (it must hold "key") and makes it durable.
  void append(const nlohmann::json& record);
  /// Lines dropped on opening (torn by a kill).
  int dropped_lines() const { return dropped_; }
  const std::filesystem::path& file() const { return file_; }

 private:
  std::filesystem::path file_;
  std::map<std::string, nlohmann::json> records_;
  int dropped_ = 0;
};

}  // namespace softarm::studies

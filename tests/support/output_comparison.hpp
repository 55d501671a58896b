// Two runs' result directories compared number by number (tests/tools/compare_outputs.cpp and
// scripts/compare_revisions.sh): the check that a change of code leaves every printed result as it
// was, or says where it does not.
//
// Every text file of the first directory is compared with the file of the same relative path in
// the second: JSON and JSON-lines value by value (keys must match), CSV field by field as RFC 4180
// reads it, any other text (VTU, HTML, .inp) token by token. Numbers are equal when
// |a - b| <= atol + rtol * max(|a|, |b|) (two NaN are equal); text must match exactly. Times are
// not results: a JSON key or CSV column named "seconds", "*_seconds" or "*_s" (the project's unit
// suffix for seconds), and a number written as a duration in prose ("total 66.5 s"), are skipped.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace softarm::test {

struct ComparisonTolerance {
  double relative = 1e-6;
  double absolute = 1e-12;
};

struct OutputDifference {
  std::string file;   // relative to the directories compared
  std::string where;  // a JSON pointer, "record 3, column extension_mm", or "token 120"
  std::string first, second;
};

struct OutputComparison {
  std::vector<OutputDifference> differences;
  int files_compared = 0;
  long numbers_compared = 0;
  double largest_relative_difference = 0;  // over the numbers compared, those within tolerance included
};

/// Compares every text file under `first` with its namesake under `second` (and notes files found in
/// only one of them).
OutputComparison compare_output_directories(const std::filesystem::path& first, const std::filesystem::path& second,
                                            const ComparisonTolerance& tolerance);

/// True for a key or column that holds a time in seconds: "seconds" one of its words (split at "_"), or "*_s".
bool is_time_name(const std::string& name);

}  // namespace softarm::test

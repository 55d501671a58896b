#pragma once
// The design-rule report of a study (issue 5): report.html (plots in the
// thesis' form, the table of values, the rule in words, the chosen value beside
// the thesis' choice, deformed shapes of the chosen points), results.csv and
// summary.json in the study's directory; and index.html over every study in
// the output root.
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "studies/study_points.hpp"
#include "studies/study_spec.hpp"

namespace softarm::engine {

/// Writes the study's files into `directory`; returns its summary (also summary.json).
nlohmann::json write_study_report(const studies::StudySpec& spec, const std::vector<studies::StudyPoint>& points,
                                  const std::map<std::string, nlohmann::json>& records,
                                  const std::filesystem::path& directory);

/// index.html in `root` over every <root>/<study>/summary.json.
void write_study_index(const std::filesystem::path& root);

}  // namespace softarm::engine

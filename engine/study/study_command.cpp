#include "engine/study/study_command.hpp"

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <thread>

#include "engine/report/output_files.hpp"
#include "engine/study/study_report.hpp"
#include "fem/core/input_error.hpp"
#include "studies/cluster.hpp"
#include "studies/design_rule.hpp"
#include "studies/results_store.hpp"
#include "studies/study_points.hpp"
#include "studies/study_runner.hpp"

namespace softarm::engine {

namespace {

std::vector<std::string> expand(const std::vector<std::string>& configs) {
  std::vector<std::string> files;
  for (const auto& c : configs) {
    if (std::filesystem::is_directory(c)) {
      std::vector<std::string> in_dir;
      for (const auto& e : std::filesystem::directory_iterator(c))
        if (e.path().extension() == ".json") in_dir.push_back(e.path().string());
      std::sort(in_dir.begin(), in_dir.end());
      if (in_dir.empty()) throw fem::InputError(c, "directory holds no *.json study config");
      files.insert(files.end(), in_dir.begin(), in_dir.end());
    } else {
      files.push_back(c);
    }
  }
  return files;
}

/// Reads every config first, so a typo in the last one stops the run before hours of work.
std::vector<studies::StudySpec> read_all(const std::vector<std::string>& files) {
  std::vector<studies::StudySpec> specs;
  for (const auto& f : files) {
    try {
      specs.push_back(studies::load_study(f));
      // A sweep value the scene cannot take (unknown section, taper ratio > 1, a value out of its range).
      studies::check_points(specs.back(), studies::study_points(specs.back()));
    } catch (const fem::InputError& e) {
      throw fem::InputError(e.field(), e.message() + " (in " + f + ")");
    }
    for (std::size_t i = 0; i + 1 < specs.size(); ++i)
      if (specs[i].name == specs.back().name)
        throw fem::InputError("study", "name '" + specs.back().name + "' is used by " + files[i] + " and " + f);
  }
  return specs;
}

}  // namespace

int run_study_command(const StudyOptions& options) {
  const auto specs = read_all(expand(options.configs));
  const studies::Cluster& cluster = studies::Cluster::instance();
  const int jobs = options.jobs > 0 ? options.jobs
                   : cluster.size() > 1 ? 1
                                        : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const std::filesystem::path root = options.output_root;
  if (cluster.root()) prepare_output_directory(root.string(), "-o/--output");
  if (cluster.root())
    std::cout << "softarm study: " << specs.size() << " stud" << (specs.size() == 1 ? "y" : "ies") << ", "
              << cluster.size() << " rank" << (cluster.size() == 1 ? "" : "s") << " × " << jobs
              << " point(s) at a time, results under " << root.string() << "\n";
  for (const auto& spec : specs) {
    const auto directory = root / spec.name;
    const auto points = studies::study_points(spec);
    std::map<std::string, nlohmann::json> records;
    if (options.report_only) {
      if (cluster.root())
        records = studies::ResultsStore(directory / "results.jsonl", spec.name, spec.fingerprint, false).records();
    } else {
      studies::RunOptions run;
      run.jobs = jobs;
      run.fresh = options.fresh;
      run.retry_failed = options.retry_failed;
      run.progress = &std::cerr;
      const studies::RunSummary s = studies::run_study(spec, directory, run);
      records = s.records;
      if (cluster.root())
        std::cout << spec.name << ": " << s.total << " points, " << s.already_done << " from earlier runs, "
                  << s.computed << " computed (" << s.failed << " failed) in " << static_cast<int>(s.seconds + 0.5)
                  << " s\n";
    }
    if (!cluster.root()) continue;
    const nlohmann::json summary = write_study_report(spec, points, records, directory);
    for (const auto& words : summary["rule_words"]) std::cout << "  " << words.get<std::string>() << "\n";
    std::cout << "  " << summary["comparison"].get<std::string>() << "\n  report: " << (directory / "report.html").string()
              << "\n";
  }
  if (cluster.root()) {
    write_study_index(root);
    std::cout << "index: " << (root / "index.html").string() << "\n";
  }
  return 0;
}

}  // namespace softarm::engine

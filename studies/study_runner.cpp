#include "studies/study_runner.hpp"

#include <chrono>
#include <iostream>
#include <thread>

#include "fem/core/parallel.hpp"
#include "studies/cluster.hpp"
#include "studies/point_evaluation.hpp"
#include "studies/process_pool.hpp"
#include "studies/progress_bar.hpp"
#include "studies/results_store.hpp"
#include "studies/study_points.hpp"

namespace softarm::studies {
using nlohmann::json;

namespace {

bool is_failure(const json& record) { return record.value("status", std::string()) != "ok"; }

std::string short_note(const json& record, const StudyPoint& point) {
  std::string note = point.key + " " + record.value("status", std::string("?"));
  if (record.contains("seconds")) note += " in " + std::to_string(static_cast<int>(record["seconds"].get<double>() + 0.5)) + " s";
  return note;
}

/// A child's output as a record; a crash or time-out as a failed one.
json record_of(const ProcessPool::Finished& f, const StudyPoint& point) {
  if (f.ok) {
    json record = json::parse(f.output, nullptr, false);
    if (!record.is_discarded()) return record;
  }
  return {{"status", "failed"}, {"diagnosis", f.ok ? "unreadable result" : f.failure}, {"index", point.index},
          {"key", point.key}, {"seconds", f.seconds}};
}

}  // namespace

RunSummary run_study(const StudySpec& spec, const std::filesystem::path& directory, const RunOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const Cluster& cluster = Cluster::instance();
  const std::vector<StudyPoint> points = study_points(spec);
  RunSummary summary;
  summary.total = static_cast<int>(points.size());

  // Rank 0 owns the results file and decides what is left to do.
  std::unique_ptr<ResultsStore> store;
  std::vector<int> pending;
  std::string error;
  if (cluster.root()) {
    try {
      store = std::make_unique<ResultsStore>(directory / "results.jsonl", spec.name, spec.fingerprint, options.fresh);
      for (const StudyPoint& p : points) {
        const auto it = store->records().find(p.key);
        const bool done = it != store->records().end() && !(options.retry_failed && is_failure(it->second));
        if (!done) pending.push_back(p.index);
      }
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  error = cluster.broadcast(error);
  if (!error.empty()) throw std::runtime_error(error);
  pending = cluster.broadcast(pending);
  summary.already_done = summary.total - static_cast<int>(pending.size());

  // This rank's share: every size-th pending point.
  std::vector<int> mine;
  for (std::size_t i = cluster.rank(); i < pending.size(); i += cluster.size()) mine.push_back(pending[i]);

  // One assembly thread per point when several points run at once on this machine.
  if (options.jobs > 1 || cluster.size() > 1) fem::set_thread_count(1);
  ProcessPool pool(options.jobs, spec.point_timeout_s,
                   directory / (".running-rank" + std::to_string(cluster.rank())));
  std::unique_ptr<ProgressBar> bar;
  if (cluster.root() && options.progress)
    bar = std::make_unique<ProgressBar>(*options.progress, spec.name, summary.total, summary.already_done);

  const auto take = [&](const json& record) {  // rank 0: a finished point from anywhere
    store->append(record);
    ++summary.computed;
    const bool failed = is_failure(record);
    if (failed) ++summary.failed;
    if (bar) bar->advance(failed, short_note(record, points.at(record.at("index").get<int>())));
  };

  std::size_t next = 0;
  int ranks_running = cluster.size() - 1;
  // A rank with no share (nothing left on a resume, more ranks than points) skips the loop, but still says done.
  while (next < mine.size() || !pool.idle() || (cluster.root() && ranks_running > 0)) {
    while (next < mine.size() && pool.has_free_slot()) {
      const StudyPoint& p = points[mine[next++]];
      pool.start(p.index, [&spec, &p] { return evaluate_point(spec, p).dump(); });
    }
    bool progressed = false;
    for (const auto& f : pool.collect()) {
      progressed = true;
      const json record = record_of(f, points[f.task]);
      if (cluster.root()) take(record);
      else cluster.send_result(record.dump());
    }
    if (cluster.root())
      while (const auto message = cluster.poll()) {
        progressed = true;
        if (message->done) --ranks_running;
        else take(json::parse(message->line));
      }
    if (!progressed) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (!cluster.root()) cluster.send_done();
  if (bar) bar->finish();
  std::filesystem::remove_all(directory / (".running-rank" + std::to_string(cluster.rank())));
  cluster.barrier();
  if (cluster.root()) summary.records = store->records();
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return summary;
}

}  // namespace softarm::studies

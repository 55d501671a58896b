#include "engine/design/design_checkpoint.hpp"

#include <cmath>
#include <stdexcept>

#include "fem/core/input_error.hpp"

namespace softarm::engine {
namespace {
// A design's key: its values as JSON numbers, which print every double so that it reads back exactly.
std::string key(const char* kind, const std::vector<double>& x) { return std::string(kind) + " " + nlohmann::json(x).dump(); }

std::string fingerprint(nlohmann::json document) {
  document.erase("optimiser");
  document.erase("output");
  return studies::fingerprint_of(document);
}

const nlohmann::json* record(const studies::ResultsStore& store, const std::string& k) {
  const auto found = store.records().find(k);
  return found == store.records().end() ? nullptr : &found->second;
}

// The store, or the reason it cannot be resumed as a user's error (exit 2, naming what to change).
studies::ResultsStore open_store(const std::filesystem::path& directory, const nlohmann::json& document, bool fresh) {
  try {
    return studies::ResultsStore(directory / "checkpoint.jsonl", "design", fingerprint(document), fresh);
  } catch (const std::runtime_error& e) {
    throw fem::InputError("output.directory", e.what());
  }
}
}  // namespace

DesignCheckpoint::DesignCheckpoint(const std::filesystem::path& directory, nlohmann::json config_document, bool fresh)
    : store_(open_store(directory, config_document, fresh)) {
  for (const auto& [k, r] : store_.records()) {
    if (k.rfind("evaluation ", 0) == 0) ++resumed_evaluations_;
    if (k.rfind("solid_check ", 0) == 0) ++resumed_solid_checks_;
    if (k.rfind("verification ", 0) == 0) ++resumed_verifications_;
  }
}

std::optional<optimise::Evaluation> DesignCheckpoint::evaluation(const std::vector<double>& x) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  const nlohmann::json* r = record(store_, key("evaluation", x));
  if (!r) return std::nullopt;
  optimise::Evaluation e;
  e.ok = r->at("ok").get<bool>();
  e.failure_reason = r->at("failure").get<std::string>();
  e.objective = r->at("objective").get<double>();
  e.constraints = r->at("constraints").get<std::vector<double>>();
  return e;
}

void DesignCheckpoint::add(const std::vector<double>& x, const optimise::Evaluation& e) {
  // JSON has no NaN or infinity: such an evaluation is not kept (a rerun computes it again).
  bool finite = std::isfinite(e.objective);
  for (double g : e.constraints) finite = finite && std::isfinite(g);
  if (!finite) return;
  const std::lock_guard<std::mutex> lock(mutex_);
  store_.append({{"key", key("evaluation", x)},
                 {"ok", e.ok},
                 {"failure", e.failure_reason},
                 {"objective", e.objective},
                 {"constraints", e.constraints}});
}

std::optional<objectives::SolidSegmentCheck> DesignCheckpoint::solid_check(const std::vector<double>& x) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  const nlohmann::json* r = record(store_, key("solid_check", x));
  if (!r) return std::nullopt;
  return objectives::solid_check_from_json(r->at("check"));
}

void DesignCheckpoint::add(const std::vector<double>& x, const objectives::SolidSegmentCheck& check) {
  const std::lock_guard<std::mutex> lock(mutex_);
  store_.append({{"key", key("solid_check", x)}, {"check", objectives::to_json(check)}});
}

std::optional<objectives::CellRodEvaluation> DesignCheckpoint::verification(const std::vector<double>& x) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  const nlohmann::json* r = record(store_, key("verification", x));
  if (!r) return std::nullopt;
  return objectives::cell_rod_evaluation_from_json(r->at("verification"));
}

void DesignCheckpoint::add(const std::vector<double>& x, const objectives::CellRodEvaluation& verification) {
  const std::lock_guard<std::mutex> lock(mutex_);
  store_.append({{"key", key("verification", x)}, {"verification", objectives::to_json(verification)}});
}

}  // namespace softarm::engine

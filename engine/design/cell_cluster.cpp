#include "engine/design/cell_cluster.hpp"

#include <nlohmann/json.hpp>
#include <stdexcept>

#include "engine/design/design_problem.hpp"
#include "fem/core/parallel.hpp"
#include "studies/cluster.hpp"

namespace softarm::engine {
namespace {
using nlohmann::json;
const char* const kDone = "done";

studies::Cluster& cluster() { return studies::Cluster::instance(); }
}  // namespace

CellCluster::CellCluster() = default;

CellCluster::~CellCluster() {
  if (root()) finish();
}

bool CellCluster::root() const { return cluster().root(); }
int CellCluster::size() const { return cluster().size(); }

objectives::CellRodEvaluation CellCluster::evaluate(const DesignConfig& config, const std::vector<double>& x,
                                                    const fem::TaskProgress& progress) const {
  if (size() > 1) cluster().broadcast_idle(json(x).dump());  // exact: shortest round-trip doubles
  return evaluate_here(config, x, progress);
}

void CellCluster::finish() {
  if (finished_ || size() == 1) return;
  finished_ = true;
  cluster().broadcast_idle(std::string(kDone));
}

void CellCluster::serve(const DesignConfig& config) const {
  for (;;) {
    const std::string message = cluster().broadcast_idle(std::string());
    if (message == kDone) return;
    try {
      evaluate_here(config, json::parse(message).get<std::vector<double>>());
    } catch (const std::exception&) {
      // Rank 0 meets the same failure at the same point and reports it.
    }
  }
}

objectives::CellRodEvaluation CellCluster::evaluate_here(const DesignConfig& config, const std::vector<double>& x,
                                                         const fem::TaskProgress& progress) const {
  const int layers = config.cell_layers_level;
  const auto adjust = [layers](fem::TcaSceneSpec& s) {
    if (layers > 0) s.axial_level = layers;
  };
  // Over several ranks the cells are spread (spread()) and progress is not counted.
  return objectives::evaluate_arm_on_cells(make_candidate(config, x), config.check, config.cell_levels, adjust,
                                           spread(), progress);
}

// Rank r runs tasks r, r + N, r + 2N, … on its threads; each task's text (or its error) goes to every
// rank; a task that failed anywhere throws on every rank, so all stay in step.
fem::TaskSpread CellCluster::spread() const {
  if (size() == 1) return {};
  return [](int n, const std::function<std::string(int)>& task) {
    const studies::Cluster& c = cluster();
    std::vector<int> mine;
    for (int i = c.rank(); i < n; i += c.size()) mine.push_back(i);
    std::vector<std::string> text(mine.size()), error(mine.size());
    fem::parallel_tasks(static_cast<int>(mine.size()), [&](int k) {
      try {
        text[k] = task(mine[k]);
      } catch (const std::exception& e) {
        error[k] = std::string("cell job ") + std::to_string(mine[k]) + " on rank " + std::to_string(c.rank()) +
                   ": " + e.what();
      } catch (...) {
        error[k] = "cell job " + std::to_string(mine[k]) + " on rank " + std::to_string(c.rank()) + ": unknown error";
      }
    });
    json share = json::array();
    for (std::size_t k = 0; k < mine.size(); ++k) share.push_back({mine[k], text[k], error[k]});
    std::vector<std::string> results(static_cast<std::size_t>(n));
    std::string failure;
    for (const std::string& from_rank : c.all_gather(share.dump()))
      for (const json& entry : json::parse(from_rank)) {
        results.at(entry.at(0).get<std::size_t>()) = entry.at(1).get<std::string>();
        if (failure.empty()) failure = entry.at(2).get<std::string>();
      }
    if (!failure.empty()) throw std::runtime_error(failure);
    return results;
  };
}

}  // namespace softarm::engine

#include "engine/design/search_log.hpp"

#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "engine/design/design_problem.hpp"
#include "engine/report/output_files.hpp"

namespace softarm::engine {
namespace {
std::string fixed(double v, int digits) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}
}  // namespace

std::string SearchLog::variable_text(std::size_t i, double value) const {
  const optimise::Variable* v = i < variables_.size() ? &variables_[i] : nullptr;
  if (!v || v->kind != optimise::VariableKind::categorical) {
    std::ostringstream s;
    s << value;
    return s.str();
  }
  const auto choice = static_cast<std::size_t>(std::lround(value));  // a categorical's value is its choice's index
  return choice < v->choices.size() ? csv_text(v->choices[choice]) : csv_text("?");
}

SearchLog::SearchLog(const DesignConfig& config, double reference_strain, std::vector<HistoryPoint>& points)
    : csv_(open_output_file(config.output_directory, "history.csv")), points_(&points) {
  for (const auto& v : config.variables) variables_.push_back(v.variable);
  csv_ << "evaluation,phase,feasible,objective";
  for (const auto& n : constraints_of(config, {}, reference_strain).names) csv_ << ",g_" << n;
  for (const auto& v : config.variables) csv_ << "," << v.variable.name;
  csv_ << ",failure\n";
}

void SearchLog::next_round(int evaluations, const std::string& round_label) {
  evaluations_before_ += evaluations;
  round_ = round_label;
}

void SearchLog::record(const optimise::Progress& p, const std::vector<std::string>& constraint_names, double tolerance) {
  bool feasible = p.value.ok;
  double worst = -1e300;
  std::size_t binding = 0;
  for (std::size_t i = 0; i < p.value.constraints.size(); ++i) {
    feasible = feasible && p.value.constraints[i] <= tolerance;
    if (p.value.constraints[i] > worst) worst = p.value.constraints[i], binding = i;
  }
  const int n = evaluations_before_ + p.evaluation;
  const std::string phase = round_ + p.phase;
  points_->push_back({n, p.value.ok ? p.value.objective : std::nan(""), feasible, phase});
  std::cout << "eval " << std::setw(3) << n << " [" << phase << "] ";
  if (!p.value.ok) {
    std::cout << "failed: " << p.value.failure_reason << "\n";
  } else {
    std::cout << "objective " << fixed(p.value.objective, 4) << (feasible ? "  feasible" : "  infeasible")
              << "  (tightest: " << constraint_names[binding] << " " << fixed(-100 * worst, 1)
              << " %)  best feasible " << (std::isfinite(p.best_feasible_objective) ? fixed(p.best_feasible_objective, 4) : "none")
              << "\n";
  }
  csv_ << n << "," << csv_text(phase) << "," << feasible << "," << (p.value.ok ? p.value.objective : std::nan(""));
  for (std::size_t i = 0; i < constraint_names.size(); ++i)
    csv_ << "," << (i < p.value.constraints.size() ? p.value.constraints[i] : std::nan(""));
  for (std::size_t i = 0; i < p.x.size(); ++i) csv_ << "," << variable_text(i, p.x[i]);
  csv_ << "," << csv_text(p.value.failure_reason) << "\n";
  csv_.flush();
}

}  // namespace softarm::engine

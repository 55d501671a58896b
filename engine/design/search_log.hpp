#pragma once
// What `softarm design` records of its searches: history.csv, written and flushed at every
// evaluation so that a stopped run keeps what it computed; the console line of each evaluation;
// the points of the report's convergence plot. A check-and-correct run's searches share one log:
// their evaluations are numbered on, and each phase is prefixed by its round.
#include <fstream>
#include <string>
#include <vector>

#include "engine/design/design_config.hpp"
#include "engine/design/design_report.hpp"
#include "engine/optimiser/optimiser.hpp"

namespace softarm::engine {

class SearchLog {
 public:
  /// Opens history.csv in config.output_directory and writes its header.
  SearchLog(const DesignConfig& config, double reference_strain, std::vector<HistoryPoint>& points);
  /// One evaluation of the current search (`constraint_names` its problem's, `tolerance` its feasibility tolerance).
  void record(const optimise::Progress& p, const std::vector<std::string>& constraint_names, double tolerance);
  /// The current search has ended after `evaluations`; the next one is `round_label` ("correction 1: ").
  void next_round(int evaluations, const std::string& round_label);

 private:
  /// Variable i's value as a CSV field: a number, or a categorical variable's choice by name.
  std::string variable_text(std::size_t i, double value) const;

  std::ofstream csv_;
  std::vector<optimise::Variable> variables_;  // history.csv's columns after the constraints
  std::vector<HistoryPoint>* points_;
  int evaluations_before_ = 0;  // of earlier rounds
  std::string round_;           // "" for the first search
};

}  // namespace softarm::engine

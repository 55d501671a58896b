#pragma once
// Writes the RRA scene's results: the pressure–extension curve as CSV (row by
// row, as the solver lands on each output pressure, so an interrupted run
// keeps what it computed), a JSON summary, the deformed mesh as VTU, and the
// human-readable table on stdout.
#include <fstream>
#include <ostream>
#include <string>

#include "fem/scenes/scene_config.hpp"

namespace softarm::engine {

class RraCurveWriter {
 public:
  /// Opens <directory>/curve.csv and prints the table header to `out`.
  RraCurveWriter(const std::string& directory, std::ostream& out);
  void add(const fem::RraCurvePoint& point);

 private:
  std::ofstream csv_;
  std::ostream& out_;
};

/// Writes summary.json (and deformed.vtu when asked); prints the outcome.
nlohmann::json write_rra_summary(const fem::SceneConfig& config, const fem::RraResult& result, std::ostream& out);

}  // namespace softarm::engine

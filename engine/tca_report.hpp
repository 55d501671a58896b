#pragma once
// Writes the 3CA scene's results: the pressure–bending curve as CSV row by row
// (an interrupted run keeps what it computed), a JSON summary (model choice,
// mass, the pressure reaching the target angle, peaks per part, cost), the
// deformed mesh as VTU with part and chamber ids, and a table on stdout.
#include <fstream>
#include <ostream>
#include <string>

#include "fem/scenes/scene_config.hpp"

namespace softarm::engine {

class TcaCurveWriter {
 public:
  /// Opens <directory>/curve.csv and prints the table header to `out`.
  TcaCurveWriter(const std::string& directory, std::ostream& out);
  void add(const fem::TcaState& state);

 private:
  std::ofstream csv_;
  std::ostream& out_;
};

/// Writes summary.json (and deformed.vtu when asked); prints the outcome.
nlohmann::json write_tca_summary(const fem::SceneConfig& config, const fem::TcaResult& result, std::ostream& out);

}  // namespace softarm::engine

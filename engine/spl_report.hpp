#pragma once
// Writes the SPL scene's results: the tip's path as CSV row by row, a JSON
// summary with every joint's position and orientation, mass and peaks, the
// deformed mesh as VTU, and the joint table on stdout.
#include <fstream>
#include <ostream>
#include <string>

#include "fem/scenes/scene_config.hpp"

namespace softarm::engine {

class SplCurveWriter {
 public:
  /// `iterations`: what the last column counts ("newton" for the FEM and the spatial rod's shooting,
  /// "fixed_point" for the cell rod's shape–moment iterations).
  SplCurveWriter(const std::string& directory, std::ostream& out, const std::string& iterations = "newton");
  void add(const fem::SplState& state);

 private:
  std::ofstream csv_;
  std::ostream& out_;
};

/// Every joint's position and orientation, as JSON and as the table on stdout.
nlohmann::json joints_json(const std::vector<fem::SplJoint>& joints);
void print_joint_table(const std::vector<fem::SplJoint>& joints, std::ostream& out);

nlohmann::json write_spl_summary(const fem::SceneConfig& config, const fem::SplResult& result, std::ostream& out);

}  // namespace softarm::engine

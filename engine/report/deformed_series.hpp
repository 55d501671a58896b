#pragma once
// deformed.pvd: a path run's mesh at every curve state, for ParaView's time slider.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "fem/mesh/mesh.hpp"

namespace softarm::engine {

/// Writes frames/deformed_NNN.vtu (the mesh at positions[i], with its displacement and part ids)
/// and deformed.pvd, the collection that orders them by `times[i]` (ParaView's "time": the pressure
/// in kPa, or the SPL's load fraction), into `directory`. `positions[i]` is flat, mesh.dim per node. Returns ", <directory>/deformed.pvd" for
/// the console's "written:" line ("" when there is no frame).
std::string write_deformed_series(const std::string& directory, const fem::Mesh& mesh,
                                  const std::vector<Eigen::VectorXd>& positions, const std::vector<double>& times);

/// The pressures of a scene's curve states, in kPa: the frames' times.
template <class State>
std::vector<double> pressures_of(const std::vector<State>& curve) {
  std::vector<double> pressures;
  for (const State& s : curve) pressures.push_back(s.pressure_kPa);
  return pressures;
}

}  // namespace softarm::engine

#include "fem/scenes/solver_work.hpp"

#include <algorithm>

namespace softarm::fem {

void SolverWork::add(const PressurePathResult& path, int path_dofs, double path_seconds) {
  ++paths;
  dofs += path_dofs;
  newton_iterations += path.path.stats.newton_iterations;
  factorizations += path.factorizations;
  shifted_factorizations += path.shifted_factorizations;
  lu_fallbacks += path.lu_fallbacks;
  cg_iterations += path.cg_iterations;
  seconds += path_seconds;
  longest_seconds = std::max(longest_seconds, path_seconds);
}

void SolverWork::add(const SolverWork& other) {
  paths += other.paths;
  dofs += other.dofs;
  newton_iterations += other.newton_iterations;
  factorizations += other.factorizations;
  shifted_factorizations += other.shifted_factorizations;
  lu_fallbacks += other.lu_fallbacks;
  cg_iterations += other.cg_iterations;
  seconds += other.seconds;
  longest_seconds = std::max(longest_seconds, other.longest_seconds);
}

std::string solver_work_text(const SolverWork& w) {
  return std::to_string(w.newton_iterations) + " Newton iterations, " + std::to_string(w.factorizations) +
         " factorisations (+" + std::to_string(w.shifted_factorizations) + " shifted), " +
         std::to_string(w.lu_fallbacks) + " LUs, " + std::to_string(w.cg_iterations) + " CG iterations";
}

}  // namespace softarm::fem

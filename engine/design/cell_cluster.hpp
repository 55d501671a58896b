#pragma once
// `mpirun -np N softarm design …`: rank 0 runs the design (search, checkpoint, outputs); at each
// verification on the cell rod it names the design vector to the other ranks, every rank builds the
// same arm from it, and the arm's cells (a dozen independent 3D solves, fem/scenes/spl_cell_job.hpp)
// are spread over the N ranks, each running its share on its own threads (--threads). Every rank
// gets every cell back exactly (shortest round-trip text), so the answer is the serial one. The
// other ranks print and write nothing; they return when rank 0 finishes, however it ends.
// Started without mpirun there is one rank and the cells run on this process' threads.
#include <vector>

#include "engine/design/design_config.hpp"
#include "fem/scenes/spl_cell_job.hpp"
#include "objectives/cell_rod_evaluation.hpp"

namespace softarm::engine {

class CellCluster {
 public:
  CellCluster();
  ~CellCluster();  // rank 0: finish()
  CellCluster(const CellCluster&) = delete;
  CellCluster& operator=(const CellCluster&) = delete;

  bool root() const;
  int size() const;

  /// Rank 0: the accurate model's measures of design vector `x` (objectives/cell_rod_evaluation.hpp),
  /// its cells spread over every rank. Throws as evaluate_arm_on_cells does.
  /// `progress` is told as each of rank 0's cells ends.
  objectives::CellRodEvaluation evaluate(const DesignConfig& config, const std::vector<double>& x,
                                         const fem::TaskProgress& progress = {}) const;
  /// Rank 0: no more verifications; the other ranks return from serve(). Once; the destructor calls it.
  void finish();
  /// Ranks > 0: take part in every verification rank 0 runs, until it finishes.
  void serve(const DesignConfig& config) const;

 private:
  objectives::CellRodEvaluation evaluate_here(const DesignConfig& config, const std::vector<double>& x,
                                              const fem::TaskProgress& progress = {}) const;
  fem::TaskSpread spread() const;
  bool finished_ = false;
};

}  // namespace softarm::engine

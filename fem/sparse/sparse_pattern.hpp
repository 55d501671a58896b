#pragma once
// The sparsity pattern of the global tangent, built once per mesh, and the
// accumulator that scatters element blocks into it (PolyFEM/deal.II style:
// pattern and symbolic factorisation once, numeric work per iteration).
//
// Every form declares the dof blocks it couples; each block gets a table of
// positions in the compressed matrix, so scattering is a lookup, not a search.
// A block whose dofs come in runs of consecutive numbers (a node's x, y, z) keeps one
// position per run and column: the run's rows are consecutive in every column that
// holds them, so the run's entries are consecutive there too (a third of the table
// for a Hex20, and three contiguous additions per lookup).
// Threads accumulate into private value arrays that are summed at the end,
// so assembly needs no locks and is deterministic for a fixed thread count.
// Thread 0 accumulates straight into the result matrix, so a serial assembly
// allocates no value array beside it and needs no summation pass.
#include <Eigen/SparseCore>
#include <span>
#include <vector>

namespace softarm::fem {

using SparseMatrix = Eigen::SparseMatrix<double>;  // column-major, full symmetric storage

class SparsePattern {
 public:
  explicit SparsePattern(int num_dofs) : num_dofs_(num_dofs) {}

  /// Declares that all `dofs` couple with each other; returns the block's handle.
  int declare_block(std::span<const int> dofs);
  /// Builds the compressed matrix and the position tables. Call once, after all blocks.
  void finalize();

  int num_dofs() const { return num_dofs_; }
  bool finalized() const { return finalized_; }
  const SparseMatrix& zero_matrix() const { return matrix_; }
  int block_size(int block) const { return block_sizes_[block]; }
  /// The length of the block's runs of consecutive dofs (3, 2 or 1): its dofs d[r·w .. r·w + w − 1]
  /// are d[r·w] + 0, …, w − 1 for every run r.
  int run_length(int block) const { return run_lengths_[block]; }
  /// Position table of a block, column-major: entry (r, j), the first row of run r in column j, at
  /// j·(n / w) + r (n the block size, w its run length).
  const int* positions(int block) const { return positions_.data() + position_offsets_[block]; }
  /// Where entry (i, j) of the block (row d[i], column d[j]) is stored.
  int position(int block, int i, int j) const {
    const int w = run_lengths_[block], runs = block_sizes_[block] / w;
    return positions(block)[j * runs + i / w] + i % w;
  }

 private:
  int num_dofs_;
  bool finalized_ = false;
  std::vector<int> block_dofs_, block_offsets_{0}, block_sizes_, run_lengths_;
  std::vector<int> positions_;
  std::vector<std::size_t> position_offsets_;
  SparseMatrix matrix_;
};

class HessianAccumulator {
 public:
  explicit HessianAccumulator(const SparsePattern& pattern, int threads);
  /// Adds a dense n×n block (column-major, n = block size) for the declared block.
  void add_block(int thread, int block, const double* values);
  /// Sums the thread buffers into a matrix with the pattern's structure (once: the
  /// accumulated matrix is moved into `out`).
  void finish(SparseMatrix& out);

 private:
  const SparsePattern& pattern_;
  SparseMatrix result_;                       // thread 0's values
  std::vector<std::vector<double>> buffers_;  // threads 1, 2, ...
  std::vector<double*> values_;               // per thread: where its block values go
};

}  // namespace softarm::fem

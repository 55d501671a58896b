#include "fem/sparse/sparse_pattern.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace softarm::fem {
namespace {
/// The longest of 3, 2, 1 that cuts `dofs` into runs of consecutive numbers.
int consecutive_run_length(std::span<const int> dofs) {
  for (int w : {3, 2}) {
    if (dofs.size() % w != 0) continue;
    bool runs = true;
    for (std::size_t r = 0; runs && r < dofs.size(); r += w)
      for (int k = 1; k < w; ++k) runs = runs && dofs[r + k] == dofs[r] + k;
    if (runs) return w;
  }
  return 1;
}
}  // namespace

int SparsePattern::declare_block(std::span<const int> dofs) {
  if (finalized_) throw std::logic_error("SparsePattern: block declared after finalize()");
  block_dofs_.insert(block_dofs_.end(), dofs.begin(), dofs.end());
  block_offsets_.push_back(static_cast<int>(block_dofs_.size()));
  block_sizes_.push_back(static_cast<int>(dofs.size()));
  run_lengths_.push_back(consecutive_run_length(dofs));
  return static_cast<int>(block_sizes_.size()) - 1;
}

void SparsePattern::finalize() {
  // Column by column: the rows a column couples to are the dofs of the blocks it is in, each kept
  // once (a stamp per row, not a sort of every block's copy), then sorted; the position of each
  // block entry is read off a row → position table of its column, written once per column (one per
  // run of consecutive dofs: the run's rows follow each other in the column). Work and memory
  // O(Σ block size² + nnz), no search per entry.
  const std::size_t blocks = block_sizes_.size();
  // Incidence: for each dof, the (block, index within the block) pairs it appears as.
  std::vector<int> first(num_dofs_ + 1, 0);
  for (int d : block_dofs_) ++first[d + 1];
  for (int c = 0; c < num_dofs_; ++c) first[c + 1] += first[c];
  std::vector<int> fill(first.begin(), first.end() - 1);
  std::vector<std::pair<int, int>> incidence(block_dofs_.size());
  for (std::size_t b = 0; b < blocks; ++b)
    for (int j = 0; j < block_sizes_[b]; ++j)
      incidence[fill[block_dofs_[block_offsets_[b] + j]]++] = {static_cast<int>(b), j};

  position_offsets_.assign(blocks, 0);
  std::size_t total = 0;
  for (std::size_t b = 0; b < blocks; ++b) {
    position_offsets_[b] = total;
    total += static_cast<std::size_t>(block_sizes_[b]) * (block_sizes_[b] / run_lengths_[b]);
  }
  positions_.assign(total, 0);

  matrix_.resize(num_dofs_, num_dofs_);  // compressed, empty: its column starts are written below
  int* outer = matrix_.outerIndexPtr();
  std::vector<int> inner, stamp(num_dofs_, -1), where(num_dofs_, 0);
  for (int c = 0; c < num_dofs_; ++c) {
    const std::size_t column_start = inner.size();
    stamp[c] = c, inner.push_back(c);  // every diagonal is kept (constrained dofs)
    for (int k = first[c]; k < first[c + 1]; ++k) {
      const int b = incidence[k].first;
      const int* d = block_dofs_.data() + block_offsets_[b];
      for (int i = 0; i < block_sizes_[b]; ++i)
        if (stamp[d[i]] != c) stamp[d[i]] = c, inner.push_back(d[i]);
    }
    std::sort(inner.begin() + static_cast<std::ptrdiff_t>(column_start), inner.end());
    for (std::size_t k = column_start; k < inner.size(); ++k) where[inner[k]] = static_cast<int>(k);
    outer[c + 1] = static_cast<int>(inner.size());
    // Block b's run r in column d[j] starts at row d[r·w]: stored at (j·(n / w) + r), column-major.
    for (int k = first[c]; k < first[c + 1]; ++k) {
      const auto [b, j] = incidence[k];
      const int w = run_lengths_[b], runs = block_sizes_[b] / w;
      const int* d = block_dofs_.data() + block_offsets_[b];
      int* pos = positions_.data() + position_offsets_[b] + static_cast<std::size_t>(j) * runs;
      for (int r = 0; r < runs; ++r) pos[r] = where[d[r * w]];
    }
  }
  matrix_.resizeNonZeros(static_cast<Eigen::Index>(inner.size()));
  std::copy(inner.begin(), inner.end(), matrix_.innerIndexPtr());
  std::fill_n(matrix_.valuePtr(), inner.size(), 0.0);
  finalized_ = true;
}

HessianAccumulator::HessianAccumulator(const SparsePattern& pattern, int threads)
    : pattern_(pattern), result_(pattern.zero_matrix()), buffers_(std::max(1, threads) - 1) {
  // Thread 0 writes into the result itself: one nnz-sized array and one summation pass
  // fewer per Hessian than a private array per thread (3D Hex27: nnz ≈ 170 per dof).
  values_.push_back(result_.valuePtr());
  for (auto& buf : buffers_) {
    buf.assign(static_cast<std::size_t>(result_.nonZeros()), 0.0);
    values_.push_back(buf.data());
  }
}

namespace {
/// buf[pos[r] + 0 .. w − 1] += the block column's run r, column by column: each entry once, in the
/// order of the plain scatter.
template <int w>
void scatter_runs(int n, const int* pos, const double* values, double* buf) {
  const int runs = n / w;
  for (int j = 0; j < n; ++j, pos += runs, values += n)
    for (int r = 0; r < runs; ++r) {
      double* to = buf + pos[r];
      const double* from = values + r * w;
      for (int k = 0; k < w; ++k) to[k] += from[k];
    }
}
}  // namespace

void HessianAccumulator::add_block(int thread, int block, const double* values) {
  const int n = pattern_.block_size(block);
  const int* pos = pattern_.positions(block);
  double* buf = values_[thread];
  switch (pattern_.run_length(block)) {
    case 3: return scatter_runs<3>(n, pos, values, buf);
    case 2: return scatter_runs<2>(n, pos, values, buf);
    default: return scatter_runs<1>(n, pos, values, buf);
  }
}

void HessianAccumulator::finish(SparseMatrix& out) {
  double* v = result_.valuePtr();
  const std::size_t nnz = static_cast<std::size_t>(result_.nonZeros());
  for (const auto& buf : buffers_)
    for (std::size_t k = 0; k < nnz; ++k) v[k] += buf[k];
  buffers_.clear();
  values_.clear();
  out.swap(result_);  // not operator=: Eigen 3.4's SparseMatrix has no move assignment, it would copy
}

}  // namespace softarm::fem

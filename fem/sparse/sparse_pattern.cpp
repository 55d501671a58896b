#include "fem/sparse/sparse_pattern.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace softarm::fem {

int SparsePattern::declare_block(std::span<const int> dofs) {
  if (finalized_) throw std::logic_error("SparsePattern: block declared after finalize()");
  block_dofs_.insert(block_dofs_.end(), dofs.begin(), dofs.end());
  block_offsets_.push_back(static_cast<int>(block_dofs_.size()));
  block_sizes_.push_back(static_cast<int>(dofs.size()));
  return static_cast<int>(block_sizes_.size()) - 1;
}

void SparsePattern::finalize() {
  // Column by column: the rows a column couples to are the dofs of the blocks it is in, each kept
  // once (a stamp per row, not a sort of every block's copy), then sorted; the position of each
  // block entry is read off a row → position table of its column, written once per column. Work
  // and memory O(Σ block size² + nnz), no search per entry.
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
    total += static_cast<std::size_t>(block_sizes_[b]) * block_sizes_[b];
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
    // Block b's entry (i, j) is column d[j], row d[i]: stored at (j·n + i), column-major.
    for (int k = first[c]; k < first[c + 1]; ++k) {
      const auto [b, j] = incidence[k];
      const int n = block_sizes_[b];
      const int* d = block_dofs_.data() + block_offsets_[b];
      int* pos = positions_.data() + position_offsets_[b] + static_cast<std::size_t>(j) * n;
      for (int i = 0; i < n; ++i) pos[i] = where[d[i]];
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

void HessianAccumulator::add_block(int thread, int block, const double* values) {
  const int n = pattern_.block_size(block);
  const int* pos = pattern_.positions(block);
  double* buf = values_[thread];
  for (int k = 0; k < n * n; ++k) buf[pos[k]] += values[k];
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

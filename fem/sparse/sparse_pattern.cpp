#include "fem/sparse/sparse_pattern.hpp"

#include <algorithm>
#include <stdexcept>

namespace softarm::fem {

int SparsePattern::declare_block(std::span<const int> dofs) {
  if (finalized_) throw std::logic_error("SparsePattern: block declared after finalize()");
  block_dofs_.insert(block_dofs_.end(), dofs.begin(), dofs.end());
  block_offsets_.push_back(static_cast<int>(block_dofs_.size()));
  block_sizes_.push_back(static_cast<int>(dofs.size()));
  return static_cast<int>(block_sizes_.size()) - 1;
}

void SparsePattern::finalize() {
  // Column structure: the sorted set of rows coupled to each column.
  std::vector<std::vector<int>> columns(num_dofs_);
  for (std::size_t b = 0; b < block_sizes_.size(); ++b) {
    const int* d = block_dofs_.data() + block_offsets_[b];
    for (int j = 0; j < block_sizes_[b]; ++j)
      for (int i = 0; i < block_sizes_[b]; ++i) columns[d[j]].push_back(d[i]);
  }
  for (int c = 0; c < num_dofs_; ++c) columns[c].push_back(c);  // keep every diagonal (constrained dofs)
  std::vector<Eigen::Triplet<double>> triplets;
  for (int c = 0; c < num_dofs_; ++c) {
    auto& col = columns[c];
    std::sort(col.begin(), col.end());
    col.erase(std::unique(col.begin(), col.end()), col.end());
    for (int r : col) triplets.emplace_back(r, c, 0.0);
  }
  matrix_.resize(num_dofs_, num_dofs_);
  matrix_.setFromTriplets(triplets.begin(), triplets.end());
  matrix_.makeCompressed();

  const int* outer = matrix_.outerIndexPtr();
  const int* inner = matrix_.innerIndexPtr();
  position_offsets_.clear();
  positions_.clear();
  for (std::size_t b = 0; b < block_sizes_.size(); ++b) {
    position_offsets_.push_back(positions_.size());
    const int* d = block_dofs_.data() + block_offsets_[b];
    const int n = block_sizes_[b];
    for (int j = 0; j < n; ++j) {
      const int* begin = inner + outer[d[j]];
      const int* end = inner + outer[d[j] + 1];
      for (int i = 0; i < n; ++i) {
        const int* it = std::lower_bound(begin, end, d[i]);
        positions_.push_back(static_cast<int>(it - inner));
      }
    }
  }
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
  out = std::move(result_);
}

}  // namespace softarm::fem

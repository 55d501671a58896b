#include "fem/solver/permuted_triangle.hpp"

#include <algorithm>
#include <utility>

namespace softarm::fem {

PermutedTriangle::PermutedTriangle(const SparseMatrix& K, const int* perm, bool to_lower)
    : n_(static_cast<int>(K.cols())), nonzeros_of_K_(static_cast<long>(K.nonZeros())), to_lower_(to_lower) {
  std::vector<int> inverse(n_);
  for (int i = 0; i < n_; ++i) inverse[perm[i]] = i;
  const int* outer = K.outerIndexPtr();
  const int* inner = K.innerIndexPtr();
  // Column j of the triangle is column perm[j] of K, stored in full, less the rows on the other side
  // of the diagonal, sorted by their new numbers: each column is read from one stretch of K.
  column_starts_.assign(n_ + 1, 0);
  const std::size_t entries = (static_cast<std::size_t>(K.nonZeros()) + n_) / 2;  // a symmetric pattern's
  rows_.reserve(entries);
  sources_.reserve(entries);
  std::vector<std::pair<int, int>> column;  // (new row, position in K)
  for (int j = 0; j < n_; ++j) {
    const int c = perm[j];
    column.clear();
    for (int k = outer[c]; k < outer[c + 1]; ++k) {
      const int i = inverse[inner[k]];
      if (to_lower ? i >= j : i <= j) column.emplace_back(i, k);
    }
    std::sort(column.begin(), column.end());
    for (const auto& [i, k] : column) rows_.push_back(i), sources_.push_back(k);
    column_starts_[j + 1] = static_cast<int>(rows_.size());
  }
  rows_.shrink_to_fit();  // no-ops where the pattern is symmetric, as K's is
  sources_.shrink_to_fit();
}

bool PermutedTriangle::fits(const SparseMatrix& K) const {
  return K.cols() == n_ && K.rows() == n_ && static_cast<long>(K.nonZeros()) == nonzeros_of_K_ && K.isCompressed();
}

cholmod_sparse PermutedTriangle::gather(const SparseMatrix& K) {
  const double* from = K.valuePtr();
  values_.resize(sources_.size());
  for (std::size_t k = 0; k < sources_.size(); ++k) values_[k] = from[sources_[k]];
  cholmod_sparse A{};
  A.nrow = A.ncol = static_cast<std::size_t>(n_);
  A.nzmax = values_.size();
  A.p = column_starts_.data();
  A.i = rows_.data();
  A.x = values_.data();
  A.stype = to_lower_ ? -1 : 1;
  A.itype = CHOLMOD_INT;
  A.xtype = CHOLMOD_REAL;
  A.dtype = CHOLMOD_DOUBLE;
  A.sorted = 1;
  A.packed = 1;
  return A;
}

}  // namespace softarm::fem

#pragma once
// The triangle of P K Pᵀ that CHOLMOD's numeric factorisation reads (tril for the supernodal factor,
// triu for the simplicial one), gathered from K's columns by positions worked out once per pattern.
// Given K and the factor's permutation, cholmod_factorize_p transposes one triangle of K with that
// permutation at every call (cholmod_transpose_sym: counts, then a scatter to transposed positions,
// into memory allocated and freed each time): 2.9 % of a segment's cells' samples and 6 % of the
// thesis RRA's. Column j of the triangle is column perm[j] of K, which K's full storage holds in one
// stretch, so the gather reads K in order (docs/performance.md, "The permuted triangle gathered, not
// transposed"). Its entries come from both of K's triangles, which agree to rounding, not to the bit.
#include <cholmod.h>

#include <vector>

#include "fem/sparse/sparse_pattern.hpp"

namespace softarm::fem {

class PermutedTriangle {
 public:
  PermutedTriangle() = default;
  /// For K's pattern (full symmetric storage, exactly symmetric values: the assembly adds each
  /// element's symmetric matrix to both triangles alike) and a permutation (row i of P K Pᵀ is row
  /// perm[i] of K, as CHOLMOD's analysis gives it): P K Pᵀ's lower triangle (`to_lower`) or upper one.
  PermutedTriangle(const SparseMatrix& K, const int* perm, bool to_lower);

  /// Whether K has the pattern's size and entry count (never true of a default-made one for a K with
  /// unknowns) (that it has the pattern itself, the caller
  /// knows: a solver's matrices share the pattern its analysis was made for).
  bool fits(const SparseMatrix& K) const;
  /// CHOLMOD's view of the triangle holding K's values, valid until release_values.
  cholmod_sparse gather(const SparseMatrix& K);
  /// Frees the values (half the triangle's bytes) between factorisations: a solver lives as long
  /// as its path, and the positions it keeps already add to the cells' peak memory
  /// (docs/performance.md, "The permuted triangle gathered, not transposed").
  void release_values() { values_ = {}; }

 private:
  int n_ = 0;
  long nonzeros_of_K_ = 0;
  bool to_lower_ = true;
  std::vector<int> column_starts_, rows_, sources_;  // sources_[k]: entry k's position in K
  std::vector<double> values_;
};

}  // namespace softarm::fem

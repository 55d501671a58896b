#pragma once
// CHOLMOD's symbolic analysis (the fill-reducing ordering, the elimination tree, the supernodes) kept
// by sparsity pattern for the whole process. A cell rod runs many solvers on few patterns: the thesis
// SPL's cells analyse 25 times and 7 patterns, the pressure cells' rays repeat one design's cells
// on the same meshes, and METIS took ~6 % of a cell rod's run. The analysis of a pattern is a
// function of the pattern and the solver's settings alone (METIS seeds its generator at each call),
// so a copy of the kept one is what analysing again would give: the same ordering, the same factor
// to the bit.
#include <cholmod.h>

#include <cstdint>
#include <optional>

#include "fem/sparse/sparse_pattern.hpp"

namespace softarm::fem {

/// The solver settings that shape an analysis (LinearSolver::Options' mode, ordering, postorder,
/// amalgamation and simplicial/supernodal switch), as numbers.
struct AnalysisSettings {
  int mode = 0, ordering = 0;
  bool postorder = true, large_supernodes = false;
  double supernodal_switch = 0;
  bool operator==(const AnalysisSettings&) const = default;
};

/// What names one analysis: K's pattern (its size, nonzeros and two independent 64-bit hashes of the
/// column pointers and row indices) and the settings.
struct PatternKey {
  std::int64_t rows = 0, nonzeros = 0;
  std::uint64_t hash_a = 0, hash_b = 0;
  AnalysisSettings settings;
  bool operator==(const PatternKey&) const = default;
};
PatternKey pattern_key(const SparseMatrix& K, const AnalysisSettings& settings);

/// A kept analysis: the symbolic factor copied into `common`'s allocation, with the flops and
/// nonzeros of L that CHOLMOD's analysis predicted.
struct KeptAnalysis {
  cholmod_factor* symbolic = nullptr;  // the caller's to free (cholmod_free_factor)
  double flops = 0, nonzeros = 0;
};

/// The analysis kept for `key`, copied for the caller; nothing where none is kept. Thread-safe.
std::optional<KeptAnalysis> find_analysis(const PatternKey& key, cholmod_common& common);
/// Keeps a copy of `symbolic` (just analysed, not yet factorised) for `key`; the oldest of more than
/// kKeptAnalyses is dropped. Thread-safe.
void keep_analysis(const PatternKey& key, const cholmod_factor& symbolic, double flops, double nonzeros);
inline constexpr int kKeptAnalyses = 16;
/// Analyses served from the cache and made, for the process (tests, benchmarks).
struct AnalysisCounts {
  long served = 0, made = 0;
};
AnalysisCounts analysis_counts();

}  // namespace softarm::fem

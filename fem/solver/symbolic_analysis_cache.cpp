#include "fem/solver/symbolic_analysis_cache.hpp"

#include <deque>
#include <mutex>

namespace softarm::fem {
namespace {

/// splitmix64's finaliser (Steele, Lea & Flood 2014): every input bit reaches every output bit.
std::uint64_t mix(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

struct Kept {
  PatternKey key;
  cholmod_factor* symbolic;
  double flops, nonzeros;
};

/// The kept analyses, in their own CHOLMOD workspace (started once, for the process's life).
struct Store {
  std::mutex mutex;
  cholmod_common common;
  std::deque<Kept> kept;
  AnalysisCounts counts;
  Store() { cholmod_start(&common); }
};
Store& store() {
  static Store s;
  return s;
}

}  // namespace

PatternKey pattern_key(const SparseMatrix& K, const AnalysisSettings& settings) {
  PatternKey key;
  key.rows = K.rows();
  key.nonzeros = K.nonZeros();
  key.settings = settings;
  // Two hashes of the compressed pattern: FNV-1a over the indices, and a running splitmix of them.
  std::uint64_t a = 0xcbf29ce484222325ULL, b = 0x9e3779b97f4a7c15ULL;
  const auto add = [&](std::uint64_t v) {
    a = (a ^ v) * 0x100000001b3ULL;
    b = mix(b + v + 0x9e3779b97f4a7c15ULL);
  };
  // Column by column, each column's count first (K may be uncompressed, as CHOLMOD may read it).
  for (Eigen::Index j = 0; j < K.outerSize(); ++j) {
    std::uint64_t count = 0;
    for (SparseMatrix::InnerIterator it(K, j); it; ++it) ++count;
    add(count);
    for (SparseMatrix::InnerIterator it(K, j); it; ++it) add(static_cast<std::uint64_t>(it.index()));
  }
  key.hash_a = a;
  key.hash_b = b;
  return key;
}

std::optional<KeptAnalysis> find_analysis(const PatternKey& key, cholmod_common& common) {
  Store& s = store();
  const std::lock_guard<std::mutex> lock(s.mutex);
  for (const Kept& k : s.kept)
    if (k.key == key) {
      cholmod_factor* copy = cholmod_copy_factor(k.symbolic, &common);
      if (!copy) return std::nullopt;
      ++s.counts.served;
      return KeptAnalysis{copy, k.flops, k.nonzeros};
    }
  return std::nullopt;
}

void keep_analysis(const PatternKey& key, const cholmod_factor& symbolic, double flops, double nonzeros) {
  Store& s = store();
  const std::lock_guard<std::mutex> lock(s.mutex);
  ++s.counts.made;
  for (const Kept& k : s.kept)
    if (k.key == key) return;
  cholmod_factor* copy = cholmod_copy_factor(const_cast<cholmod_factor*>(&symbolic), &s.common);
  if (!copy) return;
  s.kept.push_back({key, copy, flops, nonzeros});
  if (static_cast<int>(s.kept.size()) > kKeptAnalyses) {
    cholmod_free_factor(&s.kept.front().symbolic, &s.common);
    s.kept.pop_front();
  }
}

AnalysisCounts analysis_counts() {
  Store& s = store();
  const std::lock_guard<std::mutex> lock(s.mutex);
  return s.counts;
}

}  // namespace softarm::fem

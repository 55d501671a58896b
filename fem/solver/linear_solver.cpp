#include "fem/solver/linear_solver.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <chrono>
#include <limits>
#include <mutex>
#include <optional>

#include "fem/core/parallel.hpp"
#include "fem/solver/preconditioned_cg.hpp"
#include "fem/solver/symbolic_analysis_cache.hpp"

namespace softarm::fem {
namespace {
/// Gives the BLAS as many threads as softarm may use (--threads, SOFTARM_THREADS).
/// A threaded OpenBLAS otherwise takes every core, and when other processes want
/// them too (ctest -j2, two runs at once) its spinning threads thrash: a 3CA run
/// next to a compiler spent half its time in the kernel. Looked up at run time, so
/// any BLAS links (reference BLAS has no threads to set).
void match_blas_threads() {
  using SetThreads = void (*)(int);
  static const auto set = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
  // The cells' tasks factorise side by side: a task waits until the count it needs is set, since
  // OpenBLAS's thread count changes how it blocks a factorisation and so its rounding.
  static std::mutex mutex;
  static int applied = 0;
  const std::lock_guard<std::mutex> lock(mutex);
  if (set && applied != thread_count()) {
    applied = thread_count();
    set(applied);
  }
}

/// CHOLMOD's supernodal factorisation opens an OpenMP team of a size fixed when it was built
/// (`num_threads(CHOLMOD_OMP_NUM_THREADS)`) around the memsets that zero each supernode and clear
/// its map: a fork and join per supernode, with more threads than this machine has cores, and
/// those threads spin between teams against the cells' tasks. A `num_threads` clause overrides
/// omp_set_num_threads, but with dynamic teams on, libgomp bounds a team by min(cores,
/// nthreads-var) less the load average, so nthreads-var = 1 makes every team this thread opens a
/// team of one: the loops run in the calling thread, with the same results (copies and zeros).
/// OpenMP's settings belong to each thread, hence once per thread; looked up at run time, as the
/// BLAS's are. Ring 15 of the thesis 3CA on one core (bench_tca_cell): docs/performance.md.
void serial_openmp_in_this_thread() {
  using SetInt = void (*)(int);
  static const auto set_dynamic = reinterpret_cast<SetInt>(dlsym(RTLD_DEFAULT, "omp_set_dynamic"));
  static const auto set_threads = reinterpret_cast<SetInt>(dlsym(RTLD_DEFAULT, "omp_set_num_threads"));
  thread_local bool applied = false;
  if (applied || !set_dynamic || !set_threads) return;
  applied = true;
  set_threads(1);
  set_dynamic(1);
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

// The defaults (Options{}) are CHOLMOD's own choices, kept on measurement
// (bench_linear_solver: Hex27/P1 box 60x30x160 mm, Dragon Skin 30 tangent at rest,
// medians of 3 factorisations, same pattern as every Newton iteration):
//  - automatic simplicial/supernodal: supernodal on Hex27 (61,347 dofs: simplicial
//    42.6 s vs supernodal 3.0 s), simplicial on the 2D RRA scenes (right there: few flops
//    per entry of L, no BLAS-3 work to win).
//  - ordering: CHOLMOD's default tries AMD, finds its fill high on 3D meshes and takes
//    METIS: nnz(L) 28.7 M, 22.0 GFlop vs AMD only 37.4 M, 42.6 GFlop, 5.3 s (1.8x slower).
//    METIS only gives the same factor (the AMD trial costs < 0.5 s once per pattern and
//    keeps AMD on 2D meshes); NESDIS 22.1 GFlop, same time; trying all 9 orderings
//    saves 3.5 % of the flops for a 5.4 s analysis instead of 1.0 s: not worth it.
//  - postorder on (off: 4.6 s vs 3.0 s). Relaxed amalgamation nrelax {8, 32, 96}:
//    no gain (61k: 2.97 vs 3.17 s, 109k: 7.76 vs 7.13 s, serial OpenBLAS, 2 pinned cores).
//  - the triangle CHOLMOD reads, tril(PKPᵀ) for the supernodal factor and triu(PKPᵀ) for the
//    simplicial one, gathered from K's columns (permuted_triangle.hpp) instead of transposed by
//    CHOLMOD from one of K's triangles at every factorisation.
// What matters is the BLAS behind libblas.so.3/liblapack.so.3 (scripts/setup.sh installs
// libopenblas0-pthread): at 61k dofs reference BLAS 36.8 s, OpenBLAS serial 3.0 s (this
// 2-core machine, loaded); on 2 pinned cores of an idle Xeon, serial vs pthread OpenBLAS:
// 19,683 dofs 0.63 vs 0.29 s, 61,347 dofs 3.17 vs 1.58 s, 156,927 dofs 19.9 vs 11.9 s.
LinearSolver::LinearSolver(const Options& options) : options_(options) { configure(); }

void LinearSolver::configure() {
  Cholesky& c = cholesky_;
  using Mode = Options::Mode;
  c.setMode(options_.mode == Mode::automatic    ? Eigen::CholmodAuto
            : options_.mode == Mode::simplicial ? Eigen::CholmodSimplicialLLt
                                                : Eigen::CholmodSupernodalLLt);
  auto& cm = c.cholmod();
  cm.final_ll = 1;     // LLᵀ: fails (and says so) on an indefinite tangent
  cm.print = 0;        // a failed Cholesky is an expected event, not a warning
  cm.quick_return_if_not_posdef = 1;
  cm.postorder = options_.postorder ? 1 : 0;
  cm.supernodal_switch = options_.supernodal_switch;
  if (options_.large_supernodes) {
    cm.nrelax[0] = 8, cm.nrelax[1] = 32, cm.nrelax[2] = 96;
    cm.zrelax[0] = 0.8, cm.zrelax[1] = 0.2, cm.zrelax[2] = 0.1;
  }
  using Ordering = Options::Ordering;
  switch (options_.ordering) {
    case Ordering::cholmod_default: break;
    case Ordering::amd: cm.nmethods = 1; cm.method[0].ordering = CHOLMOD_AMD; break;
    case Ordering::metis: cm.nmethods = 1; cm.method[0].ordering = CHOLMOD_METIS; break;
    case Ordering::nesdis: cm.nmethods = 1; cm.method[0].ordering = CHOLMOD_NESDIS; break;
    case Ordering::best_of_all: cm.nmethods = 9; break;
  }
}

void LinearSolver::Cholesky::adopt_analysis(cholmod_factor* symbolic) {
  if (this->m_cholmodFactor) cholmod_free_factor(&this->m_cholmodFactor, &this->cholmod());
  this->m_cholmodFactor = symbolic;
  this->m_isInitialized = true;
  this->m_info = Eigen::Success;
  this->m_analysisIsOk = true;
  this->m_factorizationIsOk = false;
}

void LinearSolver::analyse(const SparseMatrix& K) {
  Cholesky& c = cholesky_;
  // One analysis at a time in the process: CHOLMOD's default ordering calls METIS, which seeds one
  // random generator shared by every thread at each call. Two cells analysed side by side drew from
  // it in turn, got orderings that depended on the timing, and so factors rounded differently: the
  // thesis 3CA's outputs differed by up to 3e-12 from run to run. Serialised, each call seeds and
  // draws alone, and a cell run beside another gives the bits it gives alone. The lock costs an
  // analysis (0.07 s a cell) of waiting at most; a second solver of the pattern then finds it kept.
  static std::mutex metis;
  const std::lock_guard<std::mutex> one_at_a_time(metis);
  c.permuted = {};  // its positions follow the permutation this analysis gives
  const PatternKey key =
      pattern_key(K, {static_cast<int>(options_.mode), static_cast<int>(options_.ordering), options_.postorder,
                      options_.large_supernodes, options_.supernodal_switch});
  std::optional<KeptAnalysis> kept;
  if (options_.share_analysis) kept = find_analysis(key, c.cholmod());
  if (kept) {
    c.adopt_analysis(kept->symbolic);
    factor_flops = kept->flops;
    factor_nonzeros = kept->nonzeros;
    return;
  }
  c.analyzePattern(K);
  factor_flops = c.cholmod().fl;
  factor_nonzeros = c.cholmod().lnz;
  if (options_.share_analysis && c.factor()) keep_analysis(key, *c.factor(), factor_flops, factor_nonzeros);
}

// As Eigen's CholmodBase::factorize, but CHOLMOD is handed the triangle of P K Pᵀ it would make
// itself (permuted_triangle.hpp), with the factor's ordering marked natural for the call so that it
// reads that triangle as it is; marked back after, since the solves permute b and x by L's
// permutation unless the ordering is natural.
void LinearSolver::Cholesky::factorize_from(const SparseMatrix& K) {
  eigen_assert(this->m_analysisIsOk && "analyzePattern first");
  if (!K.isCompressed()) {  // the gather reads each column from its start to the next one's
    SparseMatrix compressed = K;
    compressed.makeCompressed();
    return factorize_from(compressed);
  }
  cholmod_factor* L = this->m_cholmodFactor;
  if (!permuted.fits(K))
    permuted = PermutedTriangle(K, static_cast<const int*>(L->Perm), L->is_super);
  cholmod_sparse A = permuted.gather(K);
  const int ordering = L->ordering;
  L->ordering = CHOLMOD_NATURAL;
  cholmod_factorize_p(&A, this->m_shiftOffset, nullptr, 0, L, &this->cholmod());
  L->ordering = ordering;
  permuted.release_values();
  // On success CHOLMOD's minor is n; on failure the column where the factorisation stopped.
  this->m_info = this->m_cholmodFactor->minor == this->m_cholmodFactor->n ? Eigen::Success : Eigen::NumericalIssue;
  this->m_factorizationIsOk = true;
}

bool LinearSolver::cholesky_factorize(const SparseMatrix& K) {
  Cholesky& c = cholesky_;
  if (!cholesky_analysed_) {
    const auto t0 = std::chrono::steady_clock::now();
    analyse(K);
    cholesky_analysed_ = true;
    analyse_seconds += seconds_since(t0);
    supernodal = c.factor() && c.factor()->is_super;
  }
  const auto t0 = std::chrono::steady_clock::now();
  single_current_ = false;
  c.factorize_from(K);
  factorize_seconds += seconds_since(t0);
  cholmod_peak_bytes = static_cast<double>(c.cholmod().memory_usage);
  return c.info() == Eigen::Success;
}

bool LinearSolver::cholesky_with_shift(const SparseMatrix& K, double shift) {
  // CHOLMOD factorises K + shift·I (its beta); Eigen keeps the shift for later calls.
  cholesky_.setShift(shift);
  return cholesky_factorize(K);
}

bool LinearSolver::plain_cholesky(const SparseMatrix& K) {
  match_blas_threads();
  serial_openmp_in_this_thread();
  ++factorizations;
  shifted_ = false;
  last_shift = 0.0;
  return cholesky_with_shift(K, 0.0);
}

LinearSolver::Status LinearSolver::factorize(const SparseMatrix& K) {
  if (plain_cholesky(K)) return status_ = Status::positive_definite;
  ++lu_fallbacks;
  const auto t0 = std::chrono::steady_clock::now();
  lu_matrix_ = K;
  if (!lu_analysed_) {
    lu_.analyzePattern(lu_matrix_);
    lu_analysed_ = true;
  }
  lu_.factorize(lu_matrix_);
  factorize_seconds += seconds_since(t0);
  return status_ = (lu_.info() == Eigen::Success ? Status::indefinite : Status::singular);
}

LinearSolver::Status LinearSolver::factorize_shifted(const SparseMatrix& K) {
  if (plain_cholesky(K)) return status_ = Status::positive_definite;
  const double mean_diagonal = K.diagonal().cwiseAbs().mean();
  // Start one decade below the shift that worked last time: successive tangents of one
  // path need similar shifts, and every rejected shift costs up to a whole factorisation
  // (on the thesis 3CA's approach to its limit point the search from 1e-6 tried ~4 each).
  const double first = std::clamp(last_shift_fraction_ / 10, kMinShift, kMaxShift);
  for (double s = first; s <= kMaxShift * (1 + 1e-12); s *= 10) {
    ++shifted_factorizations;
    if (cholesky_with_shift(K, s * mean_diagonal)) {
      last_shift = s * mean_diagonal;
      last_shift_fraction_ = s;
      shifted_ = true;
      return status_ = Status::indefinite;
    }
  }
  return status_ = Status::singular;
}

// Each CG iteration is one solve with the factor (two triangular sweeps, 4·nnz(L) flops)
// plus a product with K (a few per cent of a solve): past half a factorisation's cost,
// factorising is the better buy. The cost is counted in flops, not timed, so that a run
// takes the same path whatever else the machine does (a timed budget made the thesis 3CA's
// path differ run to run: 17-24 load steps, and once a spurious failure at 275.8 kPa).
// The two kinds of flop are not equally fast: the supernodal factorisation runs BLAS-3
// at ~6 times the rate of the memory-bound sweeps. Measured (2 threads, this 2-core machine,
// medians over a 0-137.9 kPa 3CA run): Hex20 2x2x2 level 1, 16.8 GFlop and nnz(L) 23.1 M,
// factorisation / solve time 29.8 against a flop ratio of 182 (0.164); Hex27 level 1,
// 39.6 GFlop, 43.8 M, 35.7 against 226 (0.158). Budget: Hex20 14, Hex27 18 iterations.
int LinearSolver::reuse_cg_budget() const {
  constexpr double kSweepToFactorRate = 0.16;
  constexpr int kMinIterations = 4, kMaxIterations = 200;
  const double sweep_flops = 4 * std::max(factor_nonzeros, 1.0);
  return std::clamp(static_cast<int>(0.5 * kSweepToFactorRate * factor_flops / sweep_flops), kMinIterations,
                    kMaxIterations);
}

Eigen::VectorXd LinearSolver::solve(const Eigen::VectorXd& b) {
  const auto t0 = std::chrono::steady_clock::now();
  Eigen::VectorXd x;
  // A singular matrix has no factor to solve with (UMFPACK would dereference a null
  // numeric object): the answer is "no solution", NaN, for the caller to diagnose.
  if (status_ == Status::singular) return Eigen::VectorXd::Constant(b.size(), std::numeric_limits<double>::quiet_NaN());
  if (status_ == Status::positive_definite || shifted_)
    x = cholesky_.solve(b);
  else
    x = lu_.solve(b);
  solve_seconds += seconds_since(t0);
  return x;
}

Eigen::VectorXd LinearSolver::precondition(const Eigen::VectorXd& r) {
  if (!options_.single_precision_preconditioner) return solve(r);
  const auto t0 = std::chrono::steady_clock::now();
  if (!single_current_) {
    const cholmod_factor* L = cholesky_.factor();
    if (!L || !single_.assign(*L)) single_.clear();
    single_current_ = true;
  }
  if (single_.empty()) return solve(r);
  Eigen::VectorXd z = single_.solve(r);
  solve_seconds += seconds_since(t0);
  return z;
}

bool LinearSolver::solve_reusing_factor(const SparseMatrix& K, const Eigen::VectorXd& b, double tolerance,
                                        Eigen::VectorXd& d) {
  const int budget = options_.reuse_cg_iterations > 0 ? options_.reuse_cg_iterations : reuse_cg_budget();
  return solve_reusing_factor([&K](const Eigen::VectorXd& p) { return Eigen::VectorXd(K * p); }, b, tolerance, budget,
                              /*give_up_early=*/true, d);
}

bool LinearSolver::solve_reusing_factor(const LinearOperator& apply, const Eigen::VectorXd& b, double tolerance,
                                        int max_iterations, bool give_up_early, Eigen::VectorXd& d) {
  if (status_ != Status::positive_definite || shifted_) return false;
  const CgResult cg = preconditioned_cg(apply, b, [this](const Eigen::VectorXd& r) { return precondition(r); },
                                        tolerance, max_iterations, d, give_up_early);
  cg_iterations += cg.iterations;
  if (cg.converged) ++reused_solves;
  return cg.converged;
}

}  // namespace softarm::fem

#pragma once
// Sparse direct solves with SuiteSparse. The symmetric tangent is factorised
// with CHOLMOD's LLᵀ (simplicial or supernodal, CHOLMOD chooses from the
// flop count: simplicial wins on 2D meshes, supernodal on 3D ones); its symbolic analysis (fill-reducing ordering,
// elimination tree) is done once per sparsity pattern and reused for every
// Newton iteration. When the tangent is not positive definite (past a limit
// point, or far from equilibrium) the Cholesky fails and the solve falls back
// to UMFPACK's LU, whose symbolic analysis is likewise kept; or, with
// factorize_shifted(), to the Cholesky of K + σI with the smallest σ of a
// ladder that makes it positive definite (a Levenberg–Marquardt step, as in
// Ipopt's inertia correction, Wächter & Biegler 2006 §3.1): a descent
// direction for the energy at the cost of one more supernodal Cholesky, where
// UMFPACK's LU of a 3D tangent costs minutes.
//
// The defaults (Options{}) are the measured best for both the 2D axisymmetric
// scenes and 3D Hex27 bodies; see linear_solver.cpp and bench_linear_solver.
#include <Eigen/CholmodSupport>
#include <Eigen/UmfPackSupport>
#include <memory>

#include "fem/sparse/sparse_pattern.hpp"
#include "fem/solver/permuted_triangle.hpp"
#include "fem/solver/preconditioned_cg.hpp"
#include "fem/solver/single_precision_factor.hpp"

namespace softarm::fem {

class LinearSolver {
 public:
  /// positive_definite: Cholesky of K; indefinite: K is not positive definite and was
  /// factorised by LU (factorize) or shifted to K + σI (factorize_shifted); singular: no factor.
  enum class Status { positive_definite, indefinite, singular };

  /// Solver configuration (the alternatives exist for bench_linear_solver).
  struct Options {
    enum class Mode { automatic, simplicial, supernodal };
    /// cholmod_default: CHOLMOD's own strategy (AMD, then METIS when AMD's fill is high);
    /// amd, metis, nesdis: that ordering only; best_of_all: every ordering, keep the least fill.
    enum class Ordering { cholmod_default, amd, metis, nesdis, best_of_all };
    Mode mode = Mode::automatic;
    Ordering ordering = Ordering::cholmod_default;
    bool postorder = true;
    double supernodal_switch = 40.0;  // CHOLMOD's flops/nnz(L) threshold for automatic mode
    bool large_supernodes = false;    // relaxed amalgamation nrelax {8, 32, 96}, zrelax {0.8, 0.2, 0.1}
    /// CG iterations solve_reusing_factor may spend; 0: as many as cost half a factorisation
    /// (reuse_cg_budget, from CHOLMOD's flop count: the same on every run).
    int reuse_cg_iterations = 0;
    /// CG on an earlier factor preconditions with that factor copied to single precision
    /// (single_precision_factor.hpp) where it is supernodal; false: with the double factor.
    bool single_precision_preconditioner = true;
    /// The analysis of K's pattern is the process's: taken from an earlier solver's of the same pattern
    /// and settings where there is one, kept for later ones (symbolic_analysis_cache.hpp); false:
    /// analysed afresh, and not kept.
    bool share_analysis = true;
  };

  LinearSolver() : LinearSolver(Options{}) {}
  explicit LinearSolver(const Options& options);
  /// Factorises K (symmetric, both triangles stored, as the assembly makes it; the same pattern every
  /// call: permuted_triangle.hpp reads each column in full). Returns positive_definite when
  /// Cholesky succeeded, indefinite when LU was needed and succeeded, singular otherwise.
  Status factorize(const SparseMatrix& K);
  /// As factorize, but an indefinite K is replaced by K + σI, σ = s·d̄ for
  /// s = s₀, 10 s₀, …, 100 with d̄ the mean |diagonal| of K, the first that
  /// Cholesky accepts (σ is kept in last_shift); singular if none does. s₀ is
  /// a tenth of the s that worked last time (1e-6 the first time).
  Status factorize_shifted(const SparseMatrix& K);
  /// Solves with the last factor; NaN everywhere when the matrix was singular (no factor).
  Eigen::VectorXd solve(const Eigen::VectorXd& b);
  /// Solves K d = b without factorising K: conjugate gradients preconditioned with the
  /// current factor, which must be an unshifted Cholesky factor of an earlier matrix of
  /// K's pattern (preconditioned_cg.hpp), to ‖K d − b‖ ≤ tolerance·‖b‖. Returns false (d
  /// unspecified) when there is no such factor, when CG meets non-positive curvature (K is
  /// not positive definite), or when it has not converged within the iterations that cost
  /// half a factorisation (reuse_cg_budget) or will not (CG gives up early where its residuals
  /// project the tolerance well beyond them: preconditioned_cg.hpp); the caller then factorises K.
  bool solve_reusing_factor(const SparseMatrix& K, const Eigen::VectorXd& b, double tolerance, Eigen::VectorXd& d);
  /// The same for an operator given by its action (a matrix plus a low-rank term) and an
  /// explicit CG budget; CG gives up early only if `give_up_early` (a caller whose fallback is
  /// cheaper than the budget: not one whose fallback is an LU).
  bool solve_reusing_factor(const LinearOperator& apply, const Eigen::VectorXd& b, double tolerance,
                            int max_iterations, bool give_up_early, Eigen::VectorXd& d);
  Status status() const { return status_; }
  /// CG iterations that cost about half a factorisation: from the analysis' flop count and
  /// nnz(L), with the measured ratio of the two kinds of flop (linear_solver.cpp).
  int reuse_cg_budget() const;
  /// CG's sweeps read the factor's single-precision copy (Options::single_precision_preconditioner,
  /// a supernodal factor): each takes about half the time of one with the factor itself.
  bool single_precision_sweeps() const { return supernodal && options_.single_precision_preconditioner; }

  // Timings of the last call, seconds (for benchmarks).
  double analyse_seconds = 0.0, factorize_seconds = 0.0, solve_seconds = 0.0;
  int factorizations = 0, lu_fallbacks = 0, shifted_factorizations = 0;
  int reused_solves = 0, cg_iterations = 0;  // solve_reusing_factor: successes, CG iterations of every call
  double last_shift = 0.0;  // σ of the last factorisation (0: K itself)
  // After the analysis (benchmarks): predicted flops and nonzeros of L, whether
  // CHOLMOD chose the supernodal factor, and CHOLMOD's peak memory in bytes.
  double factor_flops = 0.0, factor_nonzeros = 0.0, cholmod_peak_bytes = 0.0;
  bool supernodal = false;

 private:
  void configure();
  bool cholesky_factorize(const SparseMatrix& K);
  bool cholesky_with_shift(const SparseMatrix& K, double shift);
  bool plain_cholesky(const SparseMatrix& K);  // counts the factorisation, clears any shift
  /// CG's preconditioner: the factor's single-precision copy where Options and the factor allow it
  /// (made at the first CG after each factorisation), else the factor itself.
  Eigen::VectorXd precondition(const Eigen::VectorXd& r);

  /// Eigen's CHOLMOD wrapper (analysed on K's lower triangle) that factorises from P K Pᵀ's triangle.
  struct Cholesky : Eigen::CholmodDecomposition<SparseMatrix, Eigen::Lower> {
    const cholmod_factor* factor() const { return this->m_cholmodFactor; }
    void factorize_from(const SparseMatrix& K);
    PermutedTriangle permuted;  // of the analysis's pattern and permutation, made at the first factorisation
    /// Takes `symbolic` (an analysis of K's pattern, allocated in this solver's workspace) as its own,
    /// as analyzePattern would have made it.
    void adopt_analysis(cholmod_factor* symbolic);
  };
  /// CHOLMOD's analysis of K's pattern, or the copy of one made before in this process for the same
  /// pattern and settings (symbolic_analysis_cache.hpp).
  void analyse(const SparseMatrix& K);
  Options options_;
  Cholesky cholesky_;
  Eigen::UmfPackLU<SparseMatrix> lu_;
  // UMFPACK's solve reads the factorised matrix again (iterative refinement), and Eigen's
  // UmfPackLU keeps only a reference to it; the caller's tangent is gone by the time the
  // solution is wanted (Newton moves on, dp/dV is computed after convergence), so the LU
  // factorises this copy, which lives as long as the factor.
  SparseMatrix lu_matrix_;
  bool cholesky_analysed_ = false, lu_analysed_ = false;
  Status status_ = Status::singular;
  bool shifted_ = false;  // the Cholesky factor is of K + σI
  SinglePrecisionFactor single_;
  bool single_current_ = false;  // single_ is the current factor's copy (or the factor has none)
  static constexpr double kMinShift = 1e-6, kMaxShift = 1e2;  // σ / mean |diagonal|
  double last_shift_fraction_ = kMinShift * 10;  // s of the last accepted shift
};

}  // namespace softarm::fem

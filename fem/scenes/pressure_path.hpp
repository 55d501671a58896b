#pragma once
// Pressure ramp of one chamber with limit-point detection, shared by every
// scene that inflates a chamber (RRA now, the 3CA and SPL later).
//
// At each converged state the chamber's pressure–volume stiffness
// dp/dV = 1 / (∇Vᵀ K⁻¹ ∇V) is computed from the tangent (one extra solve).
// Under pressure control a limit point (ballooning) shows as dp/dV → 0 and
// the tangent losing positive definiteness; a Newton failure with dp/dV still
// well above zero is a stall (numerical), not a burst, unless the tangent's
// lowest eigenvalue has collapsed there (a local instability that the loaded
// volume barely shows: LimitPointSettings::check_lowest_mode). The two are
// reported differently: a stall is never passed off as a physical limit.
#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include "fem/forms/chamber_pressure_form.hpp"
#include "fem/forms/elastic_form.hpp"
#include "fem/scenes/pressure_state.hpp"
#include "fem/solver/load_stepper.hpp"

namespace softarm::fem {

/// How a pressure path ended. Every outcome but `stalled` is an answer about the design: the requested
/// pressure reached; a limit point (its burst pressure); the silicone's law loses Drucker stability
/// at the state reached (a material failure); an element that every step, down to the smallest,
/// turns inside out (where the mesh can no longer follow the body). A stall is numerical only: the
/// path stopped and none of these explains it. (New values go last: cached cell results store the
/// number.)
enum class PathOutcome { completed, limit_point, stalled, material_instability, element_inversion };
inline const char* to_string(PathOutcome o) {
  switch (o) {
    case PathOutcome::completed: return "completed";
    case PathOutcome::limit_point: return "limit_point";
    case PathOutcome::stalled: return "stalled";
    case PathOutcome::material_instability: return "material_instability";
    case PathOutcome::element_inversion: return "element_inversion";
  }
  return "unknown";
}
inline constexpr PathOutcome all_path_outcomes[] = {PathOutcome::completed, PathOutcome::limit_point, PathOutcome::stalled,
                                                     PathOutcome::material_instability, PathOutcome::element_inversion};
/// The outcome in words, for reports ("limit point", "material instability", ...).
inline std::string in_words(PathOutcome o) {
  std::string words = to_string(o);
  std::replace(words.begin(), words.end(), '_', ' ');
  return words;
}
/// The outcome named `name` by to_string (completed if none is).
inline PathOutcome path_outcome_named(const std::string& name) {
  for (const PathOutcome o : all_path_outcomes)
    if (name == to_string(o)) return o;
  return PathOutcome::completed;
}
/// Whether the path ended in an answer a designer can use (everything but a numerical stall).
inline bool is_answer(PathOutcome o) { return o != PathOutcome::stalled; }
/// Whether the path ended in a failure of the design: a limit point or a named material or element failure.
inline bool is_failure(PathOutcome o) { return is_answer(o) && o != PathOutcome::completed; }
/// The outcome of a model that stopped short because its parts' paths did (a rod on cells): the
/// first failure of a part (limit point, material, element), else a stall.
inline PathOutcome outcome_of_parts(const std::vector<PathOutcome>& parts) {
  for (const PathOutcome o : parts)
    if (is_failure(o)) return o;
  return PathOutcome::stalled;
}

/// How a limit point was found: traced past the pressure maximum by chamber-volume control; where
/// the chamber's dp/dV fell to zero (extrapolated to its peak); where the tangent's lowest eigenvalue
/// collapsed (a local mode); or where one of its few lowest eigenvalues falls to zero just ahead
/// (a fold, fem/solver/fold_estimate.hpp).
enum class LimitKind { none, traced, pressure_volume, lowest_mode, fold };
inline const char* to_string(LimitKind k) {
  switch (k) {
    case LimitKind::traced: return "traced";
    case LimitKind::pressure_volume: return "pressure_volume";
    case LimitKind::lowest_mode: return "lowest_mode";
    case LimitKind::fold: return "fold";
    default: return "none";
  }
}

struct LimitPointSettings {
  /// dp/dV below this fraction of its initial value, at a failed step, means a limit point.
  double stiffness_fraction = 0.05;
  /// Where pressure control stops at (or near) a limit point, follow the path past it by
  /// chamber-volume control (fem/solver/volume_control.hpp) to locate the pressure maximum.
  bool follow_with_volume_control = true;
  /// ... when pressure control fails with dp/dV below this fraction of its initial value. 1 (the
  /// default) tries it at every stall: a 3CA whose chamber walls balloon between a few rings reaches
  /// its maximum with dp/dV of the whole loaded volume still at a third (the thesis 3CA: 33 % at
  /// 315.1 kPa, maximum at 316.4 kPa), and a thin Dragon Skin 10 end cap stalls pressure control
  /// with dp/dV at 41 % (issue 38): volume control traces both, to a maximum or to the requested
  /// pressure. A stall is reported only where volume control could not go on either.
  double volume_control_fraction = 1.0;
  /// With follow_with_volume_control: hand the path to volume control before a step past the
  /// pressure where dp/dV, extrapolated linearly in p from the last two states, falls to zero, rather
  /// than try steps beyond a maximum. Each such try costs a run of indefinite Newton iterations and
  /// shifted factorisations: the thesis 3CA's free end cell tried 4, and spent 114 Newton iterations
  /// and 70 shifted factorisations, before volume control traced its maximum. (Linear, not the
  /// parabola p(V) that name_ballooning's estimate uses: that one foresaw this cell's maximum at
  /// 299.8 kPa from 275.8, where volume control stalled; pressure control reaches 310.2, and the
  /// maximum is at 314.1.) Where volume control finds no maximum before the next output level, or a
  /// bifurcation before it, pressure control goes on from the handed-over state as it would have.
  /// Config: solver.volume_control_ahead_of_limit.
  bool hand_over_ahead = true;
  /// The same hand-over, where hand_over_ahead is off, once every start of a step past the last
  /// converged state has failed: pressure control has met the maximum, and the steps it would halve
  /// towards it fail alike. The thesis 3CA's free end cell handed over at 313.9 kPa instead of
  /// failing at 315.4 and 314.3 kPa first: 112 Newton iterations against 123, 53 factorisations and
  /// 51 shifted attempts against 66 and 70, the same maximum (314.1313 kPa).
  /// Config: solver.volume_control_after_failed_step.
  bool hand_over_after_failure = true;
  /// Where pressure control stalls with dp/dV still high, compare the tangent's lowest
  /// eigenvalue with its value at rest (fem/solver/lowest_modes.hpp): one that has fallen below
  /// lowest_mode_fraction of it is a local instability (a wall ballooning between rings) that the
  /// loaded volume does not show. Costs two factorisations and a few dozen solves, at a stall only.
  bool check_lowest_mode = true;
  double lowest_mode_fraction = 0.05;
  /// With check_lowest_mode, a stall that none of the above explains is a fold where one of the
  /// tangent's fold_modes lowest eigenvalues, extrapolated along the path, reaches zero within
  /// fold_margin of the last converged pressure (fem/solver/fold_estimate.hpp).
  int fold_modes = 4;
  double fold_margin = 0.02;
  /// Volume control solves its bordered systems by CG on K + α∇V∇Vᵀ preconditioned with the
  /// starting tangent's Cholesky factor, factorising K (LU past the maximum) only where CG fails
  /// (VolumeControlSettings::augmented_cg). The 3D scenes' default: their LU costs seconds.
  bool volume_control_by_cg = false;
};

struct PressurePathResult {
  PathOutcome outcome = PathOutcome::completed;
  std::string diagnosis;              // human-readable explanation and retry advice
  double reached_pressure_kPa = 0.0;
  double estimated_limit_pressure_kPa = 0.0;  // peak of p(V) when a limit point is found: traced past by
                                              // volume control, or extrapolated from the last states
  LimitKind limit_kind = LimitKind::none;     // with outcome limit_point: how it was found
  double handed_over_kPa = 0.0;  // where pressure control handed over to volume control ahead of a maximum (0: nowhere)
  MaterialInstability material;  // with outcome material_instability: where the law is unstable at the state reached
  int inverted_element = -1;     // with outcome element_inversion: the element the last step turned inside out
  PathResult path;
  /// With a checkpoint: the converged states taken from an earlier run's log (0: started
  /// from rest), and why an existing log was not resumed ("" if it was, or there was none).
  int resumed_states = 0;
  std::string checkpoint_discarded;
  std::vector<PressureState> history;  // every converged step under pressure control
  std::vector<PressureState> beyond_limit;  // volume control's states past the last one (pressure rises, then falls)
  /// At a stall (check_lowest_mode): the tangent's lowest eigenvalue at the last converged state
  /// over its value at rest (0: not computed), and the share of nodes its mode moves.
  double lowest_eigenvalue_ratio = 0.0, lowest_mode_participation = 0.0;
  // Linear-algebra cost of the whole path (for benchmarks).
  double analyse_s = 0.0, factorize_s = 0.0, solve_s = 0.0;
  int factorizations = 0, lu_fallbacks = 0;  // LU: the tangent was indefinite
  int shifted_factorizations = 0;             // Cholesky attempts on K + σI after K itself failed
  int reused_solves = 0, cg_iterations = 0;  // Newton steps solved by CG on an earlier factor
  // One Cholesky factorisation of the tangent as CHOLMOD's analysis predicts it: flops and
  // nonzeros of L. What a run can cost starts here: the SPL pose's 284 GFlop took 6.1 s per
  // attempt on the two cores of the development machine, the 3CA's 16.8 GFlop (Hex20 2x2x2) 0.72 s.
  double factor_flops = 0.0, factor_nonzeros = 0.0;
};

/// Where a pressure path keeps its converged states as it goes (path_log.hpp), so that a rerun
/// resumes where a stopped one ended. An empty file: none (the cells and the RRA, seconds each).
struct PathCheckpoint {
  std::string file;
  std::string fingerprint;  // names the model the states belong to; a file of another one starts over
};

struct PressurePathSpec {
  /// Share of max_pressure_kPa of each loaded chamber (empty: all 1). The load
  /// level λ sets p_i = λ·f_i·p_max; the volume conjugate to λ·p_max is
  /// V = Σ f_i V_i, and it is this V (one chamber's volume when one is loaded)
  /// whose dp/dV detects a limit point.
  std::vector<double> pressure_fractions;
  /// Apply gravity (LoadState::gravity_scale 0 → 1) before the pressure ramp:
  /// self-weight is present from the start, not ramped with the pressure.
  bool gravity_preload = false;
  double max_pressure_kPa = 0.0;
  std::vector<double> output_pressures_kPa;  // sorted, the last equals max_pressure_kPa
  /// Coordinates per node: 2 for the axisymmetric (r, z), 3 for solids with z along the axis;
  /// 0 leaves the location of an unstable mode out of the diagnosis.
  int node_dimension = 0;
  // The unstable-branch guard on (NewtonSettings::max_indefinite_iterations), as in the 3D scenes:
  // past a limit point a step gives up after 4 indefinite iterations without progress instead of 20.
  NewtonSettings newton{.max_indefinite_iterations = 4};
  StepSettings steps;
  LimitPointSettings limit;
  PathCheckpoint checkpoint;
};

/// The tangent K at a converged state as the path hands it on, where the path has just assembled it
/// (Newton's last evaluation: the rest state's, a converged step's, volume control's landing; empty
/// for a state resumed from the log): a caller that needs K there need not assemble it again, nor
/// factorise it to solve with it. The path has just solved with K for dp/dV (pv_stiffness), so its
/// solver holds K's own factor or one on which CG solved with K to 10⁻¹⁰: CG on that factor solves
/// with K in a few sweeps where a factorisation of K costs dozens. Both valid during the call only.
struct ConvergedTangent {
  const SparseMatrix* matrix = nullptr;
  /// K d = b to ‖K d − b‖ ≤ tolerance·‖b‖ by CG on the path's factor (LinearSolver::solve_reusing_factor);
  /// false where the path holds no Cholesky factor of K's pattern, or CG meets non-positive curvature
  /// or does not converge within its budget: the caller then factorises K itself. Empty where matrix is.
  std::function<bool(const Vector& b, double tolerance, Vector& d)> solve_on_path_factor;
};

/// A converged state as the path hands it on: the state, its positions and the tangent there.
using PressureStateCallback = std::function<void(const PressureState&, const Vector&, const ConvergedTangent& tangent)>;

/// Ramps the pressures of `chambers` (entries of load.chamber_pressure_MPa) from 0
/// together; calls `on_state` for every converged step. With `spec.checkpoint`, every
/// converged step is logged as it comes, and the states of an earlier run's log are handed
/// to `on_state` again, in order, before the path goes on from the last of them.
PressurePathResult run_pressure_path(const EnergyProblem& problem, const std::vector<const ChamberPressureForm*>& chambers,
                                     LoadState& load,
                                     Vector& x, const PressurePathSpec& spec,
                                     const PressureStateCallback& on_state);

}  // namespace softarm::fem

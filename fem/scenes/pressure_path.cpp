#include "fem/scenes/pressure_path.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "fem/core/number_text.hpp"
#include "fem/scenes/path_log.hpp"
#include "fem/solver/lowest_modes.hpp"
#include "fem/solver/fold_estimate.hpp"
#include "fem/solver/volume_control.hpp"

namespace softarm::fem {
namespace {
constexpr double kMPaPerKPa = 1e-3;

/// The loaded chambers with their pressure fractions: V = Σ f_i V_i is the
/// volume conjugate to the load level (the load's work is λ p_max dV).
struct LoadedVolume {
  std::vector<const ChamberPressureForm*> chambers;
  std::vector<double> fractions;
  double volume(const Vector& x) const {
    double v = 0;
    for (std::size_t i = 0; i < chambers.size(); ++i) v += fractions[i] * chambers[i]->volume(x);
    return v;
  }
  Vector gradient(const Vector& x) const {
    Vector g = Vector::Zero(x.size());
    for (std::size_t i = 0; i < chambers.size(); ++i) g += fractions[i] * chambers[i]->volume_gradient(x);
    return g;
  }
};

// CG's relative residual for K⁻¹∇V on the held factor. dp/dV is a quadratic form in K⁻¹∇V, whose
// error after CG is the energy norm of the solve's error, of second order in the residual; the same
// K⁻¹∇V is the path's slope, which the predictor needs to a few digits. At 10⁻⁵ the thesis scenes'
// outputs stay within about 10⁻⁸ of a 10⁻¹⁰ solve's (the RRA's dp/dV 5·10⁻⁹), and a converged
// state is no longer factorised only to meet the tighter tolerance: the thesis SPL pose's cells 258 →
// 197 factorisations (docs/performance.md, dp/dV on the held factor).
constexpr double kComplianceCgTolerance = 1e-5;

// dp/dV = 1/(∇Vᵀ K⁻¹ ∇V) with K the tangent at x. The solver's last factorisation is at best
// that of the iterate before x (1e-5 of the displacement away where Newton stops on its
// contraction), and where Newton reuses factors (NewtonSettings::reuse_factor) several states
// old: K⁻¹∇V is solved with K by CG on that factor, or, where CG fails, from K's own
// factorisation. Without K (tangent_at_x null) the last factorisation serves as it is. With
// `compliance_out`, K⁻¹∇V as well (zero at prescribed dofs): the path's slope dx/dλ is p_max times it.
double pv_stiffness(const EnergyProblem& problem, const LoadedVolume& chamber, LinearSolver& solver,
                    const Vector& x, const NewtonSettings& newton, const SparseMatrix* tangent_at_x,
                    Vector* compliance_out = nullptr) {
  Vector g = chamber.gradient(x);
  problem.zero_prescribed(g);
  Vector compliance;
  if (!tangent_at_x) {
    compliance = solver.solve(g);
  } else if (!solver.solve_reusing_factor(*tangent_at_x, g, kComplianceCgTolerance, compliance)) {
    factorize_tangent(solver, *tangent_at_x, newton);
    compliance = solver.solve(g);
  }
  const double compliance_mm3_per_MPa = g.dot(compliance);
  if (compliance_out) *compliance_out = std::move(compliance);
  // A singular tangent (no solve): the chamber has lost its stiffness, dp/dV = 0 (a limit point).
  if (!std::isfinite(compliance_mm3_per_MPa)) return 0.0;
  return 1e3 / compliance_mm3_per_MPa;  // MPa → kPa
}

std::string fmt(double v, int precision = 4) { return number_text(v, precision); }

/// Where dp/dV of two converged states, extrapolated linearly in the pressure, falls to zero (+∞ where
/// it is not falling).
double stiffness_gone_kPa(const PressureState& prev, const PressureState& last) {
  const double k = last.pv_stiffness_kPa_per_mm3, fall = prev.pv_stiffness_kPa_per_mm3 - k;
  if (k <= 0.0) return last.pressure_kPa;
  if (!(fall > 0.0)) return std::numeric_limits<double>::infinity();
  return last.pressure_kPa + k * (last.pressure_kPa - prev.pressure_kPa) / fall;
}

/// The pressure maximum two converged states foresee: the vertex of the parabola p(V) through their
/// slopes dp/dV (near a smooth maximum p* − p ∝ (V* − V)², so dp/dV falls to zero as √(p* − p)):
/// p* = p₁ − (dp/dV)₁² / (2 d²p/dV²), d²p/dV² from the two slopes. p₁ where dp/dV is already gone;
/// +∞ where it is not falling.
double foreseen_peak_kPa(const PressureState& prev, const PressureState& last) {
  const double k = last.pv_stiffness_kPa_per_mm3;
  if (k <= 0.0) return last.pressure_kPa;
  const double dV = last.chamber_volume_mm3 - prev.chamber_volume_mm3;
  const double curvature = dV != 0.0 ? (k - prev.pv_stiffness_kPa_per_mm3) / dV : 0.0;
  if (!(curvature < 0.0)) return std::numeric_limits<double>::infinity();
  return last.pressure_kPa - k * k / (2 * curvature);
}

/// The lowest eigenvalue of the tangent at `x` (loads as they are), from a fresh factorisation;
/// 0 when the tangent is not positive definite there.
LowestModes lowest_mode_at(const EnergyProblem& problem, LinearSolver& solver, const Vector& x) {
  const Evaluation e = problem.evaluate(x, false, true);
  if (!e.status.ok || solver.factorize(e.hessian) != LinearSolver::Status::positive_definite) {
    LowestModes none;
    none.eigenvalues = {0.0};
    none.modes = {Vector::Zero(x.size())};
    return none;
  }
  return lowest_modes(solver, e.hessian, problem.is_prescribed(), 1);
}

/// "z = 84.2 mm, 11.3 mm from the axis" for node `node` of the reference positions.
std::string node_location(const Vector& X, int node, int dimension) {
  if (dimension == 2) return "r = " + fmt(X[2 * node], 3) + " mm, z = " + fmt(X[2 * node + 1], 3) + " mm";
  const double r = std::hypot(X[3 * node], X[3 * node + 1]);
  return "z = " + fmt(X[3 * node + 2], 3) + " mm, " + fmt(r, 3) + " mm from the axis";
}

/// The body's strain-energy form, which knows its elements and laws (null: the problem has none).
const ElasticForm* elastic_form_of(const EnergyProblem& problem) {
  for (const auto& form : problem.forms())
    if (const auto* elastic = dynamic_cast<const ElasticForm*>(form.get())) return elastic;
  return nullptr;
}

/// What the diagnosis of a stop reads: the path's last pressure-controlled state and the tools to
/// look at the tangent there.
struct StopContext {
  const EnergyProblem& problem;
  const ElasticForm* body;  // the solid's strain energy (null: none)
  const PressurePathSpec& spec;
  LinearSolver& solver;
  LoadState& load;
  const std::function<void(double)>& set_pressures;
  const Vector& x_rest;   // the reference of the lowest-mode check
  const Vector& x_stall;  // the last converged state under pressure control
  const PressureState& last;
  double ratio;           // dp/dV there over its initial value
  bool flattened, flattening;
};

/// A material failure first: the state reached, x, asks the silicone's law for more than it can
/// give (not Drucker stable: it softens under further strain there), whatever the tangent shows.
bool named_material_failure(const StopContext& c, const Vector& x, PressurePathResult& out) {
  const EnergyProblem& problem = c.problem;
  const PressurePathSpec& spec = c.spec;
  const double ratio = c.ratio;
  if (c.body) out.material = c.body->material_instability(x);
  if (out.material.found()) {
    out.outcome = PathOutcome::material_instability;
    const std::string where =
        spec.node_dimension > 0
            ? " (" + node_location(problem.reference_positions(), c.body->element_corner_node(out.material.element), spec.node_dimension) + ")"
            : "";
    // A few points at a corner of the section, where the strain is singular, start to fail at a
    // pressure that falls as the mesh is refined (docs/model.md, Named failures).
    const bool at_a_point = out.material.unstable_points * 100 < out.material.checked_points;
    out.diagnosis = "material instability at " + fmt(out.reached_pressure_kPa) + " kPa: at the state reached the " +
                    "silicone's law is not Drucker stable at " + std::to_string(out.material.unstable_points) + " of " +
                    std::to_string(out.material.checked_points) + " Gauss points, at isochoric principal stretches up to " +
                    fmt(out.material.max_stretch) + " (the smallest there " + fmt(out.material.min_stretch) +
                    ") in element " + std::to_string(out.material.element) + where +
                    ": the material softens under further strain, and pressure control stopped there (" +
                    to_string(out.path.failure) + ", dp/dV " + fmt(100 * ratio, 3) + " % of its initial value). " +
                    (at_a_point ? "Where so few points fail, the strain concentrates there (a corner of the section) "
                                  "and this pressure falls with a finer mesh: the finding is the law's range, not this "
                                  "pressure. "
                                : "") +
                    "`softarm material check` prints the law's stable stretches; a law fitted over a wider range of "
                    "stretch may carry the design further." + out.diagnosis;
    return true;
  }
  return false;
}

/// The tangent's lowest eigenvalue at the stall against its value at rest (a stall with the loaded
/// volume still stiff: is the lowest mode collapsing somewhere?), into out and in words.
std::string lowest_mode_note(const StopContext& c, PressurePathResult& out) {
  const EnergyProblem& problem = c.problem;
  const PressurePathSpec& spec = c.spec;
  const PressureState& last = c.last;
  LinearSolver& solver = c.solver;
  LoadState& load = c.load;
  const auto& set_pressures = c.set_pressures;
  const Vector& x_stall = c.x_stall;
  const Vector& x_rest = c.x_rest;
  std::string mode_note;
  if (spec.limit.check_lowest_mode && out.history.size() >= 2) {
    // Only now, past volume control (which settles a limit point without it); its loads are restored after.
    const double stall_level = last.pressure_kPa / spec.max_pressure_kPa, dirichlet = load.dirichlet_scale;
    set_pressures(stall_level);
    const LowestModes now = lowest_mode_at(problem, solver, x_stall);
    set_pressures(0.0);
    load.dirichlet_scale = 0.0;
    const LowestModes rest = lowest_mode_at(problem, solver, x_rest);
    set_pressures(out.reached_pressure_kPa / spec.max_pressure_kPa);
    load.dirichlet_scale = dirichlet;
    if (rest.eigenvalues[0] > 0) {
      out.lowest_eigenvalue_ratio = std::max(0.0, now.eigenvalues[0] / rest.eigenvalues[0]);
      mode_note = " The tangent's lowest eigenvalue is " + fmt(100 * out.lowest_eigenvalue_ratio, 3) +
                  " % of its value at rest";
      if (spec.node_dimension > 0 && now.eigenvalues[0] > 0) {
        const ModeExtent e = mode_extent(now.modes[0], spec.node_dimension);
        out.lowest_mode_participation = e.participation;
        mode_note += "; its mode moves " + fmt(100 * e.participation, 2) + " % of the nodes, most at " +
                     node_location(problem.reference_positions(), e.peak_node, spec.node_dimension);
      }
      // Sufficient, not necessary: a stiff local mode (a wall between two rings) can be failing while
      // a softer global one (the 3CA's bending) is still the lowest.
      if (out.lowest_eigenvalue_ratio >= spec.limit.lowest_mode_fraction)
        mode_note += ", so the last converged state is stable in its softest mode";
      mode_note += ".";
    }
  }
  return mode_note;
}

/// The pressure-volume curve flattened: ballooning, its peak estimated from the quadratic p(V) through
/// the last two states' slopes.
void name_ballooning(const StopContext& c, PressurePathResult& out, const std::string& volume_note) {
  const PressureState& last = c.last;
  out.outcome = PathOutcome::limit_point;
  out.limit_kind = LimitKind::pressure_volume;
  out.estimated_limit_pressure_kPa = last.pressure_kPa;
  if (out.history.size() >= 2) {
    const double peak = foreseen_peak_kPa(out.history[out.history.size() - 2], last);
    if (std::isfinite(peak)) out.estimated_limit_pressure_kPa = peak;
  }
  // Volume control may have climbed past the last pressure-controlled state: the peak is no lower.
  out.estimated_limit_pressure_kPa = std::max(out.estimated_limit_pressure_kPa, out.reached_pressure_kPa);
  out.diagnosis = "limit point (ballooning): the pressure-volume curve flattens at " + fmt(last.pressure_kPa) +
                  " kPa (dp/dV fell to " + fmt(100 * c.ratio, 3) + " % of its initial value" +
                  (last.tangent_positive_definite ? "" : ", tangent no longer positive definite") +
                  "); estimated peak pressure " + fmt(out.estimated_limit_pressure_kPa) +
                  " kPa. Pressure control cannot pass it; this is the burst mode of this design." + volume_note;
}

/// The tangent's lowest mode lost almost all its stiffness while dp/dV did not fall.
void name_lowest_mode_limit(const StopContext& c, PressurePathResult& out, const std::string& mode_note) {
  out.outcome = PathOutcome::limit_point;
  out.limit_kind = LimitKind::lowest_mode;
  out.estimated_limit_pressure_kPa = c.last.pressure_kPa;
  out.diagnosis = "local limit point at " + fmt(c.last.pressure_kPa) + " kPa: pressure control stopped (" +
                  to_string(out.path.failure) + ") where the tangent's lowest mode has lost almost all its "
                  "stiffness, while dp/dV of the loaded volume, " + fmt(100 * c.ratio, 3) +
                  " % of its initial value, is above the limit-point threshold: an instability the loaded volume "
                  "barely shows (in a 3CA, a chamber wall ballooning between two rings). The burst pressure is at "
                  "or just above this one." + mode_note;
}

/// One of the lowest eigenvalues falls to zero just ahead, at `fold_kPa`.
void name_fold(const StopContext& c, const FoldEstimate& fold, double fold_kPa, PressurePathResult& out,
               const std::string& mode_note, const std::string& volume_note) {
  const PressurePathSpec& spec = c.spec;
  const PressureState& last = c.last;
  out.outcome = PathOutcome::limit_point;
  out.limit_kind = LimitKind::fold;
  out.estimated_limit_pressure_kPa = fold_kPa;
  std::string where;
  if (spec.node_dimension > 0) {
    const ModeExtent e = mode_extent(fold.mode, spec.node_dimension);
    where = ", a mode that moves " + fmt(100 * e.participation, 2) + " % of the nodes, most at " +
            node_location(c.problem.reference_positions(), e.peak_node, spec.node_dimension);
  }
  out.diagnosis = "local limit point (fold) at " + fmt(fold_kPa) + " kPa: pressure control stopped at " +
                  fmt(last.pressure_kPa) + " kPa (" + to_string(out.path.failure) + ") where the tangent's eigenvalue " +
                  std::to_string(fold.mode_index + 1) + " of " + std::to_string(fold.eigenvalues_computed) + where +
                  ", falls to zero " + fmt(fold_kPa - last.pressure_kPa, 3) + " kPa ahead (" + fmt(fold.eigenvalue, 3) +
                  " N/mm, falling by " + fmt(-fold.rate / spec.max_pressure_kPa, 3) +
                  " N/mm per kPa: the square root of the distance to the fold). The path folds there, an instability "
                  "the loaded volume barely shows (dp/dV " + fmt(100 * c.ratio, 3) +
                  " % of its initial value): the burst pressure of this design." + mode_note + volume_note;
}

/// No limit point near, but the step can be cut no further without turning an element inside out: an
/// element failure, named with its place, not a stall.
void name_inversion(const StopContext& c, PressurePathResult& out, const std::string& mode_note,
                    const std::string& volume_note) {
  const PressurePathSpec& spec = c.spec;
  out.outcome = PathOutcome::element_inversion;
  out.inverted_element = out.path.failed_element;
  const std::string where =
      spec.node_dimension > 0 ? " (" + node_location(c.problem.reference_positions(),
                                                     c.body->element_corner_node(out.inverted_element),
                                                     spec.node_dimension) + ")"
                              : "";
  out.diagnosis = "element inversion at " + fmt(c.last.pressure_kPa) + " kPa: every step beyond it, down to the " +
                  "smallest increment, turns element " + std::to_string(out.inverted_element) + where +
                  " inside out (" + out.path.message + ") while dp/dV is " + fmt(100 * c.ratio, 3) +
                  " % of its initial value, so no limit point is near: the mesh cannot follow the deformation "
                  "there (a fold or a crease of the silicone, or a contact the model does not have). A finer mesh "
                  "(mesh.level) may carry it further." + mode_note + volume_note;
}

/// None of the above: a stall. Well above the threshold the path is plainly not at a limit point;
/// close to it, the curve is flattening and a limit point may lie just ahead.
void name_stall(const StopContext& c, PressurePathResult& out, const std::string& mode_note,
                const std::string& volume_note) {
  out.outcome = PathOutcome::stalled;
  out.diagnosis = "solver stalled at " + fmt(c.last.pressure_kPa) + " kPa (" + to_string(out.path.failure) + ": " +
                  out.path.message + ") while dp/dV is " + fmt(100 * c.ratio, 3) + " % of its initial value" +
                  (c.flattening ? ": the pressure-volume curve is flattening and a limit point (ballooning) may lie "
                                  "just ahead, but none was reached. "
                                : ", so this is not a limit point. ") +
                  "Retry with a finer mesh, a smaller solver.initial_increment_fraction or more Newton iterations." +
                  mode_note + volume_note;
}

/// Names why a path stopped short where volume control did not settle it: a material failure, a
/// limit point (dp/dV, the lowest mode, a fold just ahead), an inverted element, or a stall.
void name_the_stop(const StopContext& c, const Vector& x, PressurePathResult& out) {
  if (named_material_failure(c, x, out)) return;
  const PressurePathSpec& spec = c.spec;
  const std::string mode_note = c.flattening ? std::string() : lowest_mode_note(c, out);
  const bool local_instability = out.lowest_eigenvalue_ratio > 0 && out.lowest_eigenvalue_ratio < spec.limit.lowest_mode_fraction;
  const std::string volume_note = out.diagnosis;
  // A fold that neither dp/dV nor the lowest eigenvalue shows: one of the few lowest eigenvalues
  // falling to zero just ahead (fem/solver/fold_estimate.hpp), at the last converged state.
  FoldEstimate fold;
  if (!c.flattened && !local_instability && spec.limit.check_lowest_mode && spec.limit.fold_margin > 0 &&
      out.history.size() >= 2) {
    fold = estimate_fold(c.problem, c.solver, c.x_stall, c.last.pressure_kPa / spec.max_pressure_kPa, c.set_pressures,
                         spec.limit.fold_modes);
    c.set_pressures(out.reached_pressure_kPa / spec.max_pressure_kPa);
  }
  const double fold_kPa = std::max(fold.load * spec.max_pressure_kPa, out.reached_pressure_kPa);
  const bool fold_ahead = fold.found && fold_kPa <= c.last.pressure_kPa * (1 + spec.limit.fold_margin);
  if (c.flattened) name_ballooning(c, out, volume_note);
  else if (local_instability) name_lowest_mode_limit(c, out, mode_note);
  else if (fold_ahead) name_fold(c, fold, fold_kPa, out, mode_note, volume_note);
  else if (out.path.failure == Failure::inverted_element && out.path.failed_element >= 0 && c.body)
    name_inversion(c, out, mode_note, volume_note);
  else name_stall(c, out, mode_note, volume_note);
}

/// The solver's running totals into the result: taken after pressure control and again after
/// volume control, which uses the same solver.
void take_solver_costs(const LinearSolver& solver, PressurePathResult& out) {
  out.analyse_s = solver.analyse_seconds;
  out.factorize_s = solver.factorize_seconds;
  out.solve_s = solver.solve_seconds;
  out.factorizations = solver.factorizations;
  out.lu_fallbacks = solver.lu_fallbacks;
  out.shifted_factorizations = solver.shifted_factorizations;
  out.reused_solves = solver.reused_solves;
  out.cg_iterations = solver.cg_iterations;
  out.factor_flops = solver.factor_flops;
  out.factor_nonzeros = solver.factor_nonzeros;
}

/// What every step of the path shares: the problem, its loaded volume, the solver and the load.
struct PathContext {
  const EnergyProblem& problem;
  const PressurePathSpec& spec;
  const LoadedVolume& chamber;
  LinearSolver& solver;
  LoadState& load;
  const std::function<void(double)>& set_pressures;  // every loaded chamber at level · fraction · p_max
  const PressureStateCallback& on_state;
};

/// The tangent K at a converged state for on_state, with CG on the path's factor.
ConvergedTangent converged_tangent(const PathContext& c, const SparseMatrix& K) {
  return {&K, [&solver = c.solver, &K](const Vector& b, double tolerance, Vector& d) {
            return solver.solve_reusing_factor(K, b, tolerance, d);
          }};
}

/// An earlier run's states, handed on as they came; returns where the path goes on from the last
/// of them (x, the loads and the solver's factor set there).
PathStart resume_from(const PathContext& c, const std::vector<PathLogRecord>& resumed, Vector& x,
                      PressurePathResult& out) {
  for (const PathLogRecord& r : resumed) {
    out.history.push_back(r.state);
    if (c.on_state) c.on_state(r.state, r.x, {});
  }
  const PathLogRecord& last = resumed.back();
  x = last.x;
  c.load.gravity_scale = c.spec.gravity_preload ? 1.0 : 0.0;
  c.set_pressures(last.level);
  c.load.dirichlet_scale = last.level;
  PathStart start;
  start.level = last.level;
  start.increment = last.next_increment;
  // The first record is the state at rest, whose statistics are the gravity preload's.
  if (resumed.size() >= 2) start.stats = last.stats;
  for (std::size_t i = resumed.size() >= 3 ? resumed.size() - 3 : 0; i + 1 < resumed.size(); ++i)
    start.earlier.emplace_back(resumed[i].level, resumed[i].x);
  start.resumed = true;
  out.path.stats = resumed.front().stats;
  // The uninterrupted run holds a factor of the tangent there, which Newton's next step reuses
  // (NewtonSettings::reuse_factor): so does the resumed one (at rest, exactly the same one),
  // unless the earlier run had reached the end (a replay: no step left).
  const bool finished = !c.spec.output_pressures_kPa.empty() &&
                        c.spec.output_pressures_kPa.back() / c.spec.max_pressure_kPa - last.level <= 1e-12;
  if (!finished) c.solver.factorize(c.problem.evaluate(x, true, true).hessian);
  return start;
}

/// Self-weight first, in its own path (it may bend a soft body noticeably); false, with the
/// result's outcome and diagnosis set, where the body does not carry it.
bool preload_gravity(const PathContext& c, Vector& x, PressurePathResult& out) {
  PathCallbacks gravity;
  gravity.apply_load = [&](double level) { c.load.gravity_scale = level; };
  gravity.on_converged = [](double, const Vector&, bool, const NewtonReport&) {};
  // Self-weight barely deforms a soft actuator (3CA: 3° of sag): try it in one step
  // (the step controller still cuts back if Newton struggles). Ramping it like the
  // pressure cost 5 steps and ~17 factorisations on the thesis 3CA.
  StepSettings one_step = c.spec.steps;
  one_step.initial_increment = one_step.max_increment = 1.0;
  const PathResult preload = follow_load_path(c.problem, x, c.solver, {1.0}, gravity, c.spec.newton, one_step);
  out.path.stats = preload.stats;
  if (preload.completed) return true;
  out.path = preload;
  out.outcome = PathOutcome::stalled;
  out.diagnosis = "the body does not carry its own weight: the gravity preload stopped at " +
                  fmt(100 * preload.reached_level, 3) + " % (" + to_string(preload.failure) + ": " + preload.message +
                  "). Check the supports and the materials.";
  return false;
}

/// The unloaded state, the reference of "flattening": its dp/dV is the first history entry.
void record_rest_state(const PathContext& c, const Vector& x, std::optional<PathLog>& log, PressurePathResult& out) {
  const Evaluation e0 = c.problem.evaluate(x, true, true);
  c.solver.factorize(e0.hessian);
  const PressureState s0{0.0, c.chamber.volume(x), pv_stiffness(c.problem, c.chamber, c.solver, x, c.spec.newton, nullptr),
                         c.solver.status() == LinearSolver::Status::positive_definite, 0, true};
  out.history.push_back(s0);
  if (c.on_state) c.on_state(s0, x, converged_tangent(c, e0.hessian));
  if (log) log->append({0.0, c.spec.steps.initial_increment, s0, out.path.stats, x});
}

/// The last converged states of pressure control, (level, x), oldest first, at most three: where a
/// path handed over to volume control goes on by pressure control, its start and predictor states.
using RecentStates = std::vector<std::pair<double, Vector>>;

/// When pressure control hands the path to volume control ahead of a maximum (LimitPointSettings):
/// never; before any step past the pressure where dp/dV, extrapolated, falls to zero; or before
/// such a step only once a step past the last converged state has failed from every start.
enum class HandOver { never, ahead, after_failure };

HandOver hand_over_of(const LimitPointSettings& limit) {
  if (!limit.follow_with_volume_control) return HandOver::never;
  if (limit.hand_over_ahead) return HandOver::ahead;
  return limit.hand_over_after_failure ? HandOver::after_failure : HandOver::never;
}

/// Whether a step past the path's last converged state (at `level`) has failed from every start.
bool failed_past(const PathStatistics& stats, double level) {
  return std::any_of(stats.failed_levels.begin(), stats.failed_levels.end(),
                     [&](double failed) { return failed > level + 1e-12; });
}

/// Pressure control from `start` through the output levels: every converged state into the
/// history (and the log), the preload's statistics added to the path's. Unless `hand_over` is
/// never, it stops (out.path.stopped) before a step past the pressure where dp/dV, extrapolated
/// linearly from the last two states, falls to zero (HandOver).
void follow_pressure(const PathContext& c, Vector& x, const PathStart& start, std::optional<PathLog>& log,
                     HandOver hand_over, RecentStates& recent, PressurePathResult& out) {
  std::vector<double> levels;
  for (double p : c.spec.output_pressures_kPa) levels.push_back(p / c.spec.max_pressure_kPa);
  recent = start.earlier;
  recent.emplace_back(start.level, x);
  PathCallbacks callbacks;
  std::pair<double, const Vector*> converged{0.0, nullptr};  // the state on_converged was last given
  // dx/dλ there: the load is λ p_max Σ f_i V_i, so K dx/dλ = p_max ∇V (not finite where K is singular,
  // and then the predictor takes its parabola: predict_with_slope).
  Vector slope;
  callbacks.apply_load = [&](double level) {
    c.set_pressures(level);
    c.load.dirichlet_scale = level;
  };
  callbacks.on_converged = [&](double level, const Vector& xs, bool is_output, const NewtonReport& report) {
    PressureState s{level * c.spec.max_pressure_kPa, c.chamber.volume(xs),
                    pv_stiffness(c.problem, c.chamber, c.solver, xs, c.spec.newton, &report.last.hessian, &slope),
                    report.tangent_positive_definite, report.iterations, is_output};
    slope *= c.spec.max_pressure_kPa * kMPaPerKPa;
    out.history.push_back(s);
    if (c.on_state) c.on_state(s, xs, converged_tangent(c, report.last.hessian));
    converged = {level, &xs};
    recent.emplace_back(level, xs);
    if (recent.size() > 3) recent.erase(recent.begin());
  };
  callbacks.slope = [&slope] { return slope; };
  if (hand_over != HandOver::never)
    callbacks.stop_before = [&, hand_over](double next_level, const PathStatistics& stats) {
      const std::size_t n = out.history.size();
      if (n < 2) return false;
      const double level = out.history.back().pressure_kPa / c.spec.max_pressure_kPa;
      if (hand_over == HandOver::after_failure && !failed_past(stats, level)) return false;
      return stiffness_gone_kPa(out.history[n - 2], out.history[n - 1]) < next_level * c.spec.max_pressure_kPa;
    };
  if (log)
    callbacks.on_increment = [&](double next_increment, const PathStatistics& stats) {
      log->append({converged.first, next_increment, out.history.back(), stats, *converged.second});
    };
  const PathStatistics preload_stats = out.path.stats;
  out.path = follow_load_path(c.problem, x, c.solver, levels, callbacks, c.spec.newton, c.spec.steps, start);
  out.path.stats.steps += preload_stats.steps;
  out.path.stats.newton_iterations += preload_stats.newton_iterations;
  out.path.stats.cutbacks += preload_stats.cutbacks;
  out.path.stats.second_starts += preload_stats.second_starts;
  take_solver_costs(c.solver, out);
  out.reached_pressure_kPa = out.history.back().pressure_kPa;
}

/// Volume control from the last converged state (x, at the history's last pressure) until it passes
/// the pressure maximum or the level rises to `ceiling`: its states past the last one into
/// beyond_limit; x and `level` at the traced state of the largest pressure (at least the last one's).
/// Its first volume step is `first_step_fraction` of the last pressure step's volume.
VolumeControlResult trace_volume(const PathContext& c, Vector& x, double& level, double ceiling,
                                 bool stop_at_bifurcation, double first_step_fraction, PressurePathResult& out) {
  const PressurePathSpec& spec = c.spec;
  const PressureState& last = out.history.back();
  const PressureState& prev = out.history[out.history.size() - 2];
  level = last.pressure_kPa / spec.max_pressure_kPa;
  const double step =
      first_step_fraction * std::max(last.chamber_volume_mm3 - prev.chamber_volume_mm3, 1e-4 * last.chamber_volume_mm3);
  VolumeControlProblem vp;
  vp.apply_level = c.set_pressures;
  vp.volume = [&](const Vector& xs) { return c.chamber.volume(xs); };
  vp.volume_gradient = [&](const Vector& xs) { return c.chamber.gradient(xs); };
  vp.pressure_per_level_MPa = spec.max_pressure_kPa * kMPaPerKPa;
  const VolumeControlState before{prev.pressure_kPa / spec.max_pressure_kPa, prev.chamber_volume_mm3, 0,
                                  prev.tangent_positive_definite};
  VolumeControlSettings vc_settings;
  vc_settings.verbose = spec.steps.verbose;
  vc_settings.augmented_cg = spec.limit.volume_control_by_cg;
  vc_settings.level_ceiling = ceiling;
  vc_settings.stop_at_bifurcation = stop_at_bifurcation;
  const VolumeControlResult vc = follow_volume(c.problem, x, level, c.solver, vp, step, &before, vc_settings);
  for (std::size_t i = 1; i < vc.states.size(); ++i)
    out.beyond_limit.push_back({vc.states[i].level * spec.max_pressure_kPa, vc.states[i].volume,
                                std::isnan(vc.states[i].level_slope_per_mm3)
                                    ? 0.0
                                    : vc.states[i].level_slope_per_mm3 * spec.max_pressure_kPa,
                                vc.states[i].tangent_positive_definite, vc.states[i].iterations, false});
  out.path.stats.newton_iterations += vc.newton_iterations;
  take_solver_costs(c.solver, out);
  out.reached_pressure_kPa = level * spec.max_pressure_kPa;
  return vc;
}

/// Volume control passed the pressure maximum: a traced limit point, the returned state the one at
/// the largest pressure. `how` says how pressure control came to hand it over.
void name_traced_limit(const PathContext& c, const VolumeControlResult& vc, const PressureState& last,
                       const std::string& how, PressurePathResult& out) {
  out.outcome = PathOutcome::limit_point;
  out.limit_kind = LimitKind::traced;
  out.estimated_limit_pressure_kPa = vc.peak_level * c.spec.max_pressure_kPa;
  out.diagnosis = "limit point (ballooning) at " + fmt(out.estimated_limit_pressure_kPa) +
                  " kPa: chamber-volume control followed the path past the pressure maximum (" + vc.message +
                  ", the loaded volume growing from " + fmt(last.chamber_volume_mm3) + " to " +
                  fmt(vc.states.back().volume) + " mm³)" + how + ". Pressure control cannot pass it; this is the "
                  "burst mode of this design. The returned state is the one at the largest pressure.";
}

/// Where pressure control stopped before a step past the pressure where dp/dV, extrapolated, falls to
/// zero (LimitPointSettings::hand_over_ahead, hand_over_after_failure): true where volume control
/// passes a maximum before the next output level (a traced limit point); false, with x and the loads
/// back at the handed-over state and what volume control found in the diagnosis, where it does not.
bool traced_ahead(const PathContext& c, Vector& x, PressurePathResult& out) {
  const PressurePathSpec& spec = c.spec;
  const PressureState last = out.history.back();
  const double last_level = last.pressure_kPa / spec.max_pressure_kPa;
  double ceiling = 1.0;  // the next output level
  for (const double p : spec.output_pressures_kPa)
    if (p / spec.max_pressure_kPa > last_level + 1e-12) {
      ceiling = p / spec.max_pressure_kPa;
      break;
    }
  const double stiffness_gone = stiffness_gone_kPa(out.history[out.history.size() - 2], last);
  const Vector x_over = x;
  double level = last_level;
  out.handed_over_kPa = last.pressure_kPa;
  // A quarter of the last pressure step's volume first: the hand-over foresees the maximum within
  // the next pressure step, and near it dV/dp grows, so a whole step lands past the top too far to
  // place it and follow_volume traces it again with quarter steps (the thesis 3CA's free end cell:
  // 287 and 432 mm³ steps, 8 Newton iterations and 520 CG iterations spent before the retrace).
  // Where the maximum is further the steps grow by half after each easy one, which costs: the
  // ballooning tube handed over after a failed step, its top 1.5 steps' volume away, 135 -> 158
  // Newton iterations (docs/performance.md, "The first volume step").
  const VolumeControlResult vc = trace_volume(c, x, level, ceiling, true, 0.25, out);
  if (vc.passed_peak) {
    const bool after_failure = failed_past(out.path.stats, last_level);
    name_traced_limit(c, vc, last,
                      "; pressure control handed the path over at " + fmt(last.pressure_kPa) + " kPa, " +
                          (after_failure ? "where a step past it had failed and " : "") +
                          "its dp/dV extrapolated to zero at " + fmt(stiffness_gone) + " kPa",
                      out);
    return true;
  }
  x = x_over;
  c.set_pressures(last_level);
  out.beyond_limit.clear();
  out.reached_pressure_kPa = last.pressure_kPa;
  out.diagnosis = " Volume control from " + fmt(last.pressure_kPa) + " kPa, where dp/dV extrapolated to zero at " +
                  fmt(stiffness_gone) + " kPa, found no maximum before " + fmt(ceiling * spec.max_pressure_kPa) +
                  " kPa (" + vc.message + "); pressure control went on from there.";
  return false;
}

/// Volume control found no maximum ahead of the handed-over state: pressure control goes on from
/// there, its step and predictor as they were, without handing over again.
void go_on_by_pressure(const PathContext& c, Vector& x, RecentStates& recent, std::optional<PathLog>& log,
                       PressurePathResult& out) {
  PathStart start;
  start.level = recent.back().first;
  x = recent.back().second;
  start.increment = out.path.next_level - start.level;
  start.earlier.assign(recent.begin(), recent.end() - 1);
  start.stats = out.path.stats;
  start.resumed = true;  // the outputs up to the handed-over state are reached
  out.path.stats = {};
  c.set_pressures(start.level);
  c.load.dirichlet_scale = start.level;
  c.solver.factorize(c.problem.evaluate(x, true, true).hessian);
  follow_pressure(c, x, start, log, HandOver::never, recent, out);
}

/// Past a stall of pressure control by prescribing the chamber volume instead: true where that
/// settles the answer (a traced limit point, or the requested pressure reached); false where the
/// stop is still to be named, with what volume control saw in the diagnosis and x, the loads and
/// reached pressure at the state to name it by.
bool settled_by_volume_control(const PathContext& c, Vector& x, const Vector& x_stall, double ratio,
                               PressurePathResult& out) {
  const PressurePathSpec& spec = c.spec;
  const PressureState last = out.history.back();
  double level = 0.0;
  const VolumeControlResult vc = trace_volume(c, x, level, 1.0, false, 1.0, out);
  if (vc.passed_peak) {
    name_traced_limit(c, vc, last, "", out);
    return true;
  }
  if (level < 1.0) {
    // No maximum: keep the pressure-controlled diagnosis, with what volume control saw.
    out.diagnosis = " Volume control from there: " + vc.message + ".";
    return false;
  }
  Vector x_end = x;
  c.set_pressures(1.0);
  const NewtonReport landing = solve_newton(c.problem, x_end, c.solver, spec.newton);
  if (!landing.converged) {
    // Volume control climbed past the requested pressure but Newton cannot land on it (a solver
    // limited to a few iterations): no state at the requested pressure, so no answer; the stall
    // of pressure control is reported at its last state.
    x = x_stall;
    c.set_pressures(last.pressure_kPa / spec.max_pressure_kPa);
    out.reached_pressure_kPa = last.pressure_kPa;
    out.beyond_limit.clear();  // its states overshoot the requested pressure: not part of the answer
    out.diagnosis = " Volume control from there climbed past the requested pressure without a maximum (" +
                    vc.message + "), where Newton could not land on it (" + landing.message + ").";
    return false;
  }
  // No maximum, and the path climbed to the requested pressure: the stall was numerical (a thin
  // cap that balloons and tightens again, a Newton step pressure control could not take). Volume
  // control stops at the first state at or above it; Newton at exactly the requested pressure
  // from there lands on it (the branch is stable again).
  x = x_end;
  const PressureState s{spec.max_pressure_kPa, c.chamber.volume(x),
                        pv_stiffness(c.problem, c.chamber, c.solver, x, spec.newton, nullptr),
                        landing.tangent_positive_definite, landing.iterations, true};
  take_solver_costs(c.solver, out);
  out.outcome = PathOutcome::completed;
  out.reached_pressure_kPa = s.pressure_kPa;
  out.diagnosis = "reached " + fmt(s.pressure_kPa) + " kPa: pressure control stopped at " + fmt(last.pressure_kPa) +
                  " kPa (" + to_string(out.path.failure) + ", dp/dV " + fmt(100 * ratio, 3) +
                  " % of its initial value) and chamber-volume control carried the path on to the requested "
                  "pressure without a maximum (" + vc.message + ")";
  out.history.push_back(s);
  if (c.on_state) c.on_state(s, x, converged_tangent(c, landing.last.hessian));
  return true;
}
}  // namespace

PressurePathResult run_pressure_path(const EnergyProblem& problem, const std::vector<const ChamberPressureForm*>& chambers,
                                     LoadState& load, Vector& x, const PressurePathSpec& spec,
                                     const PressureStateCallback& on_state) {
  PressurePathResult out;
  LinearSolver solver;
  LoadedVolume chamber{chambers, spec.pressure_fractions};
  if (chamber.fractions.empty()) chamber.fractions.assign(chambers.size(), 1.0);
  if (chamber.fractions.size() != chambers.size())
    throw std::logic_error("run_pressure_path: one pressure fraction per chamber");
  const std::function<void(double)> set_pressures = [&](double level) {
    for (std::size_t i = 0; i < chambers.size(); ++i) {
      const auto c = static_cast<std::size_t>(chambers[i]->chamber());
      if (load.chamber_pressure_MPa.size() <= c) load.chamber_pressure_MPa.resize(c + 1, 0.0);
      load.chamber_pressure_MPa[c] = level * chamber.fractions[i] * spec.max_pressure_kPa * kMPaPerKPa;
    }
  };
  const PathContext c{problem, spec, chamber, solver, load, set_pressures, on_state};

  std::optional<PathLog> log;
  if (!spec.checkpoint.file.empty()) {
    log.emplace(spec.checkpoint.file, spec.checkpoint.fingerprint, x.size());
    out.checkpoint_discarded = log->discarded_reason();
  }
  // Taken out of the log and dropped once replayed: the thesis SPL's are ~150 MB.
  std::vector<PathLogRecord> resumed = log ? log->take_resumed() : std::vector<PathLogRecord>{};
  out.resumed_states = static_cast<int>(resumed.size());
  const bool from_rest = resumed.empty();

  // 1. The unloaded state (after self-weight), or where an earlier run stopped.
  set_pressures(0.0);
  load.dirichlet_scale = 0.0;
  load.gravity_scale = 0.0;
  problem.apply_constraints(x, 0.0);
  PathStart start;
  if (!from_rest) start = resume_from(c, resumed, x, out);
  else if (spec.gravity_preload && !preload_gravity(c, x, out)) return out;
  const Vector x_rest = from_rest ? x : resumed.front().x;  // the reference for the lowest-mode check at a stall
  resumed = {};
  if (from_rest) record_rest_state(c, x, log, out);

  // 2. Pressure control through the output pressures, handed to volume control ahead of a maximum.
  RecentStates recent;
  follow_pressure(c, x, start, log, hand_over_of(spec.limit), recent, out);
  std::string ahead_note;  // what volume control ahead of a maximum found where it did not settle the path
  if (out.path.stopped) {
    if (traced_ahead(c, x, out)) return out;
    ahead_note = out.diagnosis;
    out.diagnosis.clear();
    go_on_by_pressure(c, x, recent, log, out);
  }
  if (out.path.completed) {
    out.outcome = PathOutcome::completed;
    out.diagnosis = "reached " + fmt(spec.max_pressure_kPa) + " kPa" + (ahead_note.empty() ? "" : "." + ahead_note);
    return out;
  }

  // 3. A stop: past it by volume control where the pressure-volume curve flattens, else named.
  const PressureState last = out.history.back();
  const double ratio = last.pv_stiffness_kPa_per_mm3 / out.history.front().pv_stiffness_kPa_per_mm3;
  const bool flattened = ratio < spec.limit.stiffness_fraction || !last.tangent_positive_definite;
  const bool flattening = ratio < 5 * spec.limit.stiffness_fraction;
  const bool try_volume_control = ratio < spec.limit.volume_control_fraction;
  const Vector x_stall = x;  // volume control moves x; the lowest-mode check looks at the stall
  if ((flattened || try_volume_control) && spec.limit.follow_with_volume_control && out.history.size() >= 2 &&
      settled_by_volume_control(c, x, x_stall, ratio, out)) {
    out.diagnosis += ahead_note;
    return out;
  }
  const StopContext context{problem, elastic_form_of(problem), spec, solver, load, set_pressures, x_rest, x_stall,
                            last, ratio, flattened, flattening};
  name_the_stop(context, x, out);
  out.diagnosis += ahead_note;
  return out;
}

}  // namespace softarm::fem

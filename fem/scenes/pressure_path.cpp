#include "fem/scenes/pressure_path.hpp"

#include <cmath>
#include <sstream>

namespace softarm::fem {
namespace {
constexpr double kMPaPerKPa = 1e-3;

// dp/dV = 1/(∇Vᵀ K⁻¹ ∇V), using the solver's last factorisation of the tangent.
double pv_stiffness(const EnergyProblem& problem, const ChamberPressureForm& chamber, LinearSolver& solver,
                    const Vector& x) {
  Vector g = chamber.volume_gradient(x);
  problem.zero_prescribed(g);
  const double compliance_mm3_per_MPa = g.dot(solver.solve(g));
  return 1e3 / compliance_mm3_per_MPa;  // MPa → kPa
}

std::string fmt(double v, int precision = 4) {
  std::ostringstream s;
  s.precision(precision);
  s << v;
  return s.str();
}
}  // namespace

PressurePathResult run_pressure_path(const EnergyProblem& problem, const ChamberPressureForm& chamber, LoadState& load,
                                     Vector& x, const PressurePathSpec& spec,
                                     const std::function<void(const PressureState&, const Vector&)>& on_state) {
  PressurePathResult out;
  LinearSolver solver;
  if (load.chamber_pressure_MPa.size() <= static_cast<std::size_t>(spec.chamber))
    load.chamber_pressure_MPa.resize(spec.chamber + 1, 0.0);

  // The unloaded state: its stiffness is the reference for "flattening".
  load.chamber_pressure_MPa[spec.chamber] = 0.0;
  load.dirichlet_scale = 0.0;
  problem.apply_constraints(x, 0.0);
  {
    const Evaluation e0 = problem.evaluate(x, true, true);
    solver.factorize(e0.hessian);
    PressureState s0{0.0, chamber.volume(x), pv_stiffness(problem, chamber, solver, x),
                     solver.status() == LinearSolver::Status::positive_definite, 0, true};
    out.history.push_back(s0);
    if (on_state) on_state(s0, x);
  }

  std::vector<double> levels;
  for (double p : spec.output_pressures_kPa) levels.push_back(p / spec.max_pressure_kPa);
  PathCallbacks callbacks;
  callbacks.apply_load = [&](double level) {
    load.chamber_pressure_MPa[spec.chamber] = level * spec.max_pressure_kPa * kMPaPerKPa;
    load.dirichlet_scale = level;
  };
  callbacks.on_converged = [&](double level, const Vector& xs, bool is_output, const NewtonReport& report) {
    PressureState s{level * spec.max_pressure_kPa, chamber.volume(xs), pv_stiffness(problem, chamber, solver, xs),
                    report.tangent_positive_definite, report.iterations, is_output};
    out.history.push_back(s);
    if (on_state) on_state(s, xs);
  };
  out.path = follow_load_path(problem, x, solver, levels, callbacks, spec.newton, spec.steps);
  out.analyse_s = solver.analyse_seconds;
  out.factorize_s = solver.factorize_seconds;
  out.solve_s = solver.solve_seconds;
  out.factorizations = solver.factorizations;
  out.lu_fallbacks = solver.lu_fallbacks;
  out.reached_pressure_kPa = out.history.back().pressure_kPa;
  if (out.path.completed) {
    out.outcome = PathOutcome::completed;
    out.diagnosis = "reached " + fmt(spec.max_pressure_kPa) + " kPa";
    return out;
  }

  const PressureState& last = out.history.back();
  const double k0 = out.history.front().pv_stiffness_kPa_per_mm3;
  const double ratio = last.pv_stiffness_kPa_per_mm3 / k0;
  const bool flattened = ratio < spec.limit.stiffness_fraction || !last.tangent_positive_definite;
  if (flattened) {
    out.outcome = PathOutcome::limit_point;
    out.estimated_limit_pressure_kPa = last.pressure_kPa;
    // Peak of the quadratic p(V) through the last two states' slopes.
    if (out.history.size() >= 2) {
      const PressureState& prev = out.history[out.history.size() - 2];
      const double dV = last.chamber_volume_mm3 - prev.chamber_volume_mm3;
      const double c = dV != 0.0 ? (last.pv_stiffness_kPa_per_mm3 - prev.pv_stiffness_kPa_per_mm3) / dV : 0.0;
      if (c < 0.0 && last.pv_stiffness_kPa_per_mm3 > 0.0)
        out.estimated_limit_pressure_kPa = last.pressure_kPa - last.pv_stiffness_kPa_per_mm3 * last.pv_stiffness_kPa_per_mm3 / (2 * c);
    }
    out.diagnosis = "limit point (ballooning): the pressure-volume curve flattens at " + fmt(last.pressure_kPa) +
                    " kPa (dp/dV fell to " + fmt(100 * ratio, 3) + " % of its initial value" +
                    (last.tangent_positive_definite ? "" : ", tangent no longer positive definite") +
                    "); estimated peak pressure " + fmt(out.estimated_limit_pressure_kPa) +
                    " kPa. Pressure control cannot pass it; this is the burst mode of this design.";
  } else {
    out.outcome = PathOutcome::stalled;
    // Well above the threshold the path is plainly not at a limit point; close to it,
    // the curve is flattening and a limit point may lie just ahead.
    const bool flattening = ratio < 5 * spec.limit.stiffness_fraction;
    out.diagnosis = "solver stalled at " + fmt(last.pressure_kPa) + " kPa (" + to_string(out.path.failure) + ": " +
                    out.path.message + ") while dp/dV is " + fmt(100 * ratio, 3) + " % of its initial value" +
                    (flattening ? ": the pressure-volume curve is flattening and a limit point (ballooning) may lie "
                                  "just ahead, but none was reached. "
                                : ", so this is not a limit point. ") +
                    "Retry with a finer mesh, a smaller solver.initial_increment_fraction or more Newton iterations.";
  }
  return out;
}

}  // namespace softarm::fem

#pragma once
// Chamber-volume control: follows an equilibrium path by prescribing the
// loaded volume V = Σ f_i V_i instead of the load level λ (the pressure), so
// it passes the pressure maximum where pressure control must stop (ballooning:
// the p–V curve turns over). The unknowns are the positions x and λ; the
// equations are equilibrium and the volume constraint,
//
//   r(x, λ) = ∇Π(x; λ) = 0,      V(x) − V* = 0,
//
// with ∂r/∂λ = −P ∇V (the chamber forms' potential is −λ·P·V, P the peak
// pressure in MPa). Newton on both, by the bordering method: with K = ∂r/∂x
// (the exact tangent, pressure stiffness included),
//   K a = −r,   K b = P ∇V,   δλ = (V* − V − ∇V·a) / (∇V·b),   δx = a + δλ b.
// The bordered matrix [K, −P∇V; ∇Vᵀ, 0] stays regular at the pressure maximum,
// where K alone turns singular; past it K is indefinite and the linear solver
// takes its LU route, or (augmented_cg) CG on K + α∇V∇Vᵀ (Crisfield,
// Non-linear Finite Element Analysis of Solids and Structures, vol. 1,
// §9.2–9.3: displacement control by a single constraint; here the constraint
// is the chamber volume, the quantity a syringe pump would prescribe).
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "fem/assembly/energy_problem.hpp"
#include "fem/solver/linear_solver.hpp"

namespace softarm::fem {

struct VolumeControlSettings {
  int max_steps = 60;
  int max_iterations = 20;
  double residual_tolerance = 1e-8;  // ‖r‖ / force scale, as Newton's
  double volume_tolerance = 1e-10;   // |V − V*| / V*
  double update_tolerance = 1e-6;    // ‖δx‖ / max(‖x − X‖, 1e-3 mm), as Newton's: with the residual on its
                                     // round-off floor (below 100 × residual_tolerance, no longer falling),
                                     // a settled update means converged
  double drop_fraction = 2e-4;       // the maximum is passed once λ falls this far below it: 10⁴ times the
                                     // equilibrium tolerance, so a fall is a fall (a Dragon Skin 10 RRA's
                                     // p(V) top is that flat before its Newton iterations stall)
  double level_ceiling = 1.0;        // stop where the level rises to this one (the full load, or the next output
                                     // level of a path handed over ahead of its maximum) without a maximum
  // Past a maximum by a fall of more than retrace_fall_fraction (10 drop_fractions), or with the
  // parabola's vertex more than retrace_vertex_fraction above the largest traced state, the steps were
  // too long to place the maximum: the top is traced again with quarter steps, at most max_retraces times.
  double retrace_fall_fraction = 2e-3, retrace_vertex_fraction = 1e-4;
  int max_retraces = 2;
  // Stop at the first state whose tangent is indefinite while dλ/dV is still positive (a bifurcation
  // from the traced branch). Known only where K is factorised: augmented_cg certifies indefiniteness
  // by dλ/dV < 0 alone, so it cannot see one.
  bool stop_at_bifurcation = false;
  bool verbose = false;              // print each volume step's Newton iterations (print_convergence_tables)
  // Solve each Newton iteration's two systems by CG on K + α∇V∇Vᵀ, preconditioned with the
  // Cholesky factor of the starting tangent, and factorise K only where that fails
  // (volume_control.cpp). For 3D bodies, whose indefinite K costs an LU of seconds; the
  // axisymmetric scenes' LU is cheap and exact.
  bool augmented_cg = false;
};

struct VolumeControlState {
  double level = 0, volume = 0;
  int iterations = 0;
  bool tangent_positive_definite = true;
  /// dλ/dV = 1/(P ∇Vᵀ K⁻¹ ∇V) from the exact tangent of the last Newton iteration, 1/mm³
  /// (NaN where not computed): negative only past a pressure maximum (K indefinite in a mode
  /// that changes the volume); a negative eigenvalue in a mode the volume does not see (a
  /// bifurcation) leaves it positive.
  double level_slope_per_mm3 = std::numeric_limits<double>::quiet_NaN();
};

struct VolumeControlResult {
  bool passed_peak = false;
  double peak_level = 0, peak_volume = 0;  // vertex of the parabola through the three states around the largest λ
  std::vector<VolumeControlState> states;  // every converged state, in path order
  std::string message;                     // why the continuation stopped
  int newton_iterations = 0;
};

struct VolumeControlProblem {
  std::function<void(double)> apply_level;                 // sets the loads for level λ
  std::function<double(const Vector&)> volume;             // V(x)
  std::function<Vector(const Vector&)> volume_gradient;    // ∇V(x), full dof vector
  double pressure_per_level_MPa = 0;                       // P: the pressure at λ = 1
};

/// From the equilibrium (x, level) follows the path in volume steps starting at
/// `initial_volume_step` until the level has fallen `drop_fraction` below its
/// maximum, or has fallen at all at a state whose own dλ/dV is negative (the
/// tangent's answer, not the noise of a flat top), rises to settings.level_ceiling
/// or more (the chamber stiffens again), or the steps run out. `previous`: the equilibrium
/// state before (x, level) on the path, if known, so a maximum at (x, level)
/// itself is recognised. On return x holds the state
/// with the largest level and `level` its level; `states` starts with (x, level).
VolumeControlResult follow_volume(const EnergyProblem& problem, Vector& x, double& level, LinearSolver& solver,
                                  const VolumeControlProblem& vp, double initial_volume_step,
                                  const VolumeControlState* previous = nullptr,
                                  const VolumeControlSettings& settings = {});

}  // namespace softarm::fem

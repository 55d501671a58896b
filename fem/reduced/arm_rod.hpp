#pragma once
// The reduced model of softarm's assemblies: a planar, extensible Euler–Bernoulli
// rod with finite-strain fibre sections (rod_section.hpp, section_equilibrium.hpp),
// clamped at S = 0, made of pieces in series: RRAs, 3CA segments and rigid
// connectors. Loads: chamber pressures (axial forces at the chambers' axes),
// gravity on the distributed mass, a tip mass. Large rotations are exact (the
// shape is integrated from the curvature); the sections' response is the
// materials' own uniaxial law, so the stiffening or softening of the silicone
// and the Drucker limit are in the model.
//
// Solution by shooting: with no support but the clamp, the internal force at a
// section is the weight beyond it, known before the shape; only the clamp's
// moment is unknown. Integrating from the clamp (each section's equilibrium
// gives its stretch and curvature, the shape follows, the moment changes by
// m' = −r' × F), the moment at the free tip must vanish: a scalar equation in
// the clamp moment, solved by the secant method safeguarded by a bracket
// (shooting_root.hpp). Loads are followed by continuation with
// step halving; a step that cannot be completed is a limit point (the arm
// cannot hold the load) or a section failure, reported with its reason.
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "fem/materials/material.hpp"
#include "fem/reduced/fibre_law.hpp"
#include "fem/reduced/rod_layout.hpp"
#include "fem/reduced/rod_section.hpp"
#include "fem/reduced/section_equilibrium.hpp"

namespace softarm::fem {

struct RodLoad {
  /// Per piece (connectors ignored): chamber pressures 1..3 (an RRA uses the first).
  std::vector<std::array<double, 3>> chamber_pressure_kPa;
  std::array<double, 2> gravity_m_s2{0, 0};  // in the plane of the rod
  double tip_mass_kg = 0;
  double clamp_angle_rad = -1.5707963267948966;  // axis direction at the clamp (default: hanging, −Z)
};

struct RodState {
  std::vector<double> theta, stretch, curvature;  // per node
  std::vector<double> x, z;                       // node positions, mm (clamp at the origin)
  std::vector<double> moment;                     // bending moment per node, N·mm
  bool converged = false;
  std::string diagnosis;
  int newton_iterations = 0;                      // shooting evaluations (shooting_root.hpp)
};

class ArmRod {
 public:
  explicit ArmRod(ArmRodSpec spec);

  /// Equilibrium under `load`, by Newton from `start` (or the straight rod).
  RodState solve(const RodLoad& load, const RodState* start = nullptr) const;
  /// Follows the load from `from` (or the unloaded straight rod) to `load`: gravity
  /// and tip mass first, then the pressures in `steps` equal increments with step
  /// halving. `on_step(fraction, state)` sees every converged step. The returned
  /// state is the last converged one; converged=false says the path stopped, and why.
  RodState follow(const RodLoad& load, int steps, const std::function<void(double, const RodState&)>& on_step = {}) const;

  /// Tip tangent angle relative to the clamp direction, rad (counter-clockwise > 0).
  double tip_rotation(const RodState& s, const RodLoad& load) const { return s.theta.back() - load.clamp_angle_rad; }
  PieceExtremes extremes(const RodState& s, const RodLoad& load, int piece) const;

  double mass_kg() const;
  using PartMasses = RodPartMasses;
  PartMasses part_masses_kg() const { return layout_.masses; }
  double length_mm() const { return layout_.s.back(); }
  const std::vector<double>& arc_length() const { return layout_.s; }
  int node_count() const { return static_cast<int>(layout_.s.size()); }

 private:
  ArmRodSpec spec_;
  FibreLaw tube_law_, sheath_law_;
  bool same_law_ = false;  // tube and sheath of one material: one table lookup per fibre
  bool rings_confine() const;  // ring_confinement asked and the rings are rigid (100x the tube's shear modulus)
  SectionLaws laws() const { return {&tube_law_, same_law_ ? &tube_law_ : &sheath_law_}; }
  RodLayout layout_;
  std::vector<RodSection> sections_;  // per node (empty at a connector)

  double shoot(double clamp_moment_Nmm, const RodLoad& load, RodState& state, std::string& failure) const;
  std::vector<double> chamber_forces(int node, const RodLoad& load) const;
};

}  // namespace softarm::fem

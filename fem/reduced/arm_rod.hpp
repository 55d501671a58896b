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
// the clamp moment, solved by the secant method. Loads are followed by continuation with
// step halving; a step that cannot be completed is a limit point (the arm
// cannot hold the load) or a section failure, reported with its reason.
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "fem/materials/material.hpp"
#include "fem/reduced/fibre_law.hpp"
#include "fem/reduced/rod_section.hpp"
#include "fem/reduced/section_equilibrium.hpp"

namespace softarm::fem {

/// Multiplier of the chambers' pressure force p·A_c, as a function of pressure
/// (piecewise linear, constant beyond the ends): 1 without calibration.
struct ForceFactor {
  std::vector<double> pressure_kPa, factor;
  double at(double p_kPa) const;
};

struct RodPiece {
  enum class Kind { rra, tca, connector } kind = Kind::tca;
  TcaDesign design;        // tca: the segment; rra: design.actuator
  double length_mm = 0;    // connector only
  double mass_kg = 0;      // connector only
  ForceFactor force_factor;
};

struct ArmRodSpec {
  std::vector<RodPiece> pieces;  // from the clamp to the tip
  Material tube, rings, sheath;
  int nodes_per_segment = 33;
  double bend_direction_rad = 0;  // in each 3CA's section: 0 = towards chamber 1
};

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
  int newton_iterations = 0;                      // shooting (secant) iterations
};

/// Fibre extremes of one piece at a state (for stress, stretch and durability measures).
struct PieceExtremes {
  double tube_max_stretch = 1, tube_min_stretch = 1, sheath_max_stretch = 1, sheath_min_stretch = 1;
  double chamber_max_stretch = 1;  // largest axial stretch at a pressurised chamber's axis
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
  struct PartMasses { double tube = 0, rings = 0, sheath = 0, connectors = 0; };
  PartMasses part_masses_kg() const { return masses_; }
  double length_mm() const { return s_.back(); }
  const std::vector<double>& arc_length() const { return s_; }
  int node_count() const { return static_cast<int>(s_.size()); }

 private:
  struct Node {
    int piece = -1;
    bool rigid = false;
    RodSection section;
  };
  ArmRodSpec spec_;
  FibreLaw tube_law_, sheath_law_;
  bool same_law_ = false;  // tube and sheath of one material: one table lookup per fibre
  SectionLaws laws() const { return {&tube_law_, same_law_ ? &tube_law_ : &sheath_law_}; }
  std::vector<Node> nodes_;
  std::vector<double> s_;             // reference arc length per node
  std::vector<double> interval_mass_; // kg between node j and j + 1
  PartMasses masses_;

  double shoot(double clamp_moment_Nmm, const RodLoad& load, RodState& state, std::string& failure) const;
  std::vector<double> chamber_forces(int node, const RodLoad& load) const;
};

}  // namespace softarm::fem

#pragma once
// The spatial reduced model: an extensible Kirchhoff rod (no shear; plane
// sections stay normal to the axis) that bends about any axis and twists, made
// of the same pieces, nodes and masses as the planar rod (rod_layout.hpp), with
// biaxial finite-strain fibre sections (cell_section.hpp, biaxial_section.hpp).
// It poses the SPL under any chamber pressures and gravity in any direction,
// where the planar rod needs every load in one plane.
//
// Kinematics (per reference arc length S): r' = λ0 d3, d_i' = κ × d_i with the
// curvature κ = κ1 d1 + κ2 d2 + κ3 d3; a fibre at ξ in the section stretches to
// λ0 − κ2 ξ1 + κ1 ξ2. Balance (Antman, Nonlinear Problems of Elasticity, ch. 8):
// n' + f = 0, m' + r' × n = 0, where n(S), m(S) are the force and moment that
// the part beyond S exerts on the part before it; with the clamp as the only
// support, n(S) is the weight beyond S, known before the shape. Constitutive:
// the fibres and the chambers' axial forces carry n·d3, m·d1 and m·d2
// (biaxial_section.hpp); torsion m·d3 = GJ κ3 with GJ = Σ E0 A |ξ|² / 3 over the
// cells (an incompressible law's small-strain shear modulus E0/3, and the polar
// moment for the torsion constant: exact for a circle, our approximation for
// the 3CA's lobed section; no chamber drives torsion, only out-of-plane loads).
//
// Solution by shooting, as in arm_rod.hpp but with a vector unknown: from the
// clamp moment m(0), each interval's end state by fixed-point iteration of the
// midpoint rule (frame R_(j+1) = R_j exp(ΔS [κ̄]×), κ̄ the interval's mean
// curvature; position and moment by the trapezoid rule); Newton on m(0) with a
// finite-difference Jacobian until the free tip's moment vanishes.
#include <Eigen/Core>
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "fem/reduced/biaxial_section.hpp"
#include "fem/reduced/cell_section.hpp"
#include "fem/reduced/fibre_law.hpp"
#include "fem/reduced/rod_layout.hpp"

namespace softarm::fem {

/// The rest frame of a hanging rod in the scene frame: d1 = +x, d2 = −y, d3 = −z (cell_section.hpp).
Eigen::Matrix3d hanging_rod_frame();

struct SpatialRodLoad {
  /// Per piece (connectors ignored): chamber pressures 1..3, kPa.
  std::vector<std::array<double, 3>> chamber_pressure_kPa;
  Eigen::Vector3d gravity_m_s2 = Eigen::Vector3d::Zero();  // scene frame
  double tip_mass_kg = 0;
  Eigen::Vector3d clamp_position_mm = Eigen::Vector3d::Zero();
  Eigen::Matrix3d clamp_frame = hanging_rod_frame();       // directors at the clamp, as columns
};

struct SpatialRodState {
  std::vector<Eigen::Vector3d> position;   // per node, mm, scene frame
  std::vector<Eigen::Matrix3d> frame;      // per node: directors d1, d2, d3 as columns
  std::vector<double> stretch;             // λ0 of the axis
  std::vector<Eigen::Vector3d> curvature;  // (κ1, κ2, κ3) in the directors, 1/mm of reference length
  std::vector<Eigen::Vector3d> moment;     // m(S), N·mm, scene frame
  bool converged = false;
  std::string diagnosis;
  int newton_iterations = 0;
};

class SpatialRod {
 public:
  /// `cells`: cells across each section's bounding square (cell_section.hpp).
  explicit SpatialRod(ArmRodSpec spec, int cells = 24);

  /// Equilibrium under `load`, by Newton from `start` (or the straight rod).
  SpatialRodState solve(const SpatialRodLoad& load, const SpatialRodState* start = nullptr) const;
  /// Follows the load from rest (rod_continuation.hpp).
  SpatialRodState follow(const SpatialRodLoad& load, int steps,
                         const std::function<void(double, const SpatialRodState&)>& on_step = {}) const;

  /// Angle between the axis at node j and at the clamp at rest, deg (the spec's bending angle at the tip).
  double tilt_deg(const SpatialRodState& s, const SpatialRodLoad& load, int node) const;
  PieceExtremes extremes(const SpatialRodState& s, const SpatialRodLoad& load, int piece) const;

  double mass_kg() const;
  const RodLayout& layout() const { return layout_; }
  int node_count() const { return static_cast<int>(layout_.s.size()); }

 private:
  ArmRodSpec spec_;
  FibreLaw tube_law_, sheath_law_;
  bool same_law_ = false;
  SectionLaws laws() const { return {&tube_law_, same_law_ ? &tube_law_ : &sheath_law_}; }
  RodLayout layout_;
  std::vector<CellSection> sections_;    // per node (empty at a connector)
  std::vector<double> torsion_Nmm2_;     // GJ per node

  Eigen::Vector3d shoot(const Eigen::Vector3d& clamp_moment, const SpatialRodLoad& load, SpatialRodState& state,
                        std::string& failure) const;
};

}  // namespace softarm::fem

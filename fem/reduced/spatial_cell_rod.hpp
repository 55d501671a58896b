#pragma once
// The spatial cell rod: the SPL (or any chain of 3CA segments and rigid connectors) as a
// rod whose sections are ring-pitch cells of the 3D model (fem/scenes/tca_cell.hpp), in
// any pose: each segment's cells give, along its own pressure ramp, the free stretch λ₀,
// the free curvature vector κ₀ = (κx, κy) of its axis, and the tangent's compliances to an
// end moment (2×2, about x and y) and to an axial force. The rod reads them linearly in the
// load level and by Lagrange through the cells in height (cell_interpolation.hpp), and
// integrates from the clamp down the reference height Z (the material frame R is the scene
// frame at rest, d3 = +z towards the clamp):
//     κ = κ₀(Z, t) + C(Z, t)·(Rᵀ M)_xy + (Rᵀ M)_z / GJ(Z) · e3,   λ = λ₀(Z, t) + c_N(Z, t)·N,
//     R(Z − ΔZ) = R(Z)·exp(−ΔZ [κ]×),   r(Z − ΔZ) = r(Z) − ΔZ·λ·R(Z − ΔZ/2)·e3,
// where M is the moment on the part below Z from the part above (M = −Σ (r_j − r) × f_j over
// the weights f_j below) and N = −(Σ f_j)·R e3 its tension. The weights' moments follow the
// shape, so shape and moments are iterated to a fixed point, with Anderson mixing of the last
// iterates (a horizontal arm or a heavy tip mass makes the plain iteration oscillate or
// creep). Connectors are rigid and heavy; a segment's solid end caps neither stretch nor bend
// on their own (κ₀ = 0, λ₀ = 1), and bend under moments with the cells' compliance.
//
// Left out, by construction: the caps' and clamp's disturbance of the sections next to
// them unless end tables give it (SpatialEndTable; without them the planar cell rod is +4 %
// off on the thesis 3CA; a bonded end's torsion likewise), the taper within one pitch, shear, the
// pressures' effect on GJ (the cells' torsion is taken at rest) and any coupling of twist with
// bending or stretch.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace softarm::fem {

/// One cell's response along its segment's load ramp t ∈ [0, 1] (pressures t times their peaks).
struct SpatialCellTable {
  double z_mm = 0;  // the cell's ring centre in its segment (0: the segment's distal end)
  std::vector<double> level, stretch, axial_compliance_per_N;
  std::vector<Eigen::Vector2d> curvature_per_mm;
  std::vector<Eigen::Matrix2d> bending_compliance_per_Nmm2;
  double torsion_compliance_per_Nmm2 = 0;  // 1/GJ at rest (0: rigid in torsion)
  double mass_per_length_kg_per_mm = 0;
};

/// An end of a segment measured on its own (fem/scenes/tca_end_cell.hpp): over `length_mm` from
/// its end face, its own rotation and elongation along the ramp replace the cells' κ₀ and λ₀
/// (spread evenly over that length: the turn across the end is exact, the path within it
/// approximate); the bending and axial compliances there stay the cells'. A bonded end's twist
/// compliance at rest (fem/scenes/twist_compliance.hpp: its face held from warping, its cap
/// solid), where given, replaces the cells' 1/GJ there, spread evenly likewise.
struct SpatialEndTable {
  bool at_top = false;  // the end at the segment's z = length (towards the clamp), else at z = 0
  double length_mm = 0;
  std::vector<double> level, elongation_mm;
  std::vector<Eigen::Vector2d> rotation_rad;  // the upper face's against the lower one's, about x and y
  double twist_compliance_per_Nmm = 0;        // across the end, rad per N·mm (0: the cells' GJ there)
};

struct SpatialCellPiece {
  double length_mm = 0;
  std::vector<SpatialCellTable> cells;  // empty: a rigid connector
  std::vector<SpatialEndTable> ends;    // segment: none, or either end or both
  double cap_mm = 0;                    // segment: solid cap at each end (where no end table covers it)
  double mass_kg = 0;                   // connector: its mass
};

struct SpatialCellRodSpec {
  std::vector<SpatialCellPiece> pieces;  // from the clamp to the tip
  Eigen::Vector3d gravity_m_s2 = Eigen::Vector3d::Zero();  // scene frame
  double tip_mass_kg = 0;
  double interval_mm = 0.5;              // the integration's longest interval
};

struct SpatialCellRodState {
  double level = 0;
  std::vector<Eigen::Vector3d> position;  // per node from the clamp (at (0, 0, L)) to the tip, mm
  std::vector<Eigen::Matrix3d> frame;     // per node: the section's rotation from rest
  std::vector<int> piece_first_node, piece_last_node;
  std::vector<Eigen::Vector3d> moment_Nmm;  // per interval: M on the part below its midpoint, scene frame
  /// Per interval, in its material frame: the axis' stretch λ and curvature κ under the moments (κ_z the
  /// twist rate), so that a fibre at section offset d (mm, material frame) stretches by λ + (κ × d)·e3.
  std::vector<double> stretch;
  std::vector<Eigen::Vector3d> curvature_per_mm;
  int iterations = 0;                     // shape–moment fixed-point iterations
  bool ok = false;
  bool beyond_tables = false;             // not ok because a level lies past a cell's table (else: not settled)
  std::string diagnosis;                  // why not ok
};

/// The rod's equilibrium at load level t (pressures t times their peaks, full weight). Not ok
/// where t lies beyond a cell's table (past its last output: a limit point or a stall) or the
/// shape–moment iteration does not settle. `start`: a nearby state whose moments start the
/// iteration. Without one, an iteration that does not settle is tried again with the weights raised
/// step by step from none (the branch the weightless shape bends into under its weight); with one,
/// a failure stands (a path's next state near its last, not one on another branch).
SpatialCellRodState solve_spatial_cell_rod(const SpatialCellRodSpec& spec, double level,
                                           const SpatialCellRodState* start = nullptr);

/// The twist per unit torque (rad/(N·mm)) across piece `piece` at rest, as the rod integrates it:
/// Σ ΔZ / GJ over its intervals, the end tables' twist compliances included (a connector's: 0);
/// NaN for a piece the spec does not have.
double spatial_cell_rod_twist_compliance(const SpatialCellRodSpec& spec, std::size_t piece);

/// Total length, and mass (the cells' smeared mass and the connectors'; the tip mass excluded).
double spatial_cell_rod_length_mm(const SpatialCellRodSpec& spec);
double spatial_cell_rod_mass_kg(const SpatialCellRodSpec& spec);

}  // namespace softarm::fem

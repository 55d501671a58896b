#pragma once
// A planar rod whose sections are ring-pitch cells of the 3D model
// (fem/scenes/tca_cell.hpp) instead of fibre sections (rod_section.hpp): the 3CA's
// bending curve from a few small 3D solves. Each cell gives, along the pressure
// ramp, the free stretch λ₀ and curvature κ₀ of the 3CA axis and the tangent's
// bending compliance dκ/dM at its height; the rod interpolates them in pressure
// (linearly between the cell's output states) and in height (Lagrange through the
// cells), and integrates from the clamp:
//     dθ/dS = κ₀(z, p) + (dκ/dM)(z, p)·M(S),   dr/dS = λ₀(z, p)·t(θ),
// with S the reference arc length from the clamp, t = (sin θ, −cos θ) in the bend
// plane (along the bend, along the user's z), and M(S) the moment about r(S) of the
// weight of the part beyond S, positive when it turns the rod towards the bend.
// Gravity's moment depends on the shape, so shape and moment are iterated to a fixed
// point (a contraction: the weight bends the thesis 3CA by ~3°). The end caps
// (solid silicone) neither stretch nor bend on their own: κ₀ = 0, λ₀ = 1 there.
//
// What it leaves out, by construction: the caps' and the clamp's own disturbance of
// the section's response (unless end tables give it: EndTable), the taper within one pitch, the axial force of the weight
// on λ₀ and κ₀, and anything out of the bend plane.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace softarm::fem {

/// One cell's response along its pressure ramp (its output states).
struct CellTable {
  double z_mm = 0;  // the cell's ring centre, on the 3CA's axis (0: the free end)
  std::vector<double> pressure_kPa, stretch, curvature_per_mm, bending_compliance_per_Nmm2;
  double mass_per_length_kg_per_mm = 0;
};

/// An end of the 3CA measured on its own (fem/scenes/tca_end_cell.hpp): over `length_mm` from
/// its end face, its own rotation and elongation under pressure replace the cells' κ₀ and λ₀
/// (spread evenly over that length: the angle at the tip is exact, the path within the end
/// approximate); the bending compliance there stays the cells'.
struct EndTable {
  bool at_clamp = false;
  double length_mm = 0;
  std::vector<double> pressure_kPa, rotation_rad, elongation_mm;
};

struct CellRodSpec {
  double length_mm = 0;
  double cap_mm = 0;                 // solid cap at each end (where no EndTable covers it)
  std::vector<CellTable> cells;      // at least one
  std::vector<EndTable> ends;        // none, or either end or both
  double gravity_along_bend_m_s2 = 0;  // gravity's component along the bend direction
  double gravity_along_axis_m_s2 = 0;  // ... along the user's +z (the clamp is at z = length)
  int intervals = 320;
};

struct CellRodState {
  double pressure_kPa = 0;
  double bending_angle_deg = 0;      // tip tangent against the rest tangent, > 0 towards the bend
  double tip_along_bend_mm = 0, tip_z_mm = 0;  // the free end's centre (rest: 0, 0)
  double tip_across_bend_mm = 0;     // along e_z × bend: 0 in one plane, the spatial rod's sideways sag
  /// The centreline's nodes from the clamp to the tip, mm: (along the bend, across it, z) for the planar
  /// rod (across: 0), the scene frame for the spatial rod (tca_cell_rod.cpp turns both into it).
  std::vector<Eigen::Vector3d> centreline_mm;
  int iterations = 0;                // shape–moment fixed-point iterations
  bool ok = false;
  std::string diagnosis;             // why not ok
};

/// The rod's equilibrium at pressure p. Not ok where p lies beyond a cell's table (past
/// its last output, e.g. a limit point) or the shape–moment iteration does not settle.
CellRodState solve_cell_rod(const CellRodSpec& spec, double pressure_kPa);

}  // namespace softarm::fem

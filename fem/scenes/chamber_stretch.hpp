#pragma once
// The chambers' axial stretch in an SPL pose on its cell rod: what the burst and durability criteria
// read (through the lone RRA's FEM map from an actuator's mean axial stretch to its local peaks,
// rra_calibration.hpp), as the design's check reads it along its bending path
// (objectives/cell_rod_evaluation.cpp), here in any pose.
//
// A fibre at section offset d (material frame) of an interval with axis stretch λ and curvature κ
// (spatial_cell_rod.hpp: dr/dZ = λ·R·e3, dR/dZ = R·[κ]×) runs along R·(λ e3 + κ × d), so to first
// order in |κ|·|d| it stretches by
//     λ_d = λ + (κ × d)·e3 = λ + κ_x d_y − κ_y d_x.
// Chamber k's axis (k = 1..3) stands at d_k = a_c(z)·(cos θ_k, sin θ_k), θ_k = (k − 1)·120° (the
// meshes' and the scenes' convention), a_c(z) the 3CA's axis distance at the interval's height
// (tca_design.hpp). The solid end caps hold no chamber and are left out.
#include <array>

#include "fem/mesh/spl_design.hpp"
#include "fem/reduced/spatial_cell_rod.hpp"

namespace softarm::fem {

/// The axial stretch of the fibre at `offset_mm` (material frame, x and y) of an interval with axis
/// stretch `stretch` and curvature `curvature_per_mm`.
double fibre_stretch(double stretch, const Eigen::Vector3d& curvature_per_mm, const Eigen::Vector2d& offset_mm);

/// Per segment (0: proximal), the largest stretch along any of its three chambers' axes over its
/// intervals outside the caps. `rod` holds the arm's pieces as spl_cells builds them (a segment is a
/// piece with cells, in order from the clamp) and `state` is a converged solve of it (not ok: NaN).
std::array<double, 3> chamber_axis_stretch(const SplDesign& design, const SpatialCellRodSpec& rod,
                                           const SpatialCellRodState& state);

}  // namespace softarm::fem

#pragma once
// A 3CA segment's pressure space, (p1, p2, p3) each in [0, P], read through the section's symmetry.
// Chamber k sits at (k − 1)·120° from +x (tca_scene.hpp), so the section is unchanged by a turn of
// 120° about the axis and by a mirror through any chamber's axis (the dihedral group of order 6).
// Every pressure triple is one of these maps applied to a canonical triple
//     p = g · (s, a·s, b·s),   s = max p_k (the peak),   1 ≥ a ≥ b ≥ 0,
// with the largest pressure in chamber 1 and the second in chamber 2. A response measured under the
// canonical triple gives the response under p: scalars (stretch, compliance to axial force) as they
// are, the section's rotation-like vectors (curvature κ = (κx, κy), an end's turn) by the map A of
// axial vectors, A = det(T)·T with T the in-plane map, and their compliances C by A·C·Aᵀ.
//
// The canonical directions (a, b) fill the triangle 1 ≥ a ≥ b ≥ 0. A grid of step 1/n on it, split
// into triangles, interpolates a response linearly between the rays through its points: exact for a
// response linear in the pressures at a given peak (the small-strain 3CA's: κ ∝ Σ p_k e_k), so what
// it leaves out is the response's curvature across directions, measured against rays it did not see
// (fem/scenes/spl_pressure_cells.hpp).
#include <Eigen/Core>
#include <array>
#include <vector>

namespace softarm::fem {

struct CanonicalPressures {
  double peak_kPa = 0;  // s: the largest of the three
  double a = 0, b = 0;  // the second and third largest over the peak (0 where the peak is 0)
  /// The in-plane map T taking the canonical section to the actual one (chamber 1 onto the chamber
  /// with the peak, chamber 2 onto the second), and A = det(T)·T, the map of axial vectors.
  Eigen::Matrix2d section_map = Eigen::Matrix2d::Identity();
  Eigen::Matrix2d axial_map = Eigen::Matrix2d::Identity();
};

/// The canonical form of a segment's three chamber pressures (kPa, each ≥ 0). Ties choose the lowest
/// chamber number, so equal pressures map by the identity where they can.
CanonicalPressures canonical_pressures(const std::array<double, 3>& p_kPa);

/// The grid's directions (a, b) = (i/n, j/n), 0 ≤ j ≤ i ≤ n, in the order i then j: (n+1)(n+2)/2 rays.
std::vector<Eigen::Vector2d> direction_grid(int n);

/// The linear interpolation at (a, b) over the grid of step 1/n: up to three (index into
/// direction_grid(n), weight) pairs, weights ≥ 0 summing to 1. (a, b) is clamped into the triangle.
std::vector<std::pair<int, double>> direction_weights(int n, double a, double b);

}  // namespace softarm::fem

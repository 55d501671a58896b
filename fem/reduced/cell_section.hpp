#pragma once
// Cross-sections of the spatial rod (spatial_rod.hpp), which bends about any
// axis: the section is cut into square cells on a grid, each keeping the area
// of every material inside it and its centre ξ = (ξ1, ξ2) in the section's
// director frame. The fibre through a cell has stretch λ = λ0 + g·ξ
// (biaxial_section.hpp), so the planar rod's strips (rod_section.hpp), which
// only know one coordinate, are the special case of bending about one axis.
//
// Cell areas: per row of cells, Gauss–Legendre sub-rows (3 points each) across
// the row; on each sub-row the chords of the discs (tubes, chambers, centre
// hole) and of the sheath's envelope are exact and are clipped to each cell's
// columns. Same material rules as the planar section: rings carry no axial
// load, end caps are solid tube material.
//
// Section frame: at rest the directors are d1 = +x and d2 = −y of the scene
// frame (chamber 1's axis on +x, chamber k at (k − 1)·120° counter-clockwise
// seen from +z), d3 = d1 × d2 = −z: from the clamped top towards the tip. So
// chamber k sits at ξ = a_c·(cos φ_k, −sin φ_k).
#include <Eigen/Core>
#include <vector>

#include "fem/mesh/tca_design.hpp"

namespace softarm::fem {

struct FibreCell {
  Eigen::Vector2d xi = Eigen::Vector2d::Zero();  // cell centre, mm
  double tube_area = 0, sheath_area = 0;          // mm² of each material in the cell
};

struct CellSection {
  std::vector<FibreCell> cells;                   // non-empty cells only
  std::vector<Eigen::Vector2d> chamber_xi;        // chamber k's axis, mm
  std::vector<double> chamber_force_area;         // mm², the area its pressure acts on
  double tube_area = 0, sheath_area = 0;          // mm²
};

/// The 3CA section at height z (0 = bottom, l = top); `cells` cells across the
/// envelope's bounding square, `subrows` Gauss sub-rows per row of cells.
CellSection tca_cell_section(const TcaDesign& design, double z, int cells = 24, int subrows = 2);

}  // namespace softarm::fem

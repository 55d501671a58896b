#pragma once
// Structured quadrilateral meshes of the axisymmetric (r, z) half-plane, and the
// builder every 2D mesher uses, so that node storage and element orientation
// (counter-clockwise in (r, z), mesh.hpp) are decided in one place.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "fem/mesh/mesh.hpp"

namespace softarm::fem {

/// Accumulates the nodes and 4-node elements of a 2D (r, z) mesh.
class QuadMeshBuilder {
 public:
  int add_node(const Eigen::Vector2d& rz);
  int add_node(double r, double z) { return add_node(Eigen::Vector2d(r, z)); }
  const Eigen::Vector2d& node(int id) const { return nodes_[static_cast<std::size_t>(id)]; }
  int num_nodes() const { return static_cast<int>(nodes_.size()); }

  /// Adds the quad with corners a, b, c, d in cyclic order (either sense); it is
  /// stored counter-clockwise. Two neighbouring corners may be the same node (a
  /// collapsed quad, i.e. a triangle), but the area must not vanish: a zero-area
  /// element is a mesher bug and throws std::logic_error.
  void add_quad(int a, int b, int c, int d, int part);

  /// Adds the quads between consecutive lines of a logically rectangular grid:
  /// lines[j][i] is node i of line j; all lines have the same length.
  void add_grid(const std::vector<std::vector<int>>& lines, int part);

  /// Moves the nodes and elements into a Mesh (dim 2, 4 nodes per element). Part
  /// names, node sets and chambers are the caller's to fill.
  Mesh finish(std::vector<std::string> part_names);

 private:
  std::vector<Eigen::Vector2d> nodes_;
  std::vector<int> connectivity_, part_;
};

/// Structured mesh of the rectangle [r0, r1] × [z0, z1] with nr × nz quads, part
/// "solid". Node sets: "inner" (r = r0), "outer" (r = r1), "bottom" (z = z0),
/// "top" (z = z1), "boundary" (all four sides) and "axis" (= "inner") when r0 = 0.
/// `distortion` in [0, 1] moves each interior node by up to 0.2·distortion of the
/// element size in r and z, pseudo-randomly but deterministically (patch tests);
/// every element stays convex. When r0 > 0 the inner edge is chamber 1
/// ("chamber"), its edges oriented upward (dz > 0) so the enclosed volume π r0² (z1 − z0) is positive.
/// Throws std::invalid_argument for r0 < 0, r1 <= r0, z1 <= z0, nr or nz < 1, or distortion outside [0, 1].
Mesh rectangle_mesh(double r0, double r1, double z0, double z1, int nr, int nz, double distortion = 0);

/// Structured mesh of the box [lo, hi] with nx × ny × nz trilinear hexahedra (dim 3,
/// 8 nodes, VTK order, positive Jacobian), part "solid". Node sets "x0", "x1", "y0",
/// "y1", "z0", "z1" (the faces at lo and hi of each axis) and "boundary" (all six).
/// `distortion` in [0, 1] moves each interior node by up to 0.1·distortion of the
/// element size along each axis, pseudo-randomly but deterministically; every
/// element keeps a positive Jacobian. No chamber.
/// Throws std::invalid_argument for hi <= lo on an axis, a count < 1 or distortion outside [0, 1].
Mesh box_mesh(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int nx, int ny, int nz, double distortion = 0);

/// Hexahedral mesh of the full (360°) tube r_inner <= r <= r_outer, 0 <= z <= length,
/// about the z axis: n_radial × n_circumferential × n_axial trilinear hexahedra (dim 3,
/// 8 nodes), part "solid". Node sets "inner" (r = r_inner), "outer", "z0", "z1".
/// Chamber 1 ("bore") is the inner surface as 4-node facets whose normal x_s × x_t
/// points out of the bore, into the wall (+e_r). The bore is open at its ends: the
/// facets alone do not enclose a volume (mesh.hpp asks for closed chambers), so a
/// pressure needs end caps, which are the caller's to add.
/// Throws std::invalid_argument unless 0 < r_inner < r_outer, length > 0, n_radial >= 1,
/// n_circumferential >= 3 and n_axial >= 1.
Mesh hollow_cylinder_mesh(double r_inner, double r_outer, double length, int n_radial, int n_circumferential,
                          int n_axial);

}  // namespace softarm::fem

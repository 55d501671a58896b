#pragma once
// Promotes linear meshes to quadratic Lagrange elements: one node at the
// midpoint of every edge and at the centre of every face (shared by the
// elements on either side) and one at each element's centre, in VTK's node
// order (axisymmetric_quad.hpp, hexahedron.hpp). Node sets gain the new nodes
// of boundary facets (edges in 2D, faces in 3D) whose corners are all in the
// set; chamber facets gain theirs: a 2D edge (a, b) becomes (a, mid, b), a 3D
// quadrilateral (a, b, c, d) becomes the 9-node facet (a, b, c, d, mid ab,
// mid bc, mid cd, mid da, centre). Geometry is that of the linear mesh
// (straight edges, bilinear faces), so curved boundaries keep the linear
// mesh's O(h²) approximation — unless, in 2D, an edge projection puts the
// mid-edge nodes of curved edges on the true curve; element centres then
// follow the transfinite (Gordon–Hall) blend x_c = Σ mid-edges / 2 − Σ corners / 4,
// which is the centroid for straight edges.
#include <functional>
#include <optional>

#include "fem/mesh/mesh.hpp"

namespace softarm::fem {

/// Where the mid-edge node of the edge (a, b) lies on the true geometry, or
/// nothing for a straight edge (the chord midpoint is kept).
using EdgeProjection = std::function<std::optional<Eigen::Vector2d>(const Eigen::Vector2d& a, const Eigen::Vector2d& b)>;

/// 4-node quadrilaterals (dim 2) → 9-node quadrilaterals.
Mesh to_quadratic(const Mesh& linear, const EdgeProjection& curved_edges = {});

/// 8-node hexahedra (dim 3) → 27-node hexahedra; chamber facets must be 4-node element faces.
Mesh to_quadratic_3d(const Mesh& linear);

}  // namespace softarm::fem

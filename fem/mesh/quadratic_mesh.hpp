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
// mesh's O(h²) approximation.
#include "fem/mesh/mesh.hpp"

namespace softarm::fem {

/// 4-node quadrilaterals (dim 2) → 9-node quadrilaterals.
Mesh to_quadratic(const Mesh& linear);

/// 8-node hexahedra (dim 3) → 27-node hexahedra; chamber facets must be 4-node element faces.
Mesh to_quadratic_3d(const Mesh& linear);

}  // namespace softarm::fem

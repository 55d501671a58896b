#pragma once
// Promotes a bilinear quadrilateral mesh to biquadratic (9-node) elements:
// one node at the midpoint of every edge (shared by the elements on either
// side) and one at each element's centre. Node sets gain the mid-edge nodes
// of boundary edges whose two ends are both in the set; chamber edges become
// 3-node edges (a, mid, b). Geometry is that of the linear mesh (straight
// edges), so curved boundaries keep the linear mesh's O(h²) approximation.
#include "fem/mesh/mesh.hpp"

namespace softarm::fem {

Mesh to_quadratic(const Mesh& linear);

}  // namespace softarm::fem

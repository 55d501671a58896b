#pragma once
// Serendipity meshes from triquadratic ones: a Hex27 mesh without its face-
// and body-centre nodes (VTK 20–26) is a conforming Hex20 mesh of the same
// geometry (the edges, and so the curved boundaries, are unchanged). On the
// thin, layered 3CA meshes this removes about 45 % of the unknowns, and the
// mesh is then node for node the C3D20 mesh that CalculiX solves.
#include "fem/mesh/mesh.hpp"

namespace softarm::fem {

/// The Hex20 mesh of a Hex27 mesh: elements keep nodes 0–19, 9-node chamber
/// facets drop their centre, node sets drop the removed nodes, and the kept
/// nodes are renumbered in their old order. Throws std::logic_error for a mesh
/// that is not 3D Hex27.
Mesh serendipity_from_triquadratic(const Mesh& hex27);

}  // namespace softarm::fem

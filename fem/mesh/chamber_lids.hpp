#pragma once
// Lids for cavities that a cut leaves open. A ring-pitch cell of a 3CA (tca_mesher.hpp)
// cuts its chambers at both end faces; the chamber's pressure work p·V needs a closed
// surface (chamber_pressure_form.hpp), and the fluid's push on the cut, p times the
// chamber's current cross-section there, is exactly what the lid's share of V
// contributes to the end face's equilibrium. The lid is the fan from the centroid of
// the wall's edge nodes on the cut, so it follows the wall as it balloons.
#include <vector>

#include "fem/mesh/mesh.hpp"

namespace softarm::fem {

/// Adds to every chamber of a 3D mesh one lid per loop of its facets' edges that lie on
/// `cut_nodes` (all of an edge's nodes in the set), ordered opposite to the facets'
/// traversal, so the lid's normal points out of the cavity like the facets'. A chain
/// that ends on a symmetry plane (a half model) is left open: the fan's last triangle
/// closes it along that plane. Midside nodes of quadratic facets are loop nodes too.
void add_chamber_lids(Mesh& mesh, const std::vector<int>& cut_nodes);

}  // namespace softarm::fem

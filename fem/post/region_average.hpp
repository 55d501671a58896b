#pragma once
// Peaks that converge under mesh refinement: the largest average of a field
// over a neighbourhood of fixed physical size.
//
// Where a stiff ring is bonded into a soft tube, the bond line meets the free
// surface at the groove lip: a bi-material corner, where linear elasticity's
// stress and strain are singular (Bogy 1971) and the finite-strain fields grow
// with every refinement. The value at that point is no criterion (one RRA mesh
// level finer, the thesis design's pointwise stretch peak grows by tens of %).
// The integral of the field over a fixed volume converges, because the
// singularity is integrable. This is the "volume method" of the theory of
// critical distances (Taylor 2007, "The Theory of Critical Distances", §2.4):
//
//     f̄(c) = ∫_{B(c, ρ) ∩ Ω_part} f dV / ∫_{B(c, ρ) ∩ Ω_part} dV,   peak = max over c of f̄(c),
//
// with B(c, ρ) the ball of radius ρ about c in the reference configuration (a
// fixed piece of material) and dV = 2π r dA for an axisymmetric mesh. Discretely:
// each element carries its field value (e.g. the largest over its Gauss points)
// at its reference centroid, weighted by its reference volume; the candidate
// centres c are the elements' centroids. ρ is a definition (docs/definitions.md,
// "Peak averaging radius"), not a numerical parameter: the criterion converges to
// a value that depends on it.
#include <vector>

#include "fem/mesh/mesh.hpp"

namespace softarm::fem {

struct RegionPeak {
  double value = 0;        // max over the centres of the field's average over the ball
  int centre_element = -1; // the element whose centroid is that centre (-1: no element selected)
  int elements_averaged = 0;
};

/// The largest ball average of `field` (one value per element) over the elements of part
/// `part` of an axisymmetric (dim = 2) mesh, with the ball's radius `radius_mm` > 0.
/// Throws std::invalid_argument for a 3D mesh, a field of the wrong size or a radius ≤ 0.
RegionPeak max_region_average(const Mesh& mesh, const std::vector<double>& field, int part, double radius_mm);

}  // namespace softarm::fem

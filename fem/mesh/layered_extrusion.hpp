#pragma once
// Hexahedral meshes by extruding an ActuatorSection along z through a stack of
// layers: every layer chooses, per section quadrilateral, the part of its
// elements (or none: a chamber, a gap) and whether the cell is part of a
// chamber's cavity. The section's node positions are re-evaluated at every
// node height, so tapers (radii, spacing, axis positions varying with z) are
// meshed exactly at the nodes. Quadratic meshes extrude the 9-node section
// quads into 27-node hexahedra (VTK order, hexahedron.hpp); linear meshes use
// their corners (8-node hexahedra).
//
// Chamber facets are found, not declared: a facet joins a cavity cell and an
// existing element (sideways or above/below), oriented out of the cavity, so
// the chamber surface is closed wherever the walls are. A cavity cut by a
// symmetry plane y = 0 stays open there, which is harmless for the volume
// V = (1/3)∮ x·n dA: on that plane x·n = ±y = 0 (chamber_pressure_form.hpp).
#include <functional>
#include <string>
#include <vector>

#include "fem/mesh/actuator_section.hpp"
#include "fem/mesh/mesh.hpp"

namespace softarm::fem {

/// One slab z0 ≤ z ≤ z1 of the stack, split into `divisions` element layers.
struct ExtrusionLayer {
  double z0 = 0, z1 = 0;
  int divisions = 1;
};

struct ExtrusionRules {
  /// The section's sizes at height z.
  std::function<SectionGeometry(double z)> geometry;
  /// Part index of the elements of section quad `quad` in layer `layer`, or −1 for no element.
  std::function<int(int quad, int layer)> part;
  /// Index into the mesh's chambers whose cavity the cell (quad, layer) belongs to, or −1.
  std::function<int(int quad, int layer)> cavity;
};

/// The extruded mesh (dim 3; order 1: Hex8, order 2: Hex27) with `part_names` and
/// `chambers` (their facets filled in here). Node sets: "bottom" (z = z0 of the first
/// layer), "top" (z = z1 of the last) and "plane_y0" (nodes on y = 0). Nodes used
/// by no element are not created. Throws std::logic_error for an empty stack.
Mesh extrude_section(const ActuatorSection& section, const std::vector<ExtrusionLayer>& layers,
                     const ExtrusionRules& rules, int order, std::vector<std::string> part_names,
                     std::vector<Chamber> chambers);

}  // namespace softarm::fem

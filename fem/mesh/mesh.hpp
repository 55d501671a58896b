#pragma once
// Unstructured mesh shared by every scene. Axisymmetric meshes (dim = 2) live
// in the (r, z) half-plane with z the symmetry axis; 3D meshes (dim = 3) in
// (x, y, z). Lengths in mm.
#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

namespace softarm::fem {

/// A pressurised cavity's boundary, as oriented facets of the mesh.
/// Axisymmetric: 2-node edges (a, b) in (r, z), chained from the axis around the
/// cavity so that the enclosed volume V = Σ π (z_b − z_a)(r_a² + r_a r_b + r_b²)/3
/// is positive (the closing segment on the axis contributes nothing).
/// 3D: quadrilateral facets (4 or 9 nodes, VTK order) whose normals point out of the
/// cavity (into the wall); the facets must close the cavity for V to be a volume.
struct Chamber {
  int id = 0;            // chamber number as the user sees it (1-based for the SPL)
  std::string name;
  std::vector<std::vector<int>> facets;
  /// 3D only: flat closures of a cavity that a cut face leaves open (a ring-pitch cell's
  /// end faces, chamber_lids.hpp). Each is a loop of nodes on the cut, running
  /// counter-clockwise about the normal out of the cavity; the lid is the fan of
  /// triangles from the loop's centroid over consecutive nodes, the last back to the first.
  std::vector<std::vector<int>> lids;
};

struct Mesh {
  int dim = 2;                 // 2: axisymmetric (r, z); 3: three-dimensional
  int nodes_per_element = 4;   // 4: bilinear quadrilateral (axisymmetric); 8: trilinear hexahedron
  Eigen::MatrixXd X;           // reference node coordinates, one row per node (dim columns), mm
  std::vector<int> connectivity;  // nodes_per_element entries per element, counter-clockwise in (r, z)
  std::vector<int> part;          // part index of each element
  std::vector<std::string> part_names;
  std::map<std::string, std::vector<int>> node_sets;  // named node groups (e.g. "axis", "fixed_end")
  std::vector<Chamber> chambers;

  int num_nodes() const { return static_cast<int>(X.rows()); }
  int num_elements() const { return nodes_per_element == 0 ? 0 : static_cast<int>(connectivity.size()) / nodes_per_element; }
  const int* element(int e) const { return connectivity.data() + static_cast<std::size_t>(e) * nodes_per_element; }
  int part_index(const std::string& name) const {
    for (std::size_t i = 0; i < part_names.size(); ++i)
      if (part_names[i] == name) return static_cast<int>(i);
    return -1;
  }
};

/// Node coordinates as one node-major vector (dim entries per node): the
/// layout of the solver's position vector x.
inline Eigen::VectorXd flattened_positions(const Mesh& mesh) {
  Eigen::VectorXd x(mesh.num_nodes() * mesh.dim);
  for (int n = 0; n < mesh.num_nodes(); ++n) x.segment(n * mesh.dim, mesh.dim) = mesh.X.row(n).transpose();
  return x;
}

}  // namespace softarm::fem

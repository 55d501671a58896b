#pragma once
// Closed 3D tube meshes for tests: the open bore of a hollow_cylinder_mesh closed by
// flat lids (so the chamber is a closed surface), and Hex27 nodes snapped onto the
// cylinders. Shared by the 3D solid tests and the CalculiX cross-checks.
#include <cmath>
#include <map>
#include <vector>

#include "fem/mesh/mesh.hpp"

namespace softarm::test {
using fem::Mesh;

/// Closes the open bore of a hollow_cylinder_mesh (chamber 0) with two flat lids, so
/// that the chamber is a closed surface (mesh.hpp) and −pV its pressure potential.
/// Each lid is a fan of facets collapsed at a new node on the axis, (axis, p, q, axis)
/// for a bore edge p → q, oriented out of the cavity; for 9-node facets the fan
/// adds the midpoints of its radial edges and facet centres. The lid of a plane
/// z = c contributes (c/3)·(signed area) to V, and its area depends only on the bore
/// edge nodes (the fan's shared interior edges cancel), so the added nodes, which
/// belong to no element, are prescribed in place. Returns the added nodes.
inline std::vector<int> close_bore(Mesh& mesh, double length) {
  std::vector<Eigen::RowVector3d> added;
  auto add_node = [&](const Eigen::RowVector3d& x) {
    added.push_back(x);
    return mesh.num_nodes() + static_cast<int>(added.size()) - 1;
  };
  auto position = [&](int n) -> Eigen::RowVector3d {
    return n < mesh.num_nodes() ? Eigen::RowVector3d(mesh.X.row(n)) : added[n - mesh.num_nodes()];
  };
  std::vector<std::vector<int>> lids;
  for (double z : {0.0, length}) {
    const int axis = add_node(Eigen::RowVector3d(0, 0, z));
    std::map<int, int> radial_mid;  // bore node → midpoint of its radial fan edge
    auto mid = [&](int n) {
      auto it = radial_mid.find(n);
      if (it == radial_mid.end()) it = radial_mid.emplace(n, add_node(0.5 * (position(n) + position(axis)))).first;
      return it->second;
    };
    for (const auto& f : mesh.chambers[0].facets) {
      // Bore facet (a, b, c, d; mids ab, bc, cd, da; centre), θ increasing a → b and d → c.
      const bool bottom = z == 0.0;
      const int a = bottom ? f[0] : f[3], b = bottom ? f[1] : f[2];
      if (std::abs(position(a).z() - z) > 1e-12) continue;
      // Out of the cavity: −e_z at the bottom (reverse the fan), +e_z at the top.
      const int p = bottom ? b : a, q = bottom ? a : b;
      std::vector<int> lid{axis, p, q, axis};
      if (f.size() == 9) {
        const int edge_mid = bottom ? f[4] : f[6];
        const int centre = add_node(0.5 * (position(axis) + position(edge_mid)));
        lid.insert(lid.end(), {mid(p), edge_mid, mid(q), axis, centre});
      }
      lids.push_back(lid);
    }
  }
  const int first = mesh.num_nodes();
  mesh.X.conservativeResize(first + static_cast<int>(added.size()), 3);
  for (std::size_t k = 0; k < added.size(); ++k) mesh.X.row(first + static_cast<int>(k)) = added[k];
  mesh.chambers[0].facets.insert(mesh.chambers[0].facets.end(), lids.begin(), lids.end());
  std::vector<int> nodes(added.size());
  for (std::size_t k = 0; k < added.size(); ++k) nodes[k] = first + static_cast<int>(k);
  return nodes;
}

/// Moves the nodes that to_quadratic_3d put on chords (mid-circumference) onto the
/// cylinders r = const, so that the Hex27 geometry is the isoparametric tube.
inline void snap_to_cylinders(Mesh& mesh, int n_circumferential) {
  constexpr double kTwoPi = 6.283185307179586;
  const double step = kTwoPi / n_circumferential;
  for (int n = 0; n < mesh.num_nodes(); ++n) {
    const double theta = std::atan2(mesh.X(n, 1), mesh.X(n, 0));
    const double off = std::remainder(theta, step);  // 0 on a grid angle, ±step/2 on a chord midpoint
    if (std::abs(off) > 1e-9) mesh.X.block<1, 2>(n, 0) /= std::cos(off);
  }
}


}  // namespace softarm::test

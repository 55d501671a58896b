#include "fem/mesh/layered_extrusion.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>

namespace softarm::fem {
namespace {

// Local edges of a 9-node quadrilateral: corner, corner, mid-edge node.
constexpr int kQuadEdges[4][3] = {{0, 1, 4}, {1, 2, 5}, {2, 3, 6}, {3, 0, 7}};

/// The element layers: layer index of each, and the node-layer index of its bottom.
struct Sublayer {
  int layer = 0;
  double z0 = 0, z1 = 0;
};

/// Orients a facet so that its normal (diagonal cross product) has a positive
/// component along `outward`.
std::vector<int> oriented(std::vector<int> facet, const Eigen::MatrixXd& X, const Eigen::Vector3d& outward) {
  const Eigen::Vector3d d1 = X.row(facet[2]) - X.row(facet[0]);
  const Eigen::Vector3d d2 = X.row(facet[3]) - X.row(facet[1]);
  if (d1.cross(d2).dot(outward) >= 0) return facet;
  if (facet.size() == 4) return {facet[0], facet[3], facet[2], facet[1]};
  return {facet[0], facet[3], facet[2], facet[1], facet[7], facet[6], facet[5], facet[4], facet[8]};
}

/// The extrusion's grid: the element layers (each layer's divisions), the node layers' heights, and
/// every (quad, layer)'s part and cavity, evaluated once; nodes are numbered node_layer · n_sec +
/// section node until compaction.
struct ExtrusionGrid {
  const ActuatorSection& section;
  int order = 1, n_sec = 0, n_quads = 0, node_layers = 0;
  std::vector<Sublayer> sub;
  std::vector<double> z_of_node_layer;
  std::vector<int> part_of, cavity_of;

  ExtrusionGrid(const ActuatorSection& s, const std::vector<ExtrusionLayer>& layers, const ExtrusionRules& rules,
                int element_order)
      : section(s), order(element_order), n_sec(s.num_nodes()), n_quads(s.num_quads()) {
    for (std::size_t l = 0; l < layers.size(); ++l)
      for (int d = 0; d < layers[l].divisions; ++d) {
        const double h = (layers[l].z1 - layers[l].z0) / layers[l].divisions;
        sub.push_back({static_cast<int>(l), layers[l].z0 + d * h, layers[l].z0 + (d + 1) * h});
      }
    node_layers = order * static_cast<int>(sub.size()) + 1;
    z_of_node_layer.resize(node_layers);
    for (std::size_t k = 0; k < sub.size(); ++k)
      for (int j = 0; j <= order; ++j)
        z_of_node_layer[order * k + j] = sub[k].z0 + (sub[k].z1 - sub[k].z0) * j / order;
    part_of.resize(n_quads * layers.size());
    cavity_of.resize(n_quads * layers.size());
    for (std::size_t l = 0; l < layers.size(); ++l)
      for (int q = 0; q < n_quads; ++q) {
        part_of[l * n_quads + q] = rules.part(q, static_cast<int>(l));
        cavity_of[l * n_quads + q] = rules.cavity(q, static_cast<int>(l));
      }
  }
  int node(int section_node, int node_layer) const { return node_layer * n_sec + section_node; }
  int part_at(int q, int s) const { return part_of[sub[s].layer * n_quads + q]; }
  int cavity_at(int q, int s) const { return cavity_of[sub[s].layer * n_quads + q]; }
};

/// The elements of every (quad, sublayer) with a part, over the grid's provisional node ids.
void add_elements(Mesh& mesh, const ExtrusionGrid& g) {
  for (std::size_t s = 0; s < g.sub.size(); ++s)
    for (int q = 0; q < g.n_quads; ++q) {
      const int p = g.part_at(q, static_cast<int>(s));
      if (p < 0) continue;
      const auto& Q = g.section.quads()[q];
      const int k0 = g.order * static_cast<int>(s), k1 = k0 + 1, k2 = k0 + g.order;
      if (g.order == 1) {
        for (int a = 0; a < 4; ++a) mesh.connectivity.push_back(g.node(Q[a], k0));
        for (int a = 0; a < 4; ++a) mesh.connectivity.push_back(g.node(Q[a], k2));
      } else {
        // VTK Hex27 from a Quad9 at three heights: corners, bottom and top edge
        // mids, vertical edge mids, face centres (ξ−: edge 3-0, ξ+: 1-2, η−: 0-1,
        // η+: 2-3, ζ−, ζ+), body centre.
        for (int a = 0; a < 4; ++a) mesh.connectivity.push_back(g.node(Q[a], k0));
        for (int a = 0; a < 4; ++a) mesh.connectivity.push_back(g.node(Q[a], k2));
        for (int a = 4; a < 8; ++a) mesh.connectivity.push_back(g.node(Q[a], k0));
        for (int a = 4; a < 8; ++a) mesh.connectivity.push_back(g.node(Q[a], k2));
        for (int a = 0; a < 4; ++a) mesh.connectivity.push_back(g.node(Q[a], k1));
        for (int a : {7, 5, 4, 6}) mesh.connectivity.push_back(g.node(Q[a], k1));
        mesh.connectivity.push_back(g.node(Q[8], k0));
        mesh.connectivity.push_back(g.node(Q[8], k2));
        mesh.connectivity.push_back(g.node(Q[8], k1));
      }
      mesh.part.push_back(p);
    }
}

/// The provisional positions of every node layer: the section at that height, at that height.
Eigen::MatrixXd node_positions(const ExtrusionGrid& g, const ExtrusionRules& rules) {
  Eigen::MatrixXd X(static_cast<Eigen::Index>(g.node_layers) * g.n_sec, 3);
  for (int k = 0; k < g.node_layers; ++k) {
    const auto x = g.section.positions(rules.geometry(g.z_of_node_layer[k]));
    for (int j = 0; j < g.n_sec; ++j) X.row(g.node(j, k)) << x[j].x(), x[j].y(), g.z_of_node_layer[k];
  }
  return X;
}

/// Each cavity's facets, pointing out of it: the side walls where a cavity quad meets a solid one in
/// the section, the floors and ceilings where it meets solid in the layer below or above.
void add_chamber_facets(std::vector<Chamber>& chambers, const ExtrusionGrid& g, const Eigen::MatrixXd& X) {
  const auto& quads = g.section.quads();
  std::map<std::pair<int, int>, std::vector<std::pair<int, int>>> quads_of_edge;  // the section's edges
  for (int q = 0; q < g.n_quads; ++q)
    for (int e = 0; e < 4; ++e) {
      const int a = quads[q][kQuadEdges[e][0]], b = quads[q][kQuadEdges[e][1]];
      quads_of_edge[{std::min(a, b), std::max(a, b)}].push_back({q, e});
    }
  const auto corners_of = [&](const std::array<int, 9>& Q, int k) {
    std::vector<int> f;
    for (int a = 0; a < (g.order == 2 ? 9 : 4); ++a) f.push_back(g.node(Q[a], k));
    return f;
  };
  for (std::size_t s = 0; s < g.sub.size(); ++s)
    for (int q = 0; q < g.n_quads; ++q) {
      const int c = g.cavity_at(q, static_cast<int>(s));
      if (c < 0) continue;
      const auto& Q = quads[q];
      const int k0 = g.order * static_cast<int>(s), k1 = k0 + 1, k2 = k0 + g.order;
      Eigen::Vector3d cell_centre = Eigen::Vector3d::Zero();
      for (int i = 0; i < 4; ++i) cell_centre += X.row(g.node(Q[i], k0)).transpose() / 4;
      for (int e = 0; e < 4; ++e) {
        const int a = Q[kQuadEdges[e][0]], b = Q[kQuadEdges[e][1]], mid = Q[kQuadEdges[e][2]];
        int neighbour = -1;
        for (const auto& [q2, e2] : quads_of_edge[{std::min(a, b), std::max(a, b)}])
          if (q2 != q) neighbour = q2;
        if (neighbour < 0 || g.part_at(neighbour, static_cast<int>(s)) < 0) continue;
        std::vector<int> f = g.order == 2
                                 ? std::vector<int>{g.node(a, k0), g.node(b, k0), g.node(b, k2), g.node(a, k2),
                                                    g.node(mid, k0), g.node(b, k1), g.node(mid, k2), g.node(a, k1),
                                                    g.node(mid, k1)}
                                 : std::vector<int>{g.node(a, k0), g.node(b, k0), g.node(b, k2), g.node(a, k2)};
        Eigen::Vector3d outward = 0.5 * (X.row(g.node(a, k0)) + X.row(g.node(b, k0))).transpose() - cell_centre;
        outward.z() = 0;
        chambers[c].facets.push_back(oriented(f, X, outward));
      }
      if (s > 0 && g.part_at(q, static_cast<int>(s) - 1) >= 0)
        chambers[c].facets.push_back(oriented(corners_of(Q, k0), X, -Eigen::Vector3d::UnitZ()));
      if (s + 1 < g.sub.size() && g.part_at(q, static_cast<int>(s) + 1) >= 0)
        chambers[c].facets.push_back(oriented(corners_of(Q, k2), X, Eigen::Vector3d::UnitZ()));
    }
}

/// Keeps the nodes that elements use, renumbered in the order the elements first use them; the
/// chambers' facets follow.
void compact_nodes(Mesh& mesh, const Eigen::MatrixXd& X, std::vector<Chamber>& chambers) {
  std::vector<int> new_id(X.rows(), -1);
  int count = 0;
  for (int& n : mesh.connectivity) {
    if (new_id[n] < 0) new_id[n] = count++;
    n = new_id[n];
  }
  mesh.X.resize(count, 3);
  for (Eigen::Index n = 0; n < X.rows(); ++n)
    if (new_id[n] >= 0) mesh.X.row(new_id[n]) = X.row(n);
  for (auto& chamber : chambers)
    for (auto& f : chamber.facets)
      for (int& n : f) {
        if (new_id[n] < 0) throw std::logic_error("extrude_section: chamber facet on a node of no element");
        n = new_id[n];
      }
}

/// The node sets "bottom" and "top" (the first and last node layers) and "plane_y0".
void add_boundary_sets(Mesh& mesh, double z_lo, double z_hi) {
  const double tol = 1e-9 * std::max(1.0, mesh.X.cwiseAbs().maxCoeff());
  for (int n = 0; n < mesh.X.rows(); ++n) {
    if (std::abs(mesh.X(n, 2) - z_lo) < tol) mesh.node_sets["bottom"].push_back(n);
    if (std::abs(mesh.X(n, 2) - z_hi) < tol) mesh.node_sets["top"].push_back(n);
    if (std::abs(mesh.X(n, 1)) < tol) mesh.node_sets["plane_y0"].push_back(n);
  }
}

}  // namespace

Mesh extrude_section(const ActuatorSection& section, const std::vector<ExtrusionLayer>& layers,
                     const ExtrusionRules& rules, int order, std::vector<std::string> part_names,
                     std::vector<Chamber> chambers) {
  if (layers.empty()) throw std::logic_error("extrude_section: no layers");
  if (order != 1 && order != 2) throw std::logic_error("extrude_section: order must be 1 or 2");
  const ExtrusionGrid grid(section, layers, rules, order);
  Mesh mesh;
  mesh.dim = 3;
  mesh.nodes_per_element = order == 2 ? 27 : 8;
  add_elements(mesh, grid);
  if (mesh.part.empty()) throw std::logic_error("extrude_section: no elements");
  const Eigen::MatrixXd X = node_positions(grid, rules);
  add_chamber_facets(chambers, grid, X);
  compact_nodes(mesh, X, chambers);
  mesh.part_names = std::move(part_names);
  mesh.chambers = std::move(chambers);
  add_boundary_sets(mesh, grid.z_of_node_layer.front(), grid.z_of_node_layer.back());
  return mesh;
}

}  // namespace softarm::fem

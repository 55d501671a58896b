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

}  // namespace

Mesh extrude_section(const ActuatorSection& section, const std::vector<ExtrusionLayer>& layers,
                     const ExtrusionRules& rules, int order, std::vector<std::string> part_names,
                     std::vector<Chamber> chambers) {
  if (layers.empty()) throw std::logic_error("extrude_section: no layers");
  if (order != 1 && order != 2) throw std::logic_error("extrude_section: order must be 1 or 2");
  std::vector<Sublayer> sub;
  for (std::size_t l = 0; l < layers.size(); ++l)
    for (int d = 0; d < layers[l].divisions; ++d) {
      const double h = (layers[l].z1 - layers[l].z0) / layers[l].divisions;
      sub.push_back({static_cast<int>(l), layers[l].z0 + d * h, layers[l].z0 + (d + 1) * h});
    }
  const int n_sec = section.num_nodes();
  const int node_layers = order * static_cast<int>(sub.size()) + 1;
  std::vector<double> z_of_node_layer(node_layers);
  for (std::size_t s = 0; s < sub.size(); ++s)
    for (int k = 0; k <= order; ++k)
      z_of_node_layer[order * s + k] = sub[s].z0 + (sub[s].z1 - sub[s].z0) * k / order;

  // Parts of every (quad, layer), evaluated once.
  const int n_quads = section.num_quads();
  std::vector<int> part_of(n_quads * layers.size()), cavity_of(n_quads * layers.size());
  for (std::size_t l = 0; l < layers.size(); ++l)
    for (int q = 0; q < n_quads; ++q) {
      part_of[l * n_quads + q] = rules.part(q, static_cast<int>(l));
      cavity_of[l * n_quads + q] = rules.cavity(q, static_cast<int>(l));
    }
  const auto part_at = [&](int q, int s) { return part_of[sub[s].layer * n_quads + q]; };
  const auto cavity_at = [&](int q, int s) { return cavity_of[sub[s].layer * n_quads + q]; };

  // Elements over provisional node ids k·n_sec + section node.
  const auto node = [&](int section_node, int node_layer) { return node_layer * n_sec + section_node; };
  Mesh mesh;
  mesh.dim = 3;
  mesh.nodes_per_element = order == 2 ? 27 : 8;
  for (std::size_t s = 0; s < sub.size(); ++s)
    for (int q = 0; q < n_quads; ++q) {
      const int p = part_at(q, static_cast<int>(s));
      if (p < 0) continue;
      const auto& Q = section.quads()[q];
      const int k0 = order * static_cast<int>(s), k1 = k0 + 1, k2 = k0 + order;
      if (order == 1) {
        for (int a = 0; a < 4; ++a) mesh.connectivity.push_back(node(Q[a], k0));
        for (int a = 0; a < 4; ++a) mesh.connectivity.push_back(node(Q[a], k2));
      } else {
        // VTK Hex27 from a Quad9 at three heights: corners, bottom and top edge
        // mids, vertical edge mids, face centres (ξ−: edge 3-0, ξ+: 1-2, η−: 0-1,
        // η+: 2-3, ζ−, ζ+), body centre.
        for (int a = 0; a < 4; ++a) mesh.connectivity.push_back(node(Q[a], k0));
        for (int a = 0; a < 4; ++a) mesh.connectivity.push_back(node(Q[a], k2));
        for (int a = 4; a < 8; ++a) mesh.connectivity.push_back(node(Q[a], k0));
        for (int a = 4; a < 8; ++a) mesh.connectivity.push_back(node(Q[a], k2));
        for (int a = 0; a < 4; ++a) mesh.connectivity.push_back(node(Q[a], k1));
        for (int a : {7, 5, 4, 6}) mesh.connectivity.push_back(node(Q[a], k1));
        mesh.connectivity.push_back(node(Q[8], k0));
        mesh.connectivity.push_back(node(Q[8], k2));
        mesh.connectivity.push_back(node(Q[8], k1));
      }
      mesh.part.push_back(p);
    }
  if (mesh.part.empty()) throw std::logic_error("extrude_section: no elements");

  // Section edge adjacency for the chambers' side walls.
  std::map<std::pair<int, int>, std::vector<std::pair<int, int>>> quads_of_edge;
  for (int q = 0; q < n_quads; ++q)
    for (int e = 0; e < 4; ++e) {
      const int a = section.quads()[q][kQuadEdges[e][0]], b = section.quads()[q][kQuadEdges[e][1]];
      quads_of_edge[{std::min(a, b), std::max(a, b)}].push_back({q, e});
    }

  // Provisional positions (all node layers), then facets, then compaction.
  Eigen::MatrixXd X(static_cast<Eigen::Index>(node_layers) * n_sec, 3);
  for (int k = 0; k < node_layers; ++k) {
    const auto x = section.positions(rules.geometry(z_of_node_layer[k]));
    for (int j = 0; j < n_sec; ++j) X.row(node(j, k)) << x[j].x(), x[j].y(), z_of_node_layer[k];
  }
  const auto corners_of = [&](const std::array<int, 9>& Q, int k) {
    std::vector<int> f;
    for (int a = 0; a < (order == 2 ? 9 : 4); ++a) f.push_back(node(Q[a], k));
    return f;
  };
  for (std::size_t s = 0; s < sub.size(); ++s)
    for (int q = 0; q < n_quads; ++q) {
      const int c = cavity_at(q, static_cast<int>(s));
      if (c < 0) continue;
      const auto& Q = section.quads()[q];
      const int k0 = order * static_cast<int>(s), k1 = k0 + 1, k2 = k0 + order;
      Eigen::Vector3d cell_centre = Eigen::Vector3d::Zero();
      for (int i = 0; i < 4; ++i) cell_centre += X.row(node(Q[i], k0)).transpose() / 4;
      for (int e = 0; e < 4; ++e) {
        const int a = Q[kQuadEdges[e][0]], b = Q[kQuadEdges[e][1]], mid = Q[kQuadEdges[e][2]];
        int neighbour = -1;
        for (const auto& [q2, e2] : quads_of_edge[{std::min(a, b), std::max(a, b)}])
          if (q2 != q) neighbour = q2;
        if (neighbour < 0 || part_at(neighbour, static_cast<int>(s)) < 0) continue;
        std::vector<int> f = order == 2 ? std::vector<int>{node(a, k0), node(b, k0), node(b, k2), node(a, k2),
                                                           node(mid, k0), node(b, k1), node(mid, k2), node(a, k1),
                                                           node(mid, k1)}
                                        : std::vector<int>{node(a, k0), node(b, k0), node(b, k2), node(a, k2)};
        Eigen::Vector3d outward = 0.5 * (X.row(node(a, k0)) + X.row(node(b, k0))).transpose() - cell_centre;
        outward.z() = 0;
        chambers[c].facets.push_back(oriented(f, X, outward));
      }
      if (s > 0 && part_at(q, static_cast<int>(s) - 1) >= 0)
        chambers[c].facets.push_back(oriented(corners_of(Q, k0), X, -Eigen::Vector3d::UnitZ()));
      if (s + 1 < sub.size() && part_at(q, static_cast<int>(s) + 1) >= 0)
        chambers[c].facets.push_back(oriented(corners_of(Q, k2), X, Eigen::Vector3d::UnitZ()));
    }

  // Compact: keep the nodes that elements use.
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
  mesh.part_names = std::move(part_names);
  mesh.chambers = std::move(chambers);

  const double z_lo = z_of_node_layer.front(), z_hi = z_of_node_layer.back();
  const double tol = 1e-9 * std::max(1.0, mesh.X.cwiseAbs().maxCoeff());
  for (int n = 0; n < count; ++n) {
    if (std::abs(mesh.X(n, 2) - z_lo) < tol) mesh.node_sets["bottom"].push_back(n);
    if (std::abs(mesh.X(n, 2) - z_hi) < tol) mesh.node_sets["top"].push_back(n);
    if (std::abs(mesh.X(n, 1)) < tol) mesh.node_sets["plane_y0"].push_back(n);
  }
  return mesh;
}

}  // namespace softarm::fem

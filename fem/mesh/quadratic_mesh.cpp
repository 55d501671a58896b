#include "fem/mesh/quadratic_mesh.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <stdexcept>

namespace softarm::fem {

Mesh to_quadratic(const Mesh& linear) {
  if (linear.dim != 2 || linear.nodes_per_element != 4)
    throw std::logic_error("to_quadratic: needs a 2D mesh of 4-node quadrilaterals");
  Mesh q = linear;
  q.nodes_per_element = 9;
  q.connectivity.clear();

  using Edge = std::pair<int, int>;
  auto key = [](int a, int b) { return Edge{std::min(a, b), std::max(a, b)}; };
  std::map<Edge, int> mid_node;
  std::map<Edge, int> edge_use;  // how many elements share an edge (1 = boundary)
  std::vector<Eigen::RowVector2d> extra;
  auto add_node = [&](const Eigen::RowVector2d& x) {
    extra.push_back(x);
    return linear.num_nodes() + static_cast<int>(extra.size()) - 1;
  };
  for (int e = 0; e < linear.num_elements(); ++e) {
    const int* n = linear.element(e);
    int conn[9];
    for (int a = 0; a < 4; ++a) conn[a] = n[a];
    for (int a = 0; a < 4; ++a) {
      const int i = n[a], j = n[(a + 1) % 4];
      const Edge k = key(i, j);
      ++edge_use[k];
      auto it = mid_node.find(k);
      if (it == mid_node.end())
        it = mid_node.emplace(k, add_node(0.5 * (linear.X.row(i) + linear.X.row(j)))).first;
      conn[4 + a] = it->second;
    }
    conn[8] = add_node(0.25 * (linear.X.row(n[0]) + linear.X.row(n[1]) + linear.X.row(n[2]) + linear.X.row(n[3])));
    q.connectivity.insert(q.connectivity.end(), conn, conn + 9);
  }
  q.X.conservativeResize(linear.num_nodes() + static_cast<int>(extra.size()), 2);
  for (std::size_t k = 0; k < extra.size(); ++k) q.X.row(linear.num_nodes() + static_cast<int>(k)) = extra[k];

  for (auto& [name, nodes] : q.node_sets) {
    const std::set<int> members(nodes.begin(), nodes.end());
    for (const auto& [edge, mid] : mid_node)
      if (edge_use[edge] == 1 && members.count(edge.first) && members.count(edge.second)) nodes.push_back(mid);
    std::sort(nodes.begin(), nodes.end());
  }
  for (auto& chamber : q.chambers)
    for (auto& facet : chamber.facets) {
      if (facet.size() != 2) throw std::logic_error("to_quadratic: chamber facets must be 2-node edges");
      facet = {facet[0], mid_node.at(key(facet[0], facet[1])), facet[1]};
    }
  return q;
}

}  // namespace softarm::fem

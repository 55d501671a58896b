#include "fem/mesh/quadratic_mesh.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <stdexcept>

namespace softarm::fem {
namespace {

using LocalCorners = std::vector<int>;

/// The reference topology of a linear element as its quadratic version sees it.
struct Topology {
  int linear_nodes;
  int quadratic_nodes;
  std::vector<LocalCorners> added;   // corners whose centroid each added node (in VTK order) sits at
  std::vector<LocalCorners> facets;  // boundary facets (edges in 2D, faces in 3D), corners in cyclic order
};

const Topology kQuad{4, 9, {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 1, 2, 3}}, {{0, 1}, {1, 2}, {2, 3}, {3, 0}}};

const Topology kHex{8,
                    27,
                    {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6}, {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7},
                     {0, 3, 7, 4}, {1, 2, 6, 5}, {0, 1, 5, 4}, {3, 2, 6, 7}, {0, 1, 2, 3}, {4, 5, 6, 7},
                     {0, 1, 2, 3, 4, 5, 6, 7}},
                    {{0, 3, 7, 4}, {1, 2, 6, 5}, {0, 1, 5, 4}, {3, 2, 6, 7}, {0, 1, 2, 3}, {4, 5, 6, 7}}};

/// Nodes at the centroids of groups of linear nodes (edges, faces, elements),
/// created once per group and shared by every element that has the group.
class CentroidNodes {
 public:
  explicit CentroidNodes(const Eigen::MatrixXd& X) : X_(X) {}
  int operator()(std::vector<int> corners) {
    std::sort(corners.begin(), corners.end());
    auto it = ids_.find(corners);
    if (it != ids_.end()) return it->second;
    Eigen::RowVectorXd x = Eigen::RowVectorXd::Zero(X_.cols());
    for (int c : corners) x += X_.row(c);
    extra_.push_back(x / static_cast<double>(corners.size()));
    const int id = static_cast<int>(X_.rows() + extra_.size()) - 1;
    ids_.emplace(std::move(corners), id);
    return id;
  }
  int at(std::vector<int> corners) const {
    std::sort(corners.begin(), corners.end());
    return ids_.at(corners);
  }
  Eigen::MatrixXd all_nodes() const {
    Eigen::MatrixXd all(X_.rows() + static_cast<Eigen::Index>(extra_.size()), X_.cols());
    all.topRows(X_.rows()) = X_;
    for (std::size_t k = 0; k < extra_.size(); ++k) all.row(X_.rows() + static_cast<Eigen::Index>(k)) = extra_[k];
    return all;
  }

 private:
  const Eigen::MatrixXd& X_;
  std::map<std::vector<int>, int> ids_;
  std::vector<Eigen::RowVectorXd> extra_;
};

/// The nodes of a promoted facet in facet order: (a, mid, b) for an edge; corners,
/// mid-edges in cyclic order, centre for a quadrilateral face.
std::vector<int> quadratic_facet(const std::vector<int>& corners, const CentroidNodes& centroid) {
  const int n = static_cast<int>(corners.size());
  if (n == 2) return {corners[0], centroid.at(corners), corners[1]};
  std::vector<int> nodes = corners;
  for (int a = 0; a < n; ++a) nodes.push_back(centroid.at({corners[a], corners[(a + 1) % n]}));
  nodes.push_back(centroid.at(corners));
  return nodes;
}

Mesh promote(const Mesh& linear, const Topology& topology) {
  Mesh q = linear;
  q.nodes_per_element = topology.quadratic_nodes;
  q.connectivity.clear();
  CentroidNodes centroid(linear.X);
  std::map<std::vector<int>, std::vector<int>> facet_corners;  // sorted corners → cyclic corners
  std::map<std::vector<int>, int> facet_use;                   // how many elements share a facet (1 = boundary)
  auto global = [](const int* n, const LocalCorners& local) {
    std::vector<int> g;
    for (int a : local) g.push_back(n[a]);
    return g;
  };
  for (int e = 0; e < linear.num_elements(); ++e) {
    const int* n = linear.element(e);
    q.connectivity.insert(q.connectivity.end(), n, n + topology.linear_nodes);
    for (const auto& local : topology.added) q.connectivity.push_back(centroid(global(n, local)));
    for (const auto& local : topology.facets) {
      std::vector<int> corners = global(n, local), key = corners;
      std::sort(key.begin(), key.end());
      facet_corners.emplace(key, corners);
      ++facet_use[key];
    }
  }
  q.X = centroid.all_nodes();

  for (auto& [name, nodes] : q.node_sets) {
    const std::set<int> members(nodes.begin(), nodes.end());
    for (const auto& [key, corners] : facet_corners)
      if (facet_use[key] == 1 && std::all_of(key.begin(), key.end(), [&](int c) { return members.count(c) > 0; }))
        for (int node : quadratic_facet(corners, centroid)) nodes.push_back(node);
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  }
  const std::size_t facet_nodes = topology.facets.front().size();
  for (auto& chamber : q.chambers)
    for (auto& facet : chamber.facets) {
      if (facet.size() != facet_nodes)
        throw std::logic_error("to_quadratic: chamber facets must have " + std::to_string(facet_nodes) + " nodes");
      facet = quadratic_facet(facet, centroid);
    }
  return q;
}

}  // namespace

Mesh to_quadratic(const Mesh& linear, const EdgeProjection& curved_edges) {
  if (linear.dim != 2 || linear.nodes_per_element != 4)
    throw std::logic_error("to_quadratic: needs a 2D mesh of 4-node quadrilaterals");
  Mesh q = promote(linear, kQuad);
  if (!curved_edges) return q;
  for (int e = 0; e < q.num_elements(); ++e) {
    const int* n = q.element(e);
    for (int a = 0; a < 4; ++a) {
      const auto on_curve = curved_edges(q.X.row(n[a]).transpose(), q.X.row(n[(a + 1) % 4]).transpose());
      if (on_curve) q.X.row(n[4 + a]) = on_curve->transpose();
    }
  }
  for (int e = 0; e < q.num_elements(); ++e) {  // Gordon–Hall centre of the (possibly curved) element
    const int* n = q.element(e);
    Eigen::RowVector2d centre = Eigen::RowVector2d::Zero();
    for (int a = 0; a < 4; ++a) centre += 0.5 * q.X.row(n[4 + a]) - 0.25 * q.X.row(n[a]);
    q.X.row(n[8]) = centre;
  }
  return q;
}

Mesh to_quadratic_3d(const Mesh& linear) {
  if (linear.dim != 3 || linear.nodes_per_element != 8)
    throw std::logic_error("to_quadratic_3d: needs a 3D mesh of 8-node hexahedra");
  return promote(linear, kHex);
}

}  // namespace softarm::fem

#include "fem/assembly/stiff_inclusions.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numeric>

namespace softarm::fem {
namespace {
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

Vec3 node(const Vector& x, int n) { return x.segment<3>(3 * n); }

int find_root(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

Vec3 centroid(const Vector& x, const std::vector<int>& group) {
  Vec3 c = Vec3::Zero();
  for (int n : group) c += node(x, n);
  return c / static_cast<double>(group.size());
}

}  // namespace

StiffInclusions StiffInclusions::of_parts(const Mesh& mesh, const std::vector<int>& parts) {
  StiffInclusions out;
  if (mesh.dim != 3 || parts.empty()) return out;
  const int nodes_per = mesh.nodes_per_element;
  std::vector<int> parent(mesh.num_nodes());
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<char> member(mesh.num_nodes(), 0);
  for (int e = 0; e < mesh.num_elements(); ++e) {
    if (std::find(parts.begin(), parts.end(), mesh.part[e]) == parts.end()) continue;
    const int* nodes = mesh.element(e);
    for (int k = 0; k < nodes_per; ++k) {
      member[nodes[k]] = 1;
      parent[find_root(parent, nodes[k])] = find_root(parent, nodes[0]);
    }
  }
  std::vector<int> group_of_root(mesh.num_nodes(), -1);
  for (int n = 0; n < mesh.num_nodes(); ++n) {
    if (!member[n]) continue;
    int& g = group_of_root[find_root(parent, n)];
    if (g < 0) {
      g = static_cast<int>(out.groups_.size());
      out.groups_.emplace_back();
    }
    out.groups_[g].push_back(n);
  }
  return out;
}

void StiffInclusions::correct_update(const Vector& x, const Vector& dx, Vector& out) const {
  for (const auto& group : groups_) {
    const Vec3 c = centroid(x, group);
    // Best-fit infinitesimal rotation of δx: J ω = Σ r_i × δx_i, J = Σ (|r_i|² I − r_i r_iᵀ)
    // (the group's centroid frame makes the translation drop out).
    Mat3 J = Mat3::Zero();
    Vec3 h = Vec3::Zero();
    for (int n : group) {
      const Vec3 r = node(x, n) - c;
      J += r.squaredNorm() * Mat3::Identity() - r * r.transpose();
      h += r.cross(node(dx, n));
    }
    const Eigen::LDLT<Mat3> ldlt(J);
    if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 0)) continue;  // collinear nodes
    const Vec3 w = ldlt.solve(h);
    const double t = w.norm();
    if (!(t > 0) || !std::isfinite(t)) continue;
    // Rodrigues: R − I − [ω]× = (sin t / t − 1) [ω]× + ((1 − cos t) / t²) [ω]×², with series below
    // t = 1e-4 where the closed forms lose their digits.
    const double a = t < 1e-4 ? -t * t / 6 : std::sin(t) / t - 1;
    const double b = t < 1e-4 ? 0.5 - t * t / 24 : (1 - std::cos(t)) / (t * t);
    for (int n : group) {
      const Vec3 r = node(x, n) - c;
      const Vec3 wr = w.cross(r);
      out.segment<3>(3 * n) += a * wr + b * w.cross(wr);
    }
  }
}

}  // namespace softarm::fem

#include "fem/mesh/structured_mesh.hpp"

#include <algorithm>
#include <cstdint>
#include <stdexcept>

namespace softarm::fem {
namespace {

/// Deterministic pseudo-random number in [−1, 1] for grid point (i, j), component c
/// (splitmix64 finaliser): the same mesh on every platform and run.
double hash_unit(int i, int j, int c) {
  std::uint64_t x = (static_cast<std::uint64_t>(i) << 40) ^ (static_cast<std::uint64_t>(j) << 16) ^
                    static_cast<std::uint64_t>(c) ^ 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  x ^= x >> 31;
  return 2.0 * static_cast<double>(x >> 11) / static_cast<double>(1ull << 53) - 1.0;
}

double signed_area(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                   const Eigen::Vector2d& d) {
  auto cross = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q) { return p.x() * q.y() - p.y() * q.x(); };
  return 0.5 * (cross(a, b) + cross(b, c) + cross(c, d) + cross(d, a));
}

}  // namespace

int QuadMeshBuilder::add_node(const Eigen::Vector2d& rz) {
  nodes_.push_back(rz);
  return static_cast<int>(nodes_.size()) - 1;
}

void QuadMeshBuilder::add_quad(int a, int b, int c, int d, int part) {
  const double area = signed_area(node(a), node(b), node(c), node(d));
  const double diagonal = std::max((node(a) - node(c)).squaredNorm(), (node(b) - node(d)).squaredNorm());
  if (!(std::abs(area) > 1e-12 * diagonal))
    throw std::logic_error("QuadMeshBuilder: element with zero area (nodes " + std::to_string(a) + ", " +
                           std::to_string(b) + ", " + std::to_string(c) + ", " + std::to_string(d) + ")");
  if (area < 0) std::swap(b, d);  // reverse the cycle: counter-clockwise in (r, z)
  connectivity_.insert(connectivity_.end(), {a, b, c, d});
  part_.push_back(part);
}

void QuadMeshBuilder::add_grid(const std::vector<std::vector<int>>& lines, int part) {
  for (std::size_t j = 0; j + 1 < lines.size(); ++j) {
    if (lines[j].size() != lines[j + 1].size()) throw std::logic_error("QuadMeshBuilder::add_grid: ragged grid");
    for (std::size_t i = 0; i + 1 < lines[j].size(); ++i)
      add_quad(lines[j][i], lines[j + 1][i], lines[j + 1][i + 1], lines[j][i + 1], part);
  }
}

Mesh QuadMeshBuilder::finish(std::vector<std::string> part_names) {
  Mesh mesh;
  mesh.dim = 2;
  mesh.nodes_per_element = 4;
  mesh.X.resize(static_cast<Eigen::Index>(nodes_.size()), 2);
  for (std::size_t n = 0; n < nodes_.size(); ++n) mesh.X.row(static_cast<Eigen::Index>(n)) = nodes_[n].transpose();
  mesh.connectivity = std::move(connectivity_);
  mesh.part = std::move(part_);
  mesh.part_names = std::move(part_names);
  nodes_.clear();
  connectivity_.clear();
  part_.clear();
  return mesh;
}

Mesh rectangle_mesh(double r0, double r1, double z0, double z1, int nr, int nz, double distortion) {
  if (!(r0 >= 0) || !(r1 > r0) || !(z1 > z0) || nr < 1 || nz < 1 || !(distortion >= 0 && distortion <= 1))
    throw std::invalid_argument("rectangle_mesh: need 0 <= r0 < r1, z0 < z1, nr, nz >= 1 and distortion in [0, 1]");
  const double hr = (r1 - r0) / nr, hz = (z1 - z0) / nz;
  // A corner moved by at most 0.2 h in each direction keeps every bilinear
  // Jacobian positive: det J >= (0.3 h_r)(0.3 h_z) − (0.2 h_r)(0.2 h_z) > 0.
  const double amplitude = 0.2 * distortion;

  QuadMeshBuilder builder;
  std::vector<std::vector<int>> columns(static_cast<std::size_t>(nr) + 1);  // columns[i][j], i along r
  for (int i = 0; i <= nr; ++i)
    for (int j = 0; j <= nz; ++j) {
      double r = r0 + i * hr, z = z0 + j * hz;
      if (i > 0 && i < nr && j > 0 && j < nz) {
        r += amplitude * hr * hash_unit(i, j, 0);
        z += amplitude * hz * hash_unit(i, j, 1);
      }
      columns[static_cast<std::size_t>(i)].push_back(builder.add_node(r, z));
    }
  builder.add_grid(columns, 0);
  Mesh mesh = builder.finish({"solid"});

  auto& sets = mesh.node_sets;
  for (int j = 0; j <= nz; ++j) {
    sets["inner"].push_back(columns.front()[static_cast<std::size_t>(j)]);
    sets["outer"].push_back(columns.back()[static_cast<std::size_t>(j)]);
  }
  for (int i = 0; i <= nr; ++i) {
    sets["bottom"].push_back(columns[static_cast<std::size_t>(i)].front());
    sets["top"].push_back(columns[static_cast<std::size_t>(i)].back());
  }
  std::vector<int> boundary;
  for (const char* side : {"inner", "outer", "bottom", "top"})
    boundary.insert(boundary.end(), sets[side].begin(), sets[side].end());
  std::sort(boundary.begin(), boundary.end());
  boundary.erase(std::unique(boundary.begin(), boundary.end()), boundary.end());
  sets["boundary"] = boundary;

  if (r0 == 0) {
    sets["axis"] = sets["inner"];
  } else {
    Chamber chamber{1, "chamber", {}};
    const auto& inner = sets["inner"];
    for (std::size_t j = 0; j + 1 < inner.size(); ++j) chamber.facets.push_back({inner[j], inner[j + 1]});
    mesh.chambers.push_back(std::move(chamber));
  }
  return mesh;
}

}  // namespace softarm::fem

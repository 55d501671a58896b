#include "fem/mesh/structured_mesh.hpp"

#include <algorithm>
#include <cmath>
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
    Chamber chamber{1, "chamber", {}, {}};
    const auto& inner = sets["inner"];
    for (std::size_t j = 0; j + 1 < inner.size(); ++j) chamber.facets.push_back({inner[j], inner[j + 1]});
    mesh.chambers.push_back(std::move(chamber));
  }
  return mesh;
}

namespace {

/// Trilinear hexahedra of a logically (ni × nj × nk) grid: node(i, j, k) gives the node id,
/// so that periodic grids can wrap. Corners in VTK order: (i, j, k), (i+1, j, k),
/// (i+1, j+1, k), (i, j+1, k), then the same at k+1; positive Jacobian when
/// (i, j, k) is a right-handed parametrisation of the solid.
template <class NodeId>
Mesh hexahedral_grid(Eigen::MatrixXd X, int ni, int nj, int nk, NodeId node) {
  Mesh mesh;
  mesh.dim = 3;
  mesh.nodes_per_element = 8;
  mesh.X = std::move(X);
  for (int k = 0; k < nk; ++k)
    for (int j = 0; j < nj; ++j)
      for (int i = 0; i < ni; ++i) {
        mesh.connectivity.insert(mesh.connectivity.end(),
                                 {node(i, j, k), node(i + 1, j, k), node(i + 1, j + 1, k), node(i, j + 1, k),
                                  node(i, j, k + 1), node(i + 1, j, k + 1), node(i + 1, j + 1, k + 1),
                                  node(i, j + 1, k + 1)});
        mesh.part.push_back(0);
      }
  mesh.part_names = {"solid"};
  return mesh;
}

}  // namespace

Mesh box_mesh(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int nx, int ny, int nz, double distortion) {
  if (!((hi - lo).minCoeff() > 0) || nx < 1 || ny < 1 || nz < 1 || !(distortion >= 0 && distortion <= 1))
    throw std::invalid_argument("box_mesh: need lo < hi on every axis, nx, ny, nz >= 1 and distortion in [0, 1]");
  const Eigen::Vector3i n(nx, ny, nz);
  const Eigen::Vector3d h = (hi - lo).cwiseQuotient(n.cast<double>());
  // With nodes moved by at most 0.1 h_i along axis i, ∂X/∂ξ = diag(h/2)(I + E) with
  // |E_ik| <= 0.2 (the |∂N_a/∂ξ_k| of a trilinear element sum to 1), so I + E is
  // diagonally dominant (off-diagonal row sums <= 0.4 < 0.8) and det(∂X/∂ξ) > 0.
  const double amplitude = 0.1 * distortion;
  auto id = [&](int i, int j, int k) { return i + (nx + 1) * (j + (ny + 1) * k); };
  Eigen::MatrixXd X((nx + 1) * (ny + 1) * (nz + 1), 3);
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        const Eigen::Vector3i ijk(i, j, k);
        const bool interior = (ijk.array() > 0).all() && (ijk.array() < n.array()).all();
        for (int c = 0; c < 3; ++c)
          X(id(i, j, k), c) = lo[c] + ijk[c] * h[c] + (interior ? amplitude * h[c] * hash_unit(i, j, 3 * k + c) : 0.0);
      }
  Mesh mesh = hexahedral_grid(std::move(X), nx, ny, nz, id);
  const char* names[3][2] = {{"x0", "x1"}, {"y0", "y1"}, {"z0", "z1"}};
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        const Eigen::Vector3i ijk(i, j, k);
        bool on_boundary = false;
        for (int c = 0; c < 3; ++c)
          for (int side = 0; side < 2; ++side)
            if (ijk[c] == side * n[c]) {
              mesh.node_sets[names[c][side]].push_back(id(i, j, k));
              on_boundary = true;
            }
        if (on_boundary) mesh.node_sets["boundary"].push_back(id(i, j, k));
      }
  return mesh;
}

Mesh hollow_cylinder_mesh(double r_inner, double r_outer, double length, int n_radial, int n_circumferential,
                          int n_axial) {
  if (!(r_inner > 0) || !(r_outer > r_inner) || !(length > 0) || n_radial < 1 || n_circumferential < 3 || n_axial < 1)
    throw std::invalid_argument(
        "hollow_cylinder_mesh: need 0 < r_inner < r_outer, length > 0, n_radial, n_axial >= 1, n_circumferential >= 3");
  constexpr double kTwoPi = 6.283185307179586;
  const int nr = n_radial + 1, nc = n_circumferential;
  // Node (i, j, k): radius index i, angle index j (periodic), axial index k.
  auto id = [&](int i, int j, int k) { return i + nr * ((j % nc) + nc * k); };
  Eigen::MatrixXd X(nr * nc * (n_axial + 1), 3);
  for (int k = 0; k <= n_axial; ++k)
    for (int j = 0; j < nc; ++j)
      for (int i = 0; i < nr; ++i) {
        const double r = r_inner + (r_outer - r_inner) * i / n_radial, t = kTwoPi * j / nc;
        X.row(id(i, j, k)) << r * std::cos(t), r * std::sin(t), length * k / n_axial;
      }
  // (r, θ, z) is right-handed (e_r × e_θ = e_z): positive Jacobians.
  Mesh mesh = hexahedral_grid(std::move(X), n_radial, nc, n_axial, id);
  for (int k = 0; k <= n_axial; ++k)
    for (int j = 0; j < nc; ++j) {
      mesh.node_sets["inner"].push_back(id(0, j, k));
      mesh.node_sets["outer"].push_back(id(n_radial, j, k));
    }
  for (int j = 0; j < nc; ++j)
    for (int i = 0; i < nr; ++i) {
      mesh.node_sets["z0"].push_back(id(i, j, 0));
      mesh.node_sets["z1"].push_back(id(i, j, n_axial));
    }
  // Facets with s along θ and t along z: x_s × x_t ∝ e_θ × e_z = e_r, out of the bore.
  Chamber bore{1, "bore", {}, {}};
  for (int k = 0; k < n_axial; ++k)
    for (int j = 0; j < nc; ++j) bore.facets.push_back({id(0, j, k), id(0, j + 1, k), id(0, j + 1, k + 1), id(0, j, k + 1)});
  mesh.chambers.push_back(std::move(bore));
  for (auto& [name, nodes] : mesh.node_sets) std::sort(nodes.begin(), nodes.end());
  return mesh;
}

}  // namespace softarm::fem

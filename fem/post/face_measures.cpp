#include "fem/post/face_measures.hpp"

#include <Eigen/Geometry>
#include <array>
#include <stdexcept>

#include "fem/elements/axisymmetric_quad.hpp"
#include "fem/elements/serendipity_quad.hpp"

namespace softarm::fem {
namespace {
// Faces of the VTK hexahedron in quad order, oriented out of the element
// (corners; for Hex27 then the mid-edge nodes and the face centre; Hex20 faces
// are the first eight of a Hex27 face, without the centre).
constexpr int kHex8Faces[6][4] = {{0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4}, {3, 7, 6, 2}, {0, 3, 2, 1}, {4, 5, 6, 7}};
constexpr int kHex27Faces[6][9] = {{0, 4, 7, 3, 16, 15, 19, 11, 20}, {1, 2, 6, 5, 9, 18, 13, 17, 21},
                                   {0, 1, 5, 4, 8, 17, 12, 16, 22},  {3, 7, 6, 2, 19, 14, 18, 10, 23},
                                   {0, 3, 2, 1, 11, 10, 9, 8, 24},   {4, 5, 6, 7, 12, 13, 14, 15, 25}};
}  // namespace

std::vector<std::vector<int>> boundary_faces_in(const Mesh& mesh, const std::vector<int>& node_set) {
  const int npe = mesh.nodes_per_element;
  if (mesh.dim != 3 || (npe != 8 && npe != 20 && npe != 27))
    throw std::logic_error("boundary_faces_in: hexahedral meshes only");
  std::vector<char> in(mesh.num_nodes(), 0);
  for (int n : node_set) in[n] = 1;
  const int face_nodes = npe == 27 ? 9 : npe == 20 ? 8 : 4;
  std::vector<std::vector<int>> faces;
  for (int e = 0; e < mesh.num_elements(); ++e)
    for (int f = 0; f < 6; ++f) {
      std::vector<int> face;
      for (int a = 0; a < face_nodes; ++a) face.push_back(mesh.element(e)[npe == 8 ? kHex8Faces[f][a] : kHex27Faces[f][a]]);
      bool all = true;
      for (int n : face) all = all && in[n];
      if (all) faces.push_back(face);
    }
  return faces;
}

namespace {
/// Calls visit(facet, N, p, da) at every 3×3 Gauss point of every 4-, 8- or 9-node facet:
/// shape values N, position p and vector area element da = w x_s × x_t.
template <class Visit>
void for_each_facet_point(const std::vector<std::vector<int>>& facets, const Eigen::VectorXd& x, Visit&& visit) {
  constexpr double g = 0.7745966692414834, kPoints[3] = {-g, 0.0, g}, kWeights[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  for (const auto& f : facets) {
    const int n = static_cast<int>(f.size());
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        std::array<double, 9> N{}, dN_ds{}, dN_dt{};
        if (n == 9)
          axisym::Quad9::shape(kPoints[i], kPoints[j], N.data(), dN_ds.data(), dN_dt.data());
        else if (n == 8)
          Quad8::shape(kPoints[i], kPoints[j], N.data(), dN_ds.data(), dN_dt.data());
        else
          axisym::Quad4::shape(kPoints[i], kPoints[j], N.data(), dN_ds.data(), dN_dt.data());
        Eigen::Vector3d p = Eigen::Vector3d::Zero(), xs = p, xt = p;
        for (int a = 0; a < n; ++a) {
          const Eigen::Vector3d xa = x.segment<3>(3 * f[a]);
          p += N[a] * xa, xs += dN_ds[a] * xa, xt += dN_dt[a] * xa;
        }
        visit(f, N, p, Eigen::Vector3d(kWeights[i] * kWeights[j] * xs.cross(xt)));
      }
  }
}
}  // namespace

Eigen::VectorXd nodal_area_weights(const std::vector<std::vector<int>>& facets, const Eigen::VectorXd& x) {
  Eigen::VectorXd w = Eigen::VectorXd::Zero(x.size() / 3);
  for_each_facet_point(facets, x, [&](const std::vector<int>& f, const std::array<double, 9>& N, const Eigen::Vector3d&,
                                      const Eigen::Vector3d& da) {
    for (std::size_t a = 0; a < f.size(); ++a) w[f[a]] += N[a] * da.norm();
  });
  return w;
}

FaceMeasure measure_face(const std::vector<std::vector<int>>& facets, const Eigen::VectorXd& x) {
  FaceMeasure m;
  Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();
  for_each_facet_point(facets, x, [&](const std::vector<int>&, const std::array<double, 9>&, const Eigen::Vector3d& p,
                                      const Eigen::Vector3d& da) {
    m.vector_area += da;
    m.area += da.norm();
    first_moment += da.norm() * p;
  });
  if (m.area > 0) m.centroid = first_moment / m.area;
  return m;
}

FaceMeasure mirror_completed(const FaceMeasure& half) {
  FaceMeasure full = half;
  full.vector_area = 2 * half.vector_area;
  full.vector_area.y() = 0;
  full.area = 2 * half.area;
  full.centroid.y() = 0;
  return full;
}

}  // namespace softarm::fem

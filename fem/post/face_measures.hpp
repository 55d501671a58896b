#pragma once
// Integral measures of a face of a 3D mesh in its deformed configuration: the
// vector area a = ∫ n dA and the centroid c = ∫ x dA / ∫ dA, integrated exactly
// over bilinear (4-node), serendipity (8-node) or biquadratic (9-node) facets
// with 3×3 Gauss points.
// They define the 3CA's outputs (spec §4): the bending angle is the angle
// between the free face's mean normal a/|a| now and at rest; the tip is the
// face's centroid (a face with a centre hole has no centre node).
#include <Eigen/Core>
#include <vector>

#include "fem/mesh/mesh.hpp"

namespace softarm::fem {

struct FaceMeasure {
  Eigen::Vector3d vector_area = Eigen::Vector3d::Zero();  // ∫ n dA, mm²
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();     // mm
  double area = 0;                                        // ∫ dA, mm²
};

/// The element faces whose nodes all lie in `node_set` (faces of 3D elements,
/// oriented out of their element), as facets in VTK quad order.
std::vector<std::vector<int>> boundary_faces_in(const Mesh& mesh, const std::vector<int>& node_set);

/// ∫ N_a dA of every node a over the facets at positions x (0 off the face): the
/// weights that spread a force over a face consistently (a tip mass's weight).
Eigen::VectorXd nodal_area_weights(const std::vector<std::vector<int>>& facets, const Eigen::VectorXd& x);

/// Measures the facets at positions x (node-major, 3 per node).
FaceMeasure measure_face(const std::vector<std::vector<int>>& facets, const Eigen::VectorXd& x);

/// The face measure of a whole body from that of its half y ≥ 0 (mirror plane y = 0).
FaceMeasure mirror_completed(const FaceMeasure& half);

}  // namespace softarm::fem

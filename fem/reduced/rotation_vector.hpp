#pragma once
// exp([v]×): the rotation by |v| about v (Rodrigues), the rods' frame update over an interval
// (spatial_rod.hpp, spatial_cell_rod.hpp).
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace softarm::fem {

inline Eigen::Matrix3d rotation_exp(const Eigen::Vector3d& v) {
  const double angle = v.norm();
  if (angle < 1e-300) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, v / angle).toRotationMatrix();
}

}  // namespace softarm::fem

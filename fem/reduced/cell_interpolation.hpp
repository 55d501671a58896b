#pragma once
// How the cell rods (cell_rod.hpp, spatial_cell_rod.hpp) read their cells' tables: linearly
// between a cell's output states along its load ramp, and by Lagrange's polynomial through the
// cells along the 3CA's height. Values may be scalars, vectors or matrices (Eigen).
#include <algorithm>
#include <optional>
#include <vector>

namespace softarm::fem {

/// The column `v` of a table at `x` along its ramp `xs` (increasing), linear between entries;
/// nothing outside the ramp (a cell that did not reach a load says nothing about it).
template <class T>
std::optional<T> along_ramp(const std::vector<double>& xs, const std::vector<T>& v, double x) {
  if (xs.empty() || x < xs.front() - 1e-9 || x > xs.back() + 1e-9) return std::nullopt;
  for (std::size_t i = 1; i < xs.size(); ++i)
    if (x <= xs[i] + 1e-9) {
      const double f = std::clamp((x - xs[i - 1]) / (xs[i] - xs[i - 1]), 0.0, 1.0);
      return T(v[i - 1] + f * (v[i] - v[i - 1]));
    }
  return v.back();
}

/// The share of the interval [at − width/2, at + width/2] inside [z0, z1]: how much of a rod's
/// interval an end table covers.
inline double overlap_share(double at, double width, double z0, double z1) {
  return std::clamp((std::min(at + width / 2, z1) - std::max(at - width / 2, z0)) / width, 0.0, 1.0);
}

/// Lagrange's interpolating polynomial through (z_k, v_k) at `at`.
template <class T>
T lagrange(const std::vector<double>& z, const std::vector<T>& v, double at) {
  T sum = T(0 * v.front());
  for (std::size_t k = 0; k < z.size(); ++k) {
    double w = 1;
    for (std::size_t j = 0; j < z.size(); ++j)
      if (j != k) w *= (at - z[j]) / (z[k] - z[j]);
    sum = T(sum + w * v[k]);
  }
  return sum;
}

}  // namespace softarm::fem

#include "fem/scenes/chamber_stretch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace softarm::fem {
namespace {
constexpr double kTwoThirdsPi = 2.0943951023931954923;  // 120°
}

double fibre_stretch(double stretch, const Eigen::Vector3d& k, const Eigen::Vector2d& d) {
  return stretch + k.x() * d.y() - k.y() * d.x();
}

std::array<double, 3> chamber_axis_stretch(const SplDesign& design, const SpatialCellRodSpec& rod,
                                           const SpatialCellRodState& state) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  std::array<double, 3> out{kNaN, kNaN, kNaN};
  if (!state.ok || state.stretch.size() != state.curvature_per_mm.size() ||
      state.piece_first_node.size() != rod.pieces.size())
    return out;
  for (std::size_t piece = 0, n = 0; piece < rod.pieces.size() && n < 3; ++piece) {
    const SpatialCellPiece& p = rod.pieces[piece];
    if (p.cells.empty()) continue;  // a connector
    const TcaDesign& segment = design.segments[n];
    const int first = state.piece_first_node[piece], last = state.piece_last_node[piece];
    const double dz = p.length_mm / std::max(1, last - first);
    double largest = 1;
    for (int i = first; i < last; ++i) {
      const double z = p.length_mm - (i - first + 0.5) * dz;  // the interval's height in the segment
      if (z < p.cap_mm || z > p.length_mm - p.cap_mm) continue;
      const double a = segment.axis_distance(z);
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector2d d(a * std::cos(k * kTwoThirdsPi), a * std::sin(k * kTwoThirdsPi));
        largest = std::max(largest, fibre_stretch(state.stretch[i], state.curvature_per_mm[i], d));
      }
    }
    out[n++] = largest;
  }
  return out;
}

}  // namespace softarm::fem

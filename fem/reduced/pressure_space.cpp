#include "fem/reduced/pressure_space.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include "fem/core/angles.hpp"

namespace softarm::fem {
namespace {

/// Chamber k's (0-based) angle from +x.
double chamber_angle(int k) { return 2 * kPi * k / 3; }

int grid_index(int i, int j) { return i * (i + 1) / 2 + j; }
}  // namespace

CanonicalPressures canonical_pressures(const std::array<double, 3>& p) {
  CanonicalPressures out;
  // The peak's chamber, then the larger of the other two (ties: the lower number).
  int k1 = 0;
  for (int k = 1; k < 3; ++k)
    if (p[k] > p[k1]) k1 = k;
  const int next = (k1 + 1) % 3, previous = (k1 + 2) % 3;
  const bool turn = p[next] >= p[previous] ? (p[next] > p[previous] || next < previous) : false;
  const int k2 = turn ? next : previous, k3 = turn ? previous : next;
  out.peak_kPa = p[k1];
  if (out.peak_kPa > 0) {
    out.a = p[k2] / out.peak_kPa;
    out.b = p[k3] / out.peak_kPa;
  }
  const double c = std::cos(chamber_angle(k1)), s = std::sin(chamber_angle(k1));
  if (turn) {
    // Chamber 2 onto the one after the peak's: the turn by the peak's angle.
    out.section_map << c, -s, s, c;
    out.axial_map = out.section_map;
  } else {
    // Chamber 2 onto the one before it: the mirror through the line at half the peak's angle,
    // θ → θ_peak − θ; axial vectors change sign under a mirror.
    out.section_map << c, s, s, -c;
    out.axial_map = -out.section_map;
  }
  return out;
}

std::vector<Eigen::Vector2d> direction_grid(int n) {
  if (n < 1) throw std::invalid_argument("direction_grid: the grid needs at least one division");
  std::vector<Eigen::Vector2d> out;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= i; ++j) out.emplace_back(double(i) / n, double(j) / n);
  return out;
}

std::vector<std::pair<int, double>> direction_weights(int n, double a, double b) {
  if (n < 1) throw std::invalid_argument("direction_weights: the grid needs at least one division");
  a = std::clamp(a, 0.0, 1.0);
  b = std::clamp(b, 0.0, a);
  const double u = a * n, v = b * n;
  const int i = std::min(static_cast<int>(std::floor(u)), n - 1), j = std::min(static_cast<int>(std::floor(v)), n - 1);
  const double fu = u - i, fv = v - j;
  // The square [i, i+1] × [j, j+1] split along its diagonal; below it (fu ≥ fv, always so where
  // j = i, the triangle's own edge) or above it.
  std::vector<std::pair<int, double>> w;
  if (fu >= fv)
    w = {{grid_index(i, j), 1 - fu}, {grid_index(i + 1, j), fu - fv}, {grid_index(i + 1, j + 1), fv}};
  else
    w = {{grid_index(i, j), 1 - fv}, {grid_index(i, j + 1), fv - fu}, {grid_index(i + 1, j + 1), fu}};
  std::erase_if(w, [](const auto& x) { return x.second <= 0; });
  return w;
}

}  // namespace softarm::fem

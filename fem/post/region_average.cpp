#include "fem/post/region_average.hpp"

#include <cmath>
#include <stdexcept>
#include <unordered_map>

namespace softarm::fem {
namespace {

struct Cell {
  double r = 0, z = 0, weight = 0;  // reference centroid (mm) and volume / 2π (mm³)
};

// Centroid and area of the element's corner polygon (the first four nodes, counter-clockwise
// in (r, z), for the bilinear and the biquadratic quadrilateral alike); its volume of
// revolution / 2π is area · r̄ (Pappus). Curved Q2 edges are straight here: an O(h²) error
// in a weight, which vanishes under refinement like the field's own error.
Cell corner_polygon(const Mesh& mesh, int e) {
  const int* n = mesh.element(e);
  double area2 = 0, cr = 0, cz = 0;
  for (int k = 0; k < 4; ++k) {
    const double r0 = mesh.X(n[k], 0), z0 = mesh.X(n[k], 1);
    const double r1 = mesh.X(n[(k + 1) % 4], 0), z1 = mesh.X(n[(k + 1) % 4], 1);
    const double cross = r0 * z1 - r1 * z0;
    area2 += cross;
    cr += (r0 + r1) * cross;
    cz += (z0 + z1) * cross;
  }
  Cell c;
  c.r = cr / (3 * area2);
  c.z = cz / (3 * area2);
  c.weight = std::abs(0.5 * area2) * c.r;
  return c;
}

long long bucket_key(long long i, long long j) { return (i << 32) ^ (j & 0xffffffffLL); }

}  // namespace

RegionPeak max_region_average(const Mesh& mesh, const std::vector<double>& field, int part, double radius_mm) {
  if (mesh.dim != 2) throw std::invalid_argument("max_region_average: axisymmetric meshes only");
  if (static_cast<int>(field.size()) != mesh.num_elements())
    throw std::invalid_argument("max_region_average: one field value per element expected");
  if (!(radius_mm > 0)) throw std::invalid_argument("max_region_average: the radius must be > 0");

  std::vector<int> members;
  std::vector<Cell> cells;
  for (int e = 0; e < mesh.num_elements(); ++e)
    if (mesh.part[e] == part) {
      members.push_back(e);
      cells.push_back(corner_polygon(mesh, e));
    }
  // Buckets of side ρ: a ball's members lie in the 3×3 buckets about its centre's.
  std::unordered_map<long long, std::vector<int>> buckets;
  auto index = [&](double v) { return static_cast<long long>(std::floor(v / radius_mm)); };
  for (std::size_t k = 0; k < cells.size(); ++k) buckets[bucket_key(index(cells[k].r), index(cells[k].z))].push_back(k);

  RegionPeak peak;
  const double rho2 = radius_mm * radius_mm;
  for (std::size_t k = 0; k < cells.size(); ++k) {
    const long long i = index(cells[k].r), j = index(cells[k].z);
    double sum = 0, weight = 0;
    int count = 0;
    for (long long di = -1; di <= 1; ++di)
      for (long long dj = -1; dj <= 1; ++dj) {
        const auto it = buckets.find(bucket_key(i + di, j + dj));
        if (it == buckets.end()) continue;
        for (int m : it->second) {
          const double dr = cells[m].r - cells[k].r, dz = cells[m].z - cells[k].z;
          if (dr * dr + dz * dz > rho2) continue;
          sum += cells[m].weight * field[members[m]];
          weight += cells[m].weight;
          ++count;
        }
      }
    const double average = sum / weight;  // the centre itself is always a member: weight > 0
    if (peak.centre_element < 0 || average > peak.value) peak = {average, members[k], count};
  }
  return peak;
}

}  // namespace softarm::fem

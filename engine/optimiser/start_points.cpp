// Seeded Latin-hypercube start points (see start_points.hpp).
#include "engine/optimiser/start_points.hpp"

#include <algorithm>
#include <numeric>
#include <random>

namespace softarm::optimise::detail {

std::vector<std::vector<double>> latin_hypercube(std::size_t count, std::size_t dimension, unsigned seed) {
  std::vector<std::vector<double>> points(count, std::vector<double>(dimension, 0.5));
  if (count == 0) return points;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(0.0, 1.0);
  std::vector<std::size_t> strata(count);
  for (std::size_t d = 0; d < dimension; ++d) {
    std::iota(strata.begin(), strata.end(), std::size_t{0});
    std::shuffle(strata.begin(), strata.end(), rng);
    for (std::size_t k = 0; k < count; ++k)
      points[k][d] = (static_cast<double>(strata[k]) + jitter(rng)) / static_cast<double>(count);
  }
  return points;
}

}  // namespace softarm::optimise::detail

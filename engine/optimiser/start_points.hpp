// Start points for the multi-start: a seeded Latin-hypercube sample of the
// normalised box (each of the `count` points in its own stratum of every
// coordinate, strata shuffled independently per coordinate, a uniform jitter
// inside each stratum). Cheap, deterministic for a seed, and spread in every
// one-dimensional projection, which is what a handful of expensive starts need.
#pragma once

#include <cstddef>
#include <vector>

namespace softarm::optimise::detail {

std::vector<std::vector<double>> latin_hypercube(std::size_t count, std::size_t dimension, unsigned seed);

}  // namespace softarm::optimise::detail

#pragma once
// FNV-1a, 64 bits: a cheap hash that catches torn or overwritten records and tells
// one config from another. Not cryptographic: there is no adversary to defend against.
#include <cstdint>
#include <string_view>

namespace softarm::fem {

inline std::uint64_t fnv1a_64(std::string_view bytes) {
  std::uint64_t h = 14695981039346656037ull;
  for (const unsigned char c : bytes) h = (h ^ c) * 1099511628211ull;
  return h;
}

}  // namespace softarm::fem

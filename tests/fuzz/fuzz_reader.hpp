#pragma once
// The contract every libFuzzer target here checks (issue 35): a reader given any bytes either
// returns a validated value or refuses them with fem::InputError (what the CLI turns into exit 2
// with the field named). Any other exception is a finding: the CLI would call it an internal
// error (exit 3). Crashes, hangs, leaks and undefined behaviour are findings of the sanitizers
// and of libFuzzer itself. Build and run: scripts/fuzz.sh.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <typeinfo>

#include "fem/core/input_error.hpp"

namespace softarm::fuzz {

/// Runs `read` on the input as text; aborts (a libFuzzer finding) on anything but success or an
/// InputError whose message is not empty.
template <class Read>
int check_reader(const std::uint8_t* data, std::size_t size, Read read) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    read(text);
  } catch (const fem::InputError& e) {
    if (std::string(e.what()).empty()) {
      std::fprintf(stderr, "fuzz: an InputError without a message\n");
      std::abort();
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz: %s escaped the reader (not an InputError): %s\n", typeid(e).name(), e.what());
    std::abort();
  }
  return 0;
}

}  // namespace softarm::fuzz

// libFuzzer target: a material (a built-in name or an object with law, coefficients, density) from
// any bytes, as a scene config's "materials" entries and `softarm material check` read it.
// Seed corpus: configs/materials/*.json (scripts/fuzz.sh).
#include "fem/core/json_reader.hpp"
#include "fem/materials/material.hpp"
#include "fuzz_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return softarm::fuzz::check_reader(data, size, [](const std::string& text) {
    softarm::fem::material_from_json(softarm::fem::parse_json_text(text, "fuzz.json"), "materials.tube");
  });
}

// libFuzzer target: a requirements config (`softarm design`'s input) from any bytes, with the
// consistency checks read_design_config makes before any work.
// Seed corpus: configs/*requirements*.json (scripts/fuzz.sh).
#include "engine/design/design_config.hpp"
#include "fem/core/json_reader.hpp"
#include "fuzz_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return softarm::fuzz::check_reader(data, size, [](const std::string& text) {
    softarm::engine::read_design_config(softarm::fem::parse_json_text(text, "fuzz.json"));
  });
}

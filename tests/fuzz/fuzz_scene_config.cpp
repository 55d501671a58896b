// libFuzzer target: a scene config (simulate's and export's input) from any bytes.
// Seed corpus: configs/*.json (scripts/fuzz.sh).
#include "fem/core/json_reader.hpp"
#include "fem/scenes/scene_config.hpp"
#include "fuzz_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return softarm::fuzz::check_reader(data, size, [](const std::string& text) {
    softarm::fem::read_scene_config(softarm::fem::parse_json_text(text, "fuzz.json"));
  });
}

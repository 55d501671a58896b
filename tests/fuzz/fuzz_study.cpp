// libFuzzer target: a study config (`softarm study`'s input: sweeps, rules, plots) from any bytes;
// a base scene it names is looked up under configs/. Seed corpus: configs/studies/*.json.
#include "fem/core/json_reader.hpp"
#include "fuzz_reader.hpp"
#include "studies/study_spec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return softarm::fuzz::check_reader(data, size, [](const std::string& text) {
    softarm::studies::read_study(softarm::fem::parse_json_text(text, "fuzz.json"),
                                 std::string(SOFTARM_SOURCE_DIR) + "/configs/studies");
  });
}

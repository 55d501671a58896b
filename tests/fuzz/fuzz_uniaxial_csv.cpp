// libFuzzer target: uniaxial test data (`softarm material fit`'s CSV) from any bytes.
// Seed corpus: the Treloar CSVs and any under configs/ (scripts/fuzz.sh).
#include "fem/materials/uniaxial_data.hpp"
#include "fuzz_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return softarm::fuzz::check_reader(
      data, size, [](const std::string& text) { softarm::fem::parse_uniaxial_csv(text, "fuzz.csv"); });
}

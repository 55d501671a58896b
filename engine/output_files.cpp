#include "engine/output_files.hpp"

#include <filesystem>

#include "fem/core/input_error.hpp"

namespace softarm::engine {

std::ofstream open_output_file(const std::string& directory, const std::string& file, std::ios::openmode mode) {
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  std::ofstream out(directory + "/" + file, mode | std::ios::out);
  if (error || !out)
    throw fem::InputError("output.directory",
                          "cannot write to '" + directory + "'" + (error ? ": " + error.message() : std::string()));
  return out;
}

void write_json_file(const std::string& directory, const std::string& file, const nlohmann::json& document) {
  open_output_file(directory, file) << document.dump(2) << "\n";
}

}  // namespace softarm::engine

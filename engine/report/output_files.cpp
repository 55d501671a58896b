#include "engine/report/output_files.hpp"

#include <filesystem>
#include <unistd.h>

#include "fem/core/input_error.hpp"

namespace softarm::engine {

void prepare_output_directory(const std::string& directory, const std::string& field) {
  namespace fs = std::filesystem;
  std::error_code error;
  const auto refuse = [&](const std::string& why) {
    throw fem::InputError(field, "cannot write to '" + directory + "': " + why +
                                     "; give a directory that can be created and written");
  };
  if (directory.empty()) refuse("empty path");
  fs::create_directories(directory, error);
  if (error) refuse(error.message());
  if (!fs::is_directory(directory, error)) refuse("not a directory");
  if (::access(directory.c_str(), W_OK | X_OK) != 0) refuse("no permission to create files in it");
}

std::string csv_text(const std::string& text) {
  std::string field = "\"";
  for (const char c : text) field += c == '"' ? std::string("\"\"") : std::string(1, c);
  return field + "\"";
}

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

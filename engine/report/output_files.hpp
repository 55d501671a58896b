#pragma once
// Result files of every scene: created in the output directory (made if
// absent); a directory that cannot be written is bad input naming
// output.directory, not an internal error.
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

namespace softarm::engine {

/// Creates `directory` (and its parents) if absent and checks that files can be made in it, before
/// any work; throws fem::InputError(field, …) naming the directory and why not (an existing file in
/// its place, no permission), so that a bad output path is exit 2 up front, not an error at the end.
void prepare_output_directory(const std::string& directory, const std::string& field);

/// Opens <directory>/<file> for writing (`mode`: anew by default); throws
/// fem::InputError("output.directory", …) if it cannot.
std::ofstream open_output_file(const std::string& directory, const std::string& file,
                               std::ios::openmode mode = std::ios::out);

/// `text` as one CSV field (RFC 4180): in double quotes, each quote doubled, so that commas, quotes
/// and line breaks in a phase name or a diagnosis stay inside their column for any CSV reader.
std::string csv_text(const std::string& text);

/// Writes `document` to <directory>/<file>, indented.
void write_json_file(const std::string& directory, const std::string& file, const nlohmann::json& document);

}  // namespace softarm::engine

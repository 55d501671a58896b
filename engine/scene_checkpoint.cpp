#include "engine/scene_checkpoint.hpp"

#include <cstdint>
#include <cstdio>
#include <filesystem>

#include "engine/report/output_files.hpp"
#include "fem/core/checksum.hpp"
#include "fem/core/input_error.hpp"

namespace softarm::engine {

fem::PathCheckpoint scene_checkpoint(nlohmann::json document, const std::string& overrides, const std::string& directory,
                                     bool fresh) {
  document.erase("output");
  document.erase("description");
  const std::string text = document.dump() + "\n" + overrides;
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(fem::fnv1a_64(text)));
  const std::string name = "path_checkpoint.bin";
  fem::PathCheckpoint checkpoint{directory + "/" + name, hex};
  std::error_code error;
  if (fresh) std::filesystem::remove(checkpoint.file, error);
  if (error)
    throw fem::InputError("output.directory", "cannot remove '" + checkpoint.file + "' for --fresh: " + error.message());
  // Writable, before the run (an empty file is a log not yet begun).
  open_output_file(directory, name, std::ios::app | std::ios::binary);
  return checkpoint;
}

std::string checkpoint_note(const fem::PathCheckpoint& checkpoint, const fem::PressurePathResult& path) {
  if (path.resumed_states > 0)
    return "resumed " + std::to_string(path.resumed_states) + " converged states of an earlier run from " +
           checkpoint.file + " (--fresh starts over)";
  if (!path.checkpoint_discarded.empty())
    return "started over: the earlier " + checkpoint.file + " was not resumed, since " + path.checkpoint_discarded;
  return "";
}

}  // namespace softarm::engine

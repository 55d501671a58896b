// Helpers the end-to-end tests share: a file's whole text, and `softarm` run as a user runs it.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace softarm::test {

/// The whole of `file` as bytes ("" when it cannot be read: the caller's CHECK then says what is missing).
inline std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// `<prefix>softarm <args> > log 2>&1`; the exit status, or 128 + the signal that killed it.
inline int run_softarm_logged(const std::string& prefix, const std::string& args, const std::filesystem::path& log) {
  const std::string cmd = prefix + std::string(SOFTARM_BINARY) + " " + args + " > " + log.string() + " 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace softarm::test

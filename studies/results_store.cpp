#include "studies/results_store.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace softarm::studies {
using nlohmann::json;

namespace {

void write_durably(const std::filesystem::path& file, const std::string& text) {
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  if (fd < 0) throw std::runtime_error("cannot open " + file.string() + " for appending");
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0) {
      ::close(fd);
      throw std::runtime_error("cannot write " + file.string());
    }
    done += static_cast<std::size_t>(n);
  }
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

std::string fingerprint_of(const nlohmann::json& what) {
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a, 64 bit
  for (unsigned char c : what.dump()) h = (h ^ c) * 1099511628211ull;
  char buffer[17];
  std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(h));
  return buffer;
}

ResultsStore::ResultsStore(std::filesystem::path file, const std::string& study, const std::string& fingerprint,
                           bool fresh)
    : file_(std::move(file)) {
  if (fresh) std::filesystem::remove(file_);
  if (std::filesystem::exists(file_)) {
    std::ifstream in(file_, std::ios::binary);
    std::stringstream buffer;
    buffer << in.rdbuf();
    const std::string text = buffer.str();
    std::size_t start = 0, good_end = 0;
    bool header_seen = false;
    while (start < text.size()) {
      const std::size_t end = text.find('\n', start);
      if (end == std::string::npos) {  // no newline: cut short by a kill
        ++dropped_;
        break;
      }
      const json record = json::parse(text.begin() + start, text.begin() + end, nullptr, false);
      if (record.is_discarded() || !record.is_object()) {
        ++dropped_;
        break;  // nothing after a torn line can be trusted to be complete
      }
      if (!header_seen) {
        if (record.value("fingerprint", "") != fingerprint)
          throw std::runtime_error(file_.string() + " holds results of another configuration of study '" +
                                   record.value("study", std::string("?")) + "' (fingerprint " +
                                   record.value("fingerprint", std::string("?")) + ", this config " + fingerprint +
                                   "): rerun with --fresh to discard them, or choose another output directory");
        header_seen = true;
      } else if (record.contains("key")) {
        records_[record["key"].get<std::string>()] = record;
      }
      good_end = end + 1;
      start = end + 1;
    }
    if (good_end < text.size()) std::filesystem::resize_file(file_, good_end);
    if (header_seen) return;
  }
  std::filesystem::create_directories(file_.parent_path().empty() ? "." : file_.parent_path());
  std::filesystem::remove(file_);
  write_durably(file_, json{{"study", study}, {"fingerprint", fingerprint}}.dump() + "\n");
}

void ResultsStore::append(const json& record) {
  write_durably(file_, record.dump() + "\n");
  records_[record.at("key").get<std::string>()] = record;
}

}  // namespace softarm::studies

#include "fem/scenes/path_log.hpp"

#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "fem/core/checksum.hpp"

namespace softarm::fem {
namespace {
const std::string kHeader = "softarm pressure-path log 1\n";
constexpr std::uint32_t kRecordMark = 0x48544150;  // "PATH"

std::uint64_t checksum(const std::string& bytes) { return fnv1a_64(bytes); }

template <class T>
void put(std::string& out, const T& value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

/// Reads the values of a record's payload in the order `put` wrote them.
class Reader {
 public:
  explicit Reader(const std::string& bytes) : bytes_(bytes) {}
  template <class T>
  T get() {
    T value;
    std::memcpy(&value, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }
  void get(double* values, std::size_t n) {
    std::memcpy(values, bytes_.data() + at_, n * sizeof(double));
    at_ += n * sizeof(double);
  }

 private:
  const std::string& bytes_;
  std::size_t at_ = 0;
};

std::string payload_of(const PathLogRecord& r) {
  std::string out;
  put(out, r.level);
  put(out, r.next_increment);
  put(out, r.state.pressure_kPa);
  put(out, r.state.chamber_volume_mm3);
  put(out, r.state.pv_stiffness_kPa_per_mm3);
  put(out, static_cast<std::int32_t>(r.state.tangent_positive_definite));
  put(out, static_cast<std::int32_t>(r.state.newton_iterations));
  put(out, static_cast<std::int32_t>(r.state.is_output));
  for (const int n : {r.stats.steps, r.stats.newton_iterations, r.stats.cutbacks, r.stats.second_starts,
                      r.stats.halved_steps})
    put(out, static_cast<std::int32_t>(n));
  out.append(reinterpret_cast<const char*>(r.x.data()), static_cast<std::size_t>(r.x.size()) * sizeof(double));
  return out;
}

PathLogRecord record_of(const std::string& payload, Eigen::Index dofs) {
  Reader in(payload);
  PathLogRecord r;
  r.level = in.get<double>();
  r.next_increment = in.get<double>();
  r.state.pressure_kPa = in.get<double>();
  r.state.chamber_volume_mm3 = in.get<double>();
  r.state.pv_stiffness_kPa_per_mm3 = in.get<double>();
  r.state.tangent_positive_definite = in.get<std::int32_t>() != 0;
  r.state.newton_iterations = in.get<std::int32_t>();
  r.state.is_output = in.get<std::int32_t>() != 0;
  for (int* n : {&r.stats.steps, &r.stats.newton_iterations, &r.stats.cutbacks, &r.stats.second_starts,
                 &r.stats.halved_steps})
    *n = in.get<std::int32_t>();
  r.x.resize(dofs);
  in.get(r.x.data(), static_cast<std::size_t>(dofs));
  return r;
}

std::size_t payload_size(Eigen::Index dofs) {
  return 5 * sizeof(double) + 8 * sizeof(std::int32_t) + static_cast<std::size_t>(dofs) * sizeof(double);
}

std::string header_of(const std::string& fingerprint, Eigen::Index dofs) {
  std::string out = kHeader;
  put(out, static_cast<std::uint64_t>(fingerprint.size()));
  out += fingerprint;
  put(out, static_cast<std::int64_t>(dofs));
  return out;
}
}  // namespace

PathLog::PathLog(std::string file, std::string fingerprint, Eigen::Index dofs)
    : file_(std::move(file)), fingerprint_(std::move(fingerprint)), dofs_(dofs) {
  const std::string header = header_of(fingerprint_, dofs_);
  std::uintmax_t valid_bytes = 0;  // of the file, up to its last whole record
  std::error_code size_error;
  const std::uintmax_t size = std::filesystem::file_size(file_, size_error);
  if (std::ifstream in{file_, std::ios::binary}; in && !size_error && size > 0) {
    std::string head(header.size(), '\0');
    if (size < header.size()) {
      discarded_reason_ = "its header is incomplete (a run stopped as it began)";
    } else if (!in.read(head.data(), static_cast<std::streamsize>(head.size())) || head != header) {
      discarded_reason_ = "it was written for another model (another config or mesh)";
    } else {
      valid_bytes = header.size();
      const std::size_t n = payload_size(dofs_);
      std::string payload(n, '\0');
      for (;;) {
        std::uint32_t mark = 0;
        std::uint64_t sum = 0;
        if (!in.read(reinterpret_cast<char*>(&mark), sizeof mark) || mark != kRecordMark) break;
        if (!in.read(payload.data(), static_cast<std::streamsize>(n))) break;
        if (!in.read(reinterpret_cast<char*>(&sum), sizeof sum) || sum != checksum(payload)) break;
        resumed_.push_back(record_of(payload, dofs_));
        valid_bytes += sizeof mark + n + sizeof sum;
      }
    }
  }
  std::error_code ec;
  if (valid_bytes > 0) {
    // Resume: drop a torn tail, then append after the last whole record.
    std::filesystem::resize_file(file_, valid_bytes, ec);
    out_.open(file_, std::ios::binary | std::ios::app);
  } else {
    if (const auto dir = std::filesystem::path(file_).parent_path(); !dir.empty())
      std::filesystem::create_directories(dir, ec);
    out_.open(file_, std::ios::binary | std::ios::trunc);
    out_.write(header.data(), static_cast<std::streamsize>(header.size()));
    out_.flush();
  }
  if (ec || !out_) throw std::runtime_error("cannot write the path log " + file_);
}

void PathLog::append(const PathLogRecord& record) {
  if (record.x.size() != dofs_) throw std::logic_error("PathLog::append: a state of another size");
  const std::string payload = payload_of(record);
  const std::uint64_t sum = checksum(payload);
  out_.write(reinterpret_cast<const char*>(&kRecordMark), sizeof kRecordMark);
  out_.write(payload.data(), static_cast<std::streamsize>(payload.size()));
  out_.write(reinterpret_cast<const char*>(&sum), sizeof sum);
  out_.flush();
  if (!out_) throw std::runtime_error("cannot write the path log " + file_);
}

}  // namespace softarm::fem

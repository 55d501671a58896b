// One CSV record's fields as RFC 4180 reads them (tests and tests/tools share it).
#pragma once

#include <string>
#include <vector>

namespace softarm::test {

/// The fields of one CSV record as RFC 4180 reads it: a field in double quotes may hold commas,
/// and "" inside it is one quote. The reader every spreadsheet uses, so a test with it fails where a
/// file would put a value under the wrong header.
inline std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') fields.back() += '"', ++i;
    else if (c == '"') quoted = !quoted;
    else if (c == ',' && !quoted) fields.emplace_back();
    else fields.back() += c;
  }
  return fields;
}

}  // namespace softarm::test

#pragma once
// Reads one JSON object against a declared spec: every field is declared with
// its type, unit (in the key), default and valid range, values are validated
// as they are read, and finish() rejects keys nobody declared (typos). The
// declarations double as documentation: describe() lists them for
// `softarm schema` (README.md, Configs and `softarm schema`).
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "fem/core/input_error.hpp"

namespace softarm::fem {

/// Valid interval for a number; open or closed at each end.
struct Range {
  double lo = -1e300, hi = 1e300;
  bool lo_open = false, hi_open = false;
  static Range closed(double lo, double hi) { return {lo, hi, false, false}; }
  static Range positive() { return {0.0, 1e300, true, false}; }
  static Range non_negative() { return {0.0, 1e300, false, false}; }
  static Range open(double lo, double hi) { return {lo, hi, true, true}; }
  static Range at_least(double lo) { return {lo, 1e300, false, false}; }
  bool contains(double x) const;
  std::string describe() const;
};

/// One declared field, kept for documentation.
struct FieldDoc {
  std::string path, type, default_value, range, doc;
};

class JsonReader {
 public:
  /// `path` is the dotted location of `object` in the file ("" at the root).
  JsonReader(const nlohmann::json& object, std::string path);

  double number(const std::string& key, Range range, const std::string& doc);
  double number(const std::string& key, double default_value, Range range, const std::string& doc);
  std::optional<double> optional_number(const std::string& key, Range range, const std::string& doc);
  int integer(const std::string& key, int default_value, Range range, const std::string& doc);
  std::optional<int> optional_integer(const std::string& key, Range range, const std::string& doc);
  bool boolean(const std::string& key, bool default_value, const std::string& doc);
  std::string string(const std::string& key, const std::string& doc);
  std::string string(const std::string& key, const std::string& default_value, const std::string& doc);
  /// A string restricted to `choices`.
  std::string choice(const std::string& key, const std::string& default_value,
                     const std::vector<std::string>& choices, const std::string& doc);
  std::vector<double> number_list(const std::string& key, Range range, const std::string& doc);
  /// A list that must be given; `expected` says what, in the message when it is missing.
  std::vector<double> required_number_list(const std::string& key, Range range, const std::string& doc,
                                           const std::string& expected);
  bool has(const std::string& key) const;
  /// Sub-object reader (the key must hold an object); an absent key reads as {}.
  JsonReader object(const std::string& key, const std::string& doc);
  const nlohmann::json& raw(const std::string& key) const;
  /// A value the caller checks itself (a list of numbers or names, an object of free keys),
  /// declared with its type, doc and what stands for it when absent (`absent`: "(optional)",
  /// "(required)", or the default the caller takes) so that `softarm schema` lists it; null when absent.
  const nlohmann::json& raw(const std::string& key, const std::string& type, const std::string& doc,
                            const std::string& absent = "(optional)");
  /// Exactly one of `keys` must be present (e.g. a physical or a normalised size).
  std::string exactly_one_of(const std::vector<std::string>& keys) const;

  /// Rejects every key that was not read: "unknown key 'lenght_mm' (known: ...)".
  void finish() const;

  std::string field(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  const std::string& path() const { return path_; }
  static const std::vector<FieldDoc>& documented_fields();

 private:
  const nlohmann::json& at(const std::string& key, const std::string& type) const;
  double read_number(const std::string& key, const Range& range) const;  // validates, declares nothing
  std::vector<double> read_number_list(const std::string& key, const Range& range) const;  // the same for a list
  void declare(const std::string& key, const std::string& type, const std::string& def, const std::string& range,
               const std::string& doc);

  const nlohmann::json& object_;
  std::string path_;
  mutable std::vector<std::string> read_;
};

/// Bounds on a JSON input (issue 35): no config softarm reads nests deeper than a few levels or
/// weighs more than a few kB; these leave room for any real one and refuse a document that would
/// exhaust the machine before it is parsed.
inline constexpr int kMaxJsonDepth = 64;
inline constexpr std::size_t kMaxJsonBytes = 16u << 20;  // 16 MiB

/// Parses a JSON file (// comments allowed). Refused with an InputError: a missing file or a
/// directory, a file over kMaxJsonBytes, nesting deeper than kMaxJsonDepth, a key given twice
/// in one object (JSON leaves it to the reader; taking the last silently would hide a typo), and
/// malformed JSON (with line and column).
nlohmann::json load_json_file(const std::string& file_name);

/// The same checks on a document held in memory; `source` names it in messages.
nlohmann::json parse_json_text(const std::string& text, const std::string& source);

/// Levenshtein distance: the fewest insertions, deletions and replacements that turn a into b
/// (what "did you mean" ranks a misspelt key or command by).
std::size_t edit_distance(const std::string& a, const std::string& b);

}  // namespace softarm::fem

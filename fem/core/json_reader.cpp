#include "fem/core/json_reader.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>
#include <stdexcept>

namespace softarm::fem {
namespace {

std::string format_number(double x) {
  std::ostringstream s;
  s.precision(10);
  s << x;
  return s.str();
}

std::string show(const nlohmann::json& value) {
  std::string s = value.dump();
  return s.size() > 60 ? s.substr(0, 57) + "..." : s;
}

std::vector<FieldDoc>& registry() {
  static std::vector<FieldDoc> docs;
  return docs;
}
std::mutex& registry_mutex() {
  static std::mutex m;
  return m;
}

}  // namespace

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

bool Range::contains(double x) const {
  if (!std::isfinite(x)) return false;
  const bool above = lo_open ? x > lo : x >= lo;
  const bool below = hi_open ? x < hi : x <= hi;
  return above && below;
}

std::string Range::describe() const {
  // An open end is still bounded by ±1e300 (a finite double with room to compute with): said, so
  // that 1e308 is not refused with a range it seems to satisfy.
  const bool no_lo = lo <= -1e299, no_hi = hi >= 1e299;
  if (no_lo && no_hi) return "any number of magnitude <= 1e300";
  if (no_hi) return (lo_open ? "> " : ">= ") + format_number(lo) + " and <= 1e300";
  if (no_lo) return (hi_open ? "< " : "<= ") + format_number(hi) + " and >= -1e300";
  return std::string(lo_open ? "(" : "[") + format_number(lo) + ", " + format_number(hi) + (hi_open ? ")" : "]");
}

JsonReader::JsonReader(const nlohmann::json& object, std::string path) : object_(object), path_(std::move(path)) {
  if (!object_.is_object() && !object_.is_null())
    throw InputError(path_, "expected a JSON object, got " + show(object_));
}

void JsonReader::declare(const std::string& key, const std::string& type, const std::string& def,
                         const std::string& range, const std::string& doc) {
  read_.push_back(key);
  std::lock_guard lock(registry_mutex());
  auto& docs = registry();
  const std::string p = field(key);
  if (std::none_of(docs.begin(), docs.end(), [&](const FieldDoc& d) { return d.path == p; }))
    docs.push_back({p, type, def, range, doc});
}

const std::vector<FieldDoc>& JsonReader::documented_fields() { return registry(); }

bool JsonReader::has(const std::string& key) const { return object_.is_object() && object_.contains(key); }

const nlohmann::json& JsonReader::raw(const std::string& key) const {
  read_.push_back(key);
  return object_.at(key);
}

const nlohmann::json& JsonReader::raw(const std::string& key, const std::string& type, const std::string& doc,
                                      const std::string& absent) {
  static const nlohmann::json null;
  declare(key, type, absent, "", doc);
  return has(key) ? object_.at(key) : null;
}

const nlohmann::json& JsonReader::at(const std::string& key, const std::string& type) const {
  if (!has(key)) throw InputError(field(key), "required " + type + " is missing");
  return object_.at(key);
}

double JsonReader::number(const std::string& key, Range range, const std::string& doc) {
  declare(key, "number", "(required)", range.describe(), doc);
  return read_number(key, range);
}

double JsonReader::read_number(const std::string& key, const Range& range) const {
  const auto& v = at(key, "number");
  if (!v.is_number()) throw InputError(field(key), "expected a number, got " + show(v));
  const double x = v.get<double>();
  if (!range.contains(x)) throw InputError(field(key), "value " + format_number(x) + " is out of range; valid: " + range.describe());
  return x;
}

double JsonReader::number(const std::string& key, double default_value, Range range, const std::string& doc) {
  declare(key, "number", format_number(default_value), range.describe(), doc);
  return has(key) ? read_number(key, range) : default_value;
}

std::optional<double> JsonReader::optional_number(const std::string& key, Range range, const std::string& doc) {
  declare(key, "number", "(optional)", range.describe(), doc);
  if (!has(key)) return std::nullopt;
  return read_number(key, range);
}

int JsonReader::integer(const std::string& key, int default_value, Range range, const std::string& doc) {
  declare(key, "integer", std::to_string(default_value), range.describe(), doc);  // the documented default wins
  return optional_integer(key, range, doc).value_or(default_value);
}

std::optional<int> JsonReader::optional_integer(const std::string& key, Range range, const std::string& doc) {
  declare(key, "integer", "(optional)", range.describe(), doc);
  if (!has(key)) return std::nullopt;
  const auto& v = object_.at(key);
  if (!v.is_number_integer() && !(v.is_number() && std::floor(v.get<double>()) == v.get<double>()))
    throw InputError(field(key), "expected an integer, got " + show(v));
  const double x = v.get<double>();
  if (!range.contains(x)) throw InputError(field(key), "value " + format_number(x) + " is out of range; valid: " + range.describe());
  return static_cast<int>(x);
}

bool JsonReader::boolean(const std::string& key, bool default_value, const std::string& doc) {
  declare(key, "boolean", default_value ? "true" : "false", "true or false", doc);
  if (!has(key)) return default_value;
  const auto& v = object_.at(key);
  if (!v.is_boolean()) throw InputError(field(key), "expected true or false, got " + show(v));
  return v.get<bool>();
}

std::string JsonReader::string(const std::string& key, const std::string& doc) {
  declare(key, "string", "(required)", "", doc);
  const auto& v = at(key, "string");
  if (!v.is_string()) throw InputError(field(key), "expected a string, got " + show(v));
  return v.get<std::string>();
}

std::string JsonReader::string(const std::string& key, const std::string& default_value, const std::string& doc) {
  if (!has(key)) {
    declare(key, "string", "\"" + default_value + "\"", "", doc);
    return default_value;
  }
  return string(key, doc);
}

std::string JsonReader::choice(const std::string& key, const std::string& default_value,
                               const std::vector<std::string>& choices, const std::string& doc) {
  std::string valid;
  for (const auto& c : choices) valid += (valid.empty() ? "\"" : ", \"") + c + "\"";
  declare(key, "string", "\"" + default_value + "\"", "one of " + valid, doc);
  if (!has(key)) return default_value;
  const auto& v = object_.at(key);
  if (!v.is_string()) throw InputError(field(key), "expected one of " + valid + ", got " + show(v));
  const auto s = v.get<std::string>();
  if (std::find(choices.begin(), choices.end(), s) == choices.end())
    throw InputError(field(key), "\"" + s + "\" is not valid; valid: " + valid);
  return s;
}

std::vector<double> JsonReader::number_list(const std::string& key, Range range, const std::string& doc) {
  declare(key, "list of numbers", "(optional)", range.describe(), doc);
  return has(key) ? read_number_list(key, range) : std::vector<double>{};
}

std::vector<double> JsonReader::required_number_list(const std::string& key, Range range, const std::string& doc,
                                                     const std::string& expected) {
  declare(key, "list of numbers", "(required)", range.describe(), doc);
  if (!has(key)) throw InputError(field(key), "required list is missing; give " + expected);
  return read_number_list(key, range);
}

std::vector<double> JsonReader::read_number_list(const std::string& key, const Range& range) const {
  std::vector<double> out;
  const auto& v = object_.at(key);
  if (!v.is_array()) throw InputError(field(key), "expected a list of numbers, got " + show(v));
  for (std::size_t i = 0; i < v.size(); ++i) {
    const std::string f = field(key) + "[" + std::to_string(i) + "]";
    if (!v[i].is_number()) throw InputError(f, "expected a number, got " + show(v[i]));
    const double x = v[i].get<double>();
    if (!range.contains(x)) throw InputError(f, "value " + format_number(x) + " is out of range; valid: " + range.describe());
    out.push_back(x);
  }
  return out;
}

JsonReader JsonReader::object(const std::string& key, const std::string& doc) {
  declare(key, "object", "{}", "", doc);
  static const nlohmann::json empty = nlohmann::json::object();
  if (!has(key)) {
    // A section given under a misspelt name ("geomtry") would otherwise read as an empty one and be
    // reported as a missing key deep inside it: name the typo first.
    if (object_.is_object())
      for (const auto& item : object_.items())
        if (item.value().is_object() && edit_distance(item.key(), key) <= std::max<std::size_t>(1, key.size() / 4))
          throw InputError(field(item.key()), "unknown key; did you mean '" + key + "'?");
    return JsonReader(empty, field(key));
  }
  const auto& v = object_.at(key);
  if (!v.is_object()) throw InputError(field(key), "expected an object, got " + show(v));
  return JsonReader(v, field(key));
}

std::string JsonReader::exactly_one_of(const std::vector<std::string>& keys) const {
  std::vector<std::string> present;
  std::string all;
  for (const auto& k : keys) {
    if (has(k)) present.push_back(k);
    all += (all.empty() ? "'" : " or '") + field(k) + "'";
  }
  if (present.size() != 1)
    throw InputError(present.empty() ? field(keys.front()) : field(present[1]),
                     "give exactly one of " + all + (present.empty() ? " (none given)" : " (several given)"));
  return present.front();
}

void JsonReader::finish() const {
  if (!object_.is_object()) return;
  for (const auto& item : object_.items()) {
    if (std::find(read_.begin(), read_.end(), item.key()) != read_.end()) continue;
    std::string known;
    for (const auto& k : read_)
      if (known.find("'" + k + "'") == std::string::npos) known += (known.empty() ? "'" : ", '") + k + "'";
    throw InputError(field(item.key()), "unknown key" + (known.empty() ? std::string() : " (known here: " + known + ")"));
  }
}

nlohmann::json parse_json_text(const std::string& text, const std::string& source) {
  // The parser's callback sees every key with its depth: a stack of the keys of the open objects
  // names where a duplicate sits, and the depth stops a runaway nesting before it is built.
  std::vector<std::vector<std::string>> keys;  // per open object (arrays hold an empty placeholder)
  std::vector<std::string> path;
  std::string failure, failure_field;
  const auto where = [&] {
    std::string p;
    for (const auto& k : path) p += (p.empty() ? "" : ".") + k;
    return p;
  };
  nlohmann::json::parser_callback_t check = [&](int depth, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using E = nlohmann::json::parse_event_t;
    if (depth > kMaxJsonDepth) {
      failure_field = where();
      failure = "nested deeper than " + std::to_string(kMaxJsonDepth) + " levels";
      throw std::length_error(failure);
    }
    if (event == E::object_start || event == E::array_start) {
      keys.emplace_back();
      path.emplace_back(event == E::array_start ? "[]" : "");
    } else if (event == E::object_end || event == E::array_end) {
      if (!keys.empty()) keys.pop_back();
      if (!path.empty()) path.pop_back();
    } else if (event == E::key && !keys.empty()) {
      const std::string key = parsed.get<std::string>();
      auto& seen = keys.back();
      if (std::find(seen.begin(), seen.end(), key) != seen.end()) {
        path.back() = key;
        failure_field = where();
        failure = "the key '" + key + "' is given twice in one object; give it once";
        throw std::length_error(failure);
      }
      seen.push_back(key);
      path.back() = key;
    }
    return true;
  };
  try {
    return nlohmann::json::parse(text, check, true, /*ignore_comments=*/true);
  } catch (const std::length_error&) {
    throw InputError(failure_field, "in '" + source + "': " + failure);
  } catch (const nlohmann::json::out_of_range& e) {
    // A number beyond a double's range (1e400) is refused by the parser itself.
    throw InputError(where(), "in '" + source + "': a number beyond the range of a double (" + e.what() +
                                  "); valid: magnitude <= 1e300");
  } catch (const nlohmann::json::parse_error& e) {
    // Translate the byte offset into line:column for the user.
    std::size_t line = 1, col = 1;
    for (std::size_t i = 0; i < std::min<std::size_t>(e.byte > 0 ? e.byte - 1 : 0, text.size()); ++i) {
      if (text[i] == '\n') { ++line; col = 1; } else { ++col; }
    }
    throw InputError("", "malformed JSON in '" + source + "' at line " + std::to_string(line) + ", column " +
                             std::to_string(col) + ": " + e.what());
  }
}

nlohmann::json load_json_file(const std::string& file_name) {
  std::error_code ec;
  if (std::filesystem::is_directory(file_name, ec))
    throw InputError("", "'" + file_name + "' is a directory; give a JSON file");
  std::ifstream in(file_name, std::ios::binary);
  if (!in) throw InputError("", "cannot open file '" + file_name + "'");
  const auto size = std::filesystem::file_size(file_name, ec);
  if (!ec && size > kMaxJsonBytes)
    throw InputError("", "'" + file_name + "' is " + std::to_string(size) + " bytes; a JSON input may have at most " +
                             std::to_string(kMaxJsonBytes) + " bytes");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parse_json_text(buffer.str(), file_name);
}

}  // namespace softarm::fem

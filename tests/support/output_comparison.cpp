#include "output_comparison.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <fstream>
#include <set>
#include <sstream>

#include "csv_fields.hpp"

namespace softarm::test {
namespace fs = std::filesystem;
using nlohmann::json;

bool is_time_name(const std::string& name) {
  // "seconds" as one of the name's words (`seconds`, `factorize_seconds`, `cell_seconds_summed`), or
  // the unit suffix `_s`.
  std::istringstream words(name);
  for (std::string word; std::getline(words, word, '_');)
    if (word == "seconds") return true;
  return name.ends_with("_s");
}

namespace {

std::string number_text(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

/// One file's comparison: collects differences into the shared result.
class FileComparison {
 public:
  FileComparison(std::string file, const ComparisonTolerance& tolerance, OutputComparison& out)
      : file_(std::move(file)), tolerance_(tolerance), out_(out) {}

  void numbers(double a, double b, const std::string& where) {
    ++out_.numbers_compared;
    if (std::isnan(a) && std::isnan(b)) return;
    const double scale = std::max(std::abs(a), std::abs(b));
    const double gap = std::abs(a - b);
    if (std::isfinite(gap) && scale > 0) out_.largest_relative_difference = std::max(out_.largest_relative_difference, gap / scale);
    if (!(gap <= tolerance_.absolute + tolerance_.relative * scale) && a != b) differ(where, number_text(a), number_text(b));
  }

  void differ(const std::string& where, const std::string& a, const std::string& b) {
    out_.differences.push_back({file_, where, a, b});
  }

  /// Text with numbers in it: the same words, and numbers equal within tolerance; a number followed
  /// by " s" or "s" (a duration) is not compared; digits inside a word ("dragon_skin_10") are text.
  void text(const std::string& a, const std::string& b, const std::string& where) {
    const auto ta = tokens(a), tb = tokens(b);
    if (ta.size() != tb.size()) return differ(where, a.substr(0, 200), b.substr(0, 200));
    for (std::size_t i = 0; i < ta.size(); ++i) {
      if (ta[i].duration && tb[i].duration) continue;
      if (ta[i].is_number && tb[i].is_number) numbers(ta[i].value, tb[i].value, where + (ta.size() > 1 ? " (token " + std::to_string(i) + ")" : ""));
      else if (ta[i].is_number != tb[i].is_number || ta[i].text != tb[i].text)
        return differ(where, a.substr(0, 200), b.substr(0, 200));
    }
  }

  void json_values(const json& a, const json& b, const std::string& pointer) {
    if (a.is_number() && b.is_number()) return numbers(a.get<double>(), b.get<double>(), pointer);
    if (a.type() != b.type()) return differ(pointer, a.dump().substr(0, 200), b.dump().substr(0, 200));
    if (a.is_string()) return text(a.get<std::string>(), b.get<std::string>(), pointer);
    if (a.is_array()) {
      if (a.size() != b.size())
        return differ(pointer, std::to_string(a.size()) + " entries", std::to_string(b.size()) + " entries");
      for (std::size_t i = 0; i < a.size(); ++i) json_values(a[i], b[i], pointer + "/" + std::to_string(i));
      return;
    }
    if (a.is_object()) {
      std::set<std::string> keys;
      for (const auto& [k, v] : a.items()) keys.insert(k);
      for (const auto& [k, v] : b.items()) keys.insert(k);
      for (const std::string& k : keys) {
        if (is_time_name(k)) continue;
        if (!a.contains(k) || !b.contains(k)) differ(pointer + "/" + k, a.contains(k) ? "present" : "absent", b.contains(k) ? "present" : "absent");
        else json_values(a[k], b[k], pointer + "/" + k);
      }
      return;
    }
    if (a != b) differ(pointer, a.dump(), b.dump());
  }

  void csv(const std::vector<std::string>& a, const std::vector<std::string>& b) {
    if (a.size() != b.size()) return differ("records", std::to_string(a.size()), std::to_string(b.size()));
    const std::vector<std::string> header = a.empty() ? std::vector<std::string>() : csv_fields(a[0]);
    for (std::size_t r = 0; r < a.size(); ++r) {
      const auto fa = csv_fields(a[r]), fb = csv_fields(b[r]);
      if (fa.size() != fb.size()) {
        differ("record " + std::to_string(r), a[r].substr(0, 200), b[r].substr(0, 200));
        continue;
      }
      for (std::size_t c = 0; c < fa.size(); ++c) {
        const std::string column = c < header.size() ? header[c] : std::to_string(c);
        if (r > 0 && is_time_name(column)) continue;
        text(fa[c], fb[c], "record " + std::to_string(r) + ", column " + column);
      }
    }
  }

 private:
  struct Token {
    bool is_number = false, duration = false;
    double value = 0;
    std::string text;
  };

  static std::vector<Token> tokens(const std::string& s) {
    std::vector<Token> out;
    std::size_t i = 0;
    while (i < s.size()) {
      const bool in_word = i > 0 && (std::isalnum(static_cast<unsigned char>(s[i - 1])) || s[i - 1] == '_');  // "dragon_skin_10", "Float64"
      const bool signed_or_dotted = (s[i] == '-' || s[i] == '+' || s[i] == '.') && i + 1 < s.size() &&
                                    (std::isdigit(static_cast<unsigned char>(s[i + 1])) || s[i + 1] == '.');
      const bool starts_number = !in_word && (std::isdigit(static_cast<unsigned char>(s[i])) || signed_or_dotted);
      if (starts_number) {
        char* end = nullptr;
        const double v = std::strtod(s.c_str() + i, &end);
        const std::size_t stop = static_cast<std::size_t>(end - s.c_str());
        if (stop > i) {
          std::size_t j = stop;
          if (j < s.size() && s[j] == ' ') ++j;
          const bool seconds = j < s.size() && s[j] == 's' && (j + 1 == s.size() || !std::isalnum(static_cast<unsigned char>(s[j + 1])));
          out.push_back({true, seconds, v, ""});
          i = stop;
          continue;
        }
      }
      if (out.empty() || out.back().is_number) out.push_back({});
      out.back().text += s[i++];
    }
    return out;
  }

  std::string file_;
  ComparisonTolerance tolerance_;
  OutputComparison& out_;
};

std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> lines_of(const fs::path& file) {
  std::vector<std::string> lines;
  std::istringstream in(read_text(file));
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

void compare_files(const fs::path& a, const fs::path& b, FileComparison& c) {
  const std::string ext = a.extension().string();
  if (ext == ".json") {
    const json ja = json::parse(read_text(a), nullptr, false), jb = json::parse(read_text(b), nullptr, false);
    if (ja.is_discarded() || jb.is_discarded()) return c.differ("", ja.is_discarded() ? "not JSON" : "JSON", jb.is_discarded() ? "not JSON" : "JSON");
    return c.json_values(ja, jb, "");
  }
  const auto la = lines_of(a), lb = lines_of(b);
  if (ext == ".jsonl") {
    if (la.size() != lb.size()) return c.differ("lines", std::to_string(la.size()), std::to_string(lb.size()));
    for (std::size_t i = 0; i < la.size(); ++i)
      c.json_values(json::parse(la[i], nullptr, false), json::parse(lb[i], nullptr, false), "line " + std::to_string(i + 1));
    return;
  }
  if (ext == ".csv") return c.csv(la, lb);
  if (la.size() != lb.size()) return c.differ("lines", std::to_string(la.size()), std::to_string(lb.size()));
  for (std::size_t i = 0; i < la.size(); ++i) c.text(la[i], lb[i], "line " + std::to_string(i + 1));
}

std::set<std::string> files_under(const fs::path& root) {
  std::set<std::string> files;
  if (!fs::is_directory(root)) return files;
  for (const auto& e : fs::recursive_directory_iterator(root))
    if (e.is_regular_file()) files.insert(fs::relative(e.path(), root).generic_string());
  return files;
}

}  // namespace

OutputComparison compare_output_directories(const fs::path& first, const fs::path& second,
                                            const ComparisonTolerance& tolerance) {
  OutputComparison out;
  const auto a = files_under(first), b = files_under(second);
  std::set<std::string> all = a;
  all.insert(b.begin(), b.end());
  for (const std::string& name : all) {
    FileComparison c(name, tolerance, out);
    if (!a.count(name) || !b.count(name)) {
      c.differ("file", a.count(name) ? "present" : "absent", b.count(name) ? "present" : "absent");
      continue;
    }
    ++out.files_compared;
    compare_files(first / name, second / name, c);
  }
  return out;
}

}  // namespace softarm::test

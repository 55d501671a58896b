#include "fem/materials/uniaxial_data.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "fem/core/input_error.hpp"

namespace softarm::fem {
namespace {

constexpr const char* expected_header = "stretch,nominal_stress_MPa";
constexpr std::size_t minimum_rows = 3;

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  std::string field;
  while (std::getline(in, field, ',')) fields.push_back(trim(field));
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

std::string shortest(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

constexpr double kMaxNominalStress_MPa = 1e6;

class CsvErrors {
 public:
  explicit CsvErrors(std::string file) : file_(std::move(file)) {}
  [[noreturn]] void raise(int line, const std::string& message) const {
    throw InputError(file_, "line " + std::to_string(line) + ": " + message);
  }
  /// The whole field as a finite number, else an error naming the column and the text.
  double number(int line, const std::string& column, const std::string& text) const {
    errno = 0;
    char* end = nullptr;
    const double x = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(x))
      raise(line, column + " \"" + text + "\" is not a finite number");
    return x;
  }

 private:
  std::string file_;
};

}  // namespace

UniaxialData parse_uniaxial_csv(const std::string& text, const std::string& file_name) {
  const CsvErrors errors(file_name);
  UniaxialData data;
  data.source = file_name;
  std::stringstream in(text);
  std::string raw;
  bool header_seen = false;
  int previous_line = 0;
  for (int line = 1; std::getline(in, raw); ++line) {
    const std::string row = trim(raw);
    if (row.empty() || row.front() == '#') continue;
    const auto fields = split_fields(row);
    if (!header_seen) {
      if (fields.size() != 2 || fields[0] != "stretch" || fields[1] != "nominal_stress_MPa")
        errors.raise(line, "header \"" + row + "\"; valid: \"" + expected_header +
                               "\" (stretch, nominal stress in MPa)");
      header_seen = true;
      continue;
    }
    if (fields.size() != 2)
      errors.raise(line, "\"" + row + "\" has " + std::to_string(fields.size()) +
                             " fields; valid: 2 (stretch, nominal stress in MPa)");
    const double stretch = errors.number(line, "stretch", fields[0]);
    const double stress = errors.number(line, "nominal_stress_MPa", fields[1]);
    if (stretch <= 0.0) errors.raise(line, "stretch " + fields[0] + " is out of range; valid: > 0");
    // 10⁶ MPa is a thousand times any elastomer's (or ABS's) strength: beyond it the data are in the
    // wrong unit or corrupt, and the fits' sums of squares overflow (1e308 printed inf and -nan).
    if (std::abs(stress) > kMaxNominalStress_MPa)
      errors.raise(line, "nominal_stress_MPa " + fields[1] + " is out of range; valid: magnitude <= " +
                             shortest(kMaxNominalStress_MPa) + " MPa (is the column in MPa?)");
    if (!data.stretch.empty() && stretch <= data.stretch.back())
      errors.raise(line, "stretch " + fields[0] + " does not increase (line " + std::to_string(previous_line) +
                             " has " + shortest(data.stretch.back()) + "); valid: strictly increasing stretches");
    data.stretch.push_back(stretch);
    data.nominal_stress_MPa.push_back(stress);
    previous_line = line;
  }
  if (!header_seen) throw InputError(file_name, std::string("is empty; valid: a header \"") + expected_header + "\" and rows");
  if (data.stretch.size() < minimum_rows)
    throw InputError(file_name, "has " + std::to_string(data.stretch.size()) + " data rows; valid: at least " +
                                    std::to_string(minimum_rows));
  // A fit needs data that load the material: with every stress zero each law's best fit is zero
  // stiffness, which no law takes, and the user would learn only that no fit is Drucker stable.
  if (std::all_of(data.nominal_stress_MPa.begin(), data.nominal_stress_MPa.end(), [](double p) { return p == 0.0; }))
    throw InputError(file_name, "every nominal_stress_MPa is 0: the data carry no stiffness to fit; valid: the "
                                "stresses a uniaxial test measured, in MPa");
  return data;
}

UniaxialData read_uniaxial_csv(const std::string& file_name) {
  std::ifstream file(file_name);
  if (!file) throw InputError(file_name, "cannot be opened for reading");
  std::stringstream text;
  text << file.rdbuf();
  return parse_uniaxial_csv(text.str(), file_name);
}

}  // namespace softarm::fem

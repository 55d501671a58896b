#include "fem/materials/coefficient_check.hpp"

#include <sstream>

#include "fem/core/input_error.hpp"

namespace softarm::fem {

std::string coefficient_field(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

std::string indexed_field(const std::string& field, std::size_t i) {
  std::ostringstream s;
  s << field << '[' << i << ']';
  return s.str();
}

void require_coefficient(bool ok, const std::string& field, double value, const std::string& valid) {
  if (ok) return;
  std::ostringstream msg;
  msg.precision(10);
  msg << "value " << value << " is out of range; valid: " << valid;
  throw InputError(field, msg.str());
}

}  // namespace softarm::fem

#pragma once
// A number for messages and diagnoses: `precision` significant digits, as
// std::ostream prints it ("30.651", "8.78e+04").
#include <sstream>
#include <string>

namespace softarm::fem {

inline std::string number_text(double value, int precision = 4) {
  std::ostringstream s;
  s.precision(precision);
  s << value;
  return s.str();
}

}  // namespace softarm::fem

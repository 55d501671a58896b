#include "engine/options/option_checks.hpp"

#include <cmath>

#include "fem/core/number_text.hpp"

namespace softarm::engine {

CLI::Validator finite_in(double lo, double hi, const std::string& unit) {
  return CLI::Validator(
      [lo, hi, unit](std::string& text) -> std::string {
        double v = 0;
        try {
          std::size_t used = 0;
          v = std::stod(text, &used);
          if (used != text.size()) return "'" + text + "' is not a number";
        } catch (const std::exception&) {
          return "'" + text + "' is not a number";
        }
        if (!std::isfinite(v) || v < lo || v > hi)
          return "value " + text + " out of range; valid: a finite number in [" + fem::number_text(lo) + ", " +
                 fem::number_text(hi) + "] " + unit;
        return "";
      },
      "FINITE[" + fem::number_text(lo) + ", " + fem::number_text(hi) + "]");
}

}  // namespace softarm::engine

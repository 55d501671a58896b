// Algorithm names and traits (see algorithms.hpp).
#include "engine/optimiser/algorithms.hpp"

#include <stdexcept>

#include "engine/optimiser/optimiser.hpp"

namespace softarm::optimise {

const std::vector<std::string>& algorithm_names() {
  static const std::vector<std::string> names{"nlopt:cobyla", "nlopt:auglag_bobyqa", "nlopt:isres",
                                              "nlopt:slsqp",  "nlopt:ccsaq",           "ipopt"};
  return names;
}

namespace detail {

Algorithm parse_algorithm(const std::string& name) {
  const auto& names = algorithm_names();
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return static_cast<Algorithm>(i);
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  throw std::invalid_argument("optimiser: unknown algorithm '" + name + "'; valid: " + list);
}

bool uses_gradients(Algorithm a) {
  return a == Algorithm::slsqp || a == Algorithm::ccsaq || a == Algorithm::ipopt;
}

bool is_global(Algorithm a) { return a == Algorithm::isres; }

}  // namespace detail
}  // namespace softarm::optimise

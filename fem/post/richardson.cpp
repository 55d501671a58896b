#include "fem/post/richardson.hpp"

#include <cmath>
#include <stdexcept>

namespace softarm::fem {
namespace {
constexpr double kMinOrder = 0.1, kMaxOrder = 10;

// (h1^q − h2^q)/(h2^q − h3^q): the ratio of successive differences that order q gives.
double difference_ratio(double h1, double h2, double h3, double q) {
  return (std::pow(h1, q) - std::pow(h2, q)) / (std::pow(h2, q) - std::pow(h3, q));
}
}  // namespace

std::optional<RichardsonEstimate> richardson_extrapolate(double h1, double f1, double h2, double f2, double h3,
                                                         double f3) {
  if (!(h1 > h2 && h2 > h3 && h3 > 0)) throw std::invalid_argument("richardson_extrapolate: needs h1 > h2 > h3 > 0");
  const double d12 = f1 - f2, d23 = f2 - f3;
  if (d12 == 0 || d23 == 0 || (d12 > 0) != (d23 > 0)) return std::nullopt;  // not monotone (or already flat)
  const double measured = d12 / d23;
  double lo = kMinOrder, hi = kMaxOrder;
  if (measured < difference_ratio(h1, h2, h3, lo) || measured > difference_ratio(h1, h2, h3, hi)) return std::nullopt;
  for (int i = 0; i < 200 && hi - lo > 1e-13; ++i) {
    const double mid = 0.5 * (lo + hi);
    (difference_ratio(h1, h2, h3, mid) < measured ? lo : hi) = mid;
  }
  const double q = 0.5 * (lo + hi);
  const double limit = richardson_with_order(h2, f2, h3, f3, q);
  return RichardsonEstimate{limit, q, std::abs(limit - f3)};
}

double richardson_with_order(double h1, double f1, double h2, double f2, double order) {
  if (!(h1 > h2 && h2 > 0 && order > 0)) throw std::invalid_argument("richardson_with_order: needs h1 > h2 > 0, q > 0");
  const double r = std::pow(h1 / h2, order);
  return f2 + (f2 - f1) / (r - 1);
}

}  // namespace softarm::fem

// Richardson extrapolation (fem/post/richardson.hpp): on series built from
// f(h) = f∞ + C·h^q it recovers f∞ and q, with constant and with the 1 : 1/2 : 1/3
// ratios of mesh.axial_level; it refuses series that do not converge monotonically.
#include <catch2/catch.hpp>
#include <cmath>
#include <stdexcept>

#include "fem/post/richardson.hpp"

using namespace softarm::fem;

namespace {
double series(double limit, double C, double q, double h) { return limit + C * std::pow(h, q); }
}  // namespace

TEST_CASE("Richardson recovers the limit and the order of an exact power series", "[richardson]") {
  struct Case {
    double limit, C, q, h1, h2, h3;
  };
  // The 3CA's axial series (ratios 1 : 1/2 : 1/3), a classic halving series, a first-order one
  // approached from below (C < 0) and a fast fourth-order one.
  for (const Case c : {Case{271.6, 36.5, 1.2, 1.0, 0.5, 1.0 / 3}, Case{10.2, -1.0, 0.9, 1.0, 0.5, 0.25},
                       Case{-3.0, -0.2, 1.0, 4.0, 3.0, 2.0}, Case{1.0, 5.0, 4.0, 0.5, 0.25, 0.125}}) {
    const auto r = richardson_extrapolate(c.h1, series(c.limit, c.C, c.q, c.h1), c.h2, series(c.limit, c.C, c.q, c.h2),
                                          c.h3, series(c.limit, c.C, c.q, c.h3));
    REQUIRE(r.has_value());
    CHECK(r->order == Approx(c.q).epsilon(1e-9));
    CHECK(r->limit == Approx(c.limit).epsilon(1e-9));
    CHECK(r->finest_error == Approx(std::abs(c.C) * std::pow(c.h3, c.q)).epsilon(1e-7));
  }
}

TEST_CASE("Richardson with a known order is the classic two-mesh formula", "[richardson]") {
  // Second order, halving: f∞ = f2 + (f2 − f1)/3.
  CHECK(richardson_with_order(1.0, 1.4, 0.5, 1.1, 2.0) == Approx(1.0));
  // Exact for any power series of that order and any ratio.
  CHECK(richardson_with_order(1.0, series(2.0, 3.0, 0.9, 1.0), 0.5, series(2.0, 3.0, 0.9, 0.5), 0.9) ==
        Approx(2.0).epsilon(1e-12));
  CHECK_THROWS_AS(richardson_with_order(0.5, 1.0, 1.0, 2.0, 1.0), std::invalid_argument);
}

TEST_CASE("Richardson refuses series that do not converge monotonically", "[richardson]") {
  // Oscillating (the Hex20 at 2x2x2 points' cancellation: soft along the axis, stiff across).
  CHECK_FALSE(richardson_extrapolate(1.0, 9.963, 0.5, 9.838, 0.25, 9.9).has_value());
  // Diverging: the differences grow, an order below 0.1.
  CHECK_FALSE(richardson_extrapolate(1.0, 1.0, 0.5, 1.1, 0.25, 1.4).has_value());
  // Flat: no difference to extrapolate from.
  CHECK_FALSE(richardson_extrapolate(1.0, 2.0, 0.5, 2.0, 0.25, 2.0).has_value());
  CHECK_THROWS_AS(richardson_extrapolate(0.5, 1.0, 1.0, 1.0, 0.25, 1.0), std::invalid_argument);
}

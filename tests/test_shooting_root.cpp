// The shooting root (fem/reduced/shooting_root.hpp) on closed forms: a smooth
// root by the secant; the band before an undefined edge beside a positive
// minimum, where the secant alone circles the minimum; no root at all, which
// must be reported as such; and the last evaluation is always at the answer.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "fem/reduced/shooting_root.hpp"

using namespace softarm::fem;

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}

TEST_CASE("the shooting root finds a smooth root by the secant in a few evaluations", "[rod][shooting]") {
  ShootingSettings s;
  s.scale = 1;
  const ShootingRoot r = shooting_root([](double m) { return m * m * m - 2; }, 1.0, s);
  REQUIRE(r.converged);
  CHECK(r.m == Approx(std::cbrt(2.0)).epsilon(1e-9));
  CHECK(r.evaluations < 15);
}

TEST_CASE("the shooting root finds the band before an undefined edge beside a positive minimum", "[rod][shooting]") {
  // f = 1 + m² − e^{40(m − 1.5)}: a minimum of 1 at m = 0, a root at m ≈ 1.530 where f plunges,
  // undefined beyond m = 1.6 (a section past its limit). The arm rod's tip moment near its
  // payload capacity has this shape (shooting_root.hpp).
  double last = kNaN;
  const auto f = [&](double m) {
    last = m;
    return m > 1.6 ? kNaN : 1 + m * m - std::exp(40 * (m - 1.5));
  };
  for (const double start : {0.3, -0.5, 1.2}) {
    ShootingSettings s;
    s.scale = 1;
    s.first_step = 1e-2;
    const ShootingRoot r = shooting_root(f, start, s);
    INFO("start " << start << ": m = " << r.m << ", f = " << r.f << ", " << r.evaluations << " evaluations");
    REQUIRE(r.converged);
    CHECK(std::abs(1 + r.m * r.m - std::exp(40 * (r.m - 1.5))) <= 1e-10);
    CHECK(r.m == Approx(1.5 + std::log(1 + r.m * r.m) / 40).epsilon(1e-12));  // the root's fixed point
    CHECK(last == r.m);  // the caller's state is the root's
  }
}

TEST_CASE("the shooting root reports no root when f keeps one sign up to its edges", "[rod][shooting]") {
  ShootingSettings s;
  s.scale = 1;
  const ShootingRoot r = shooting_root([](double m) { return std::abs(m) > 2 ? kNaN : 1 + m * m; }, 0.5, s);
  CHECK_FALSE(r.converged);
  CHECK(r.evaluations < 400);
  const ShootingRoot undefined = shooting_root([](double) { return kNaN; }, 0.0, s);
  CHECK_FALSE(undefined.converged);
  CHECK(std::isnan(undefined.f));
}

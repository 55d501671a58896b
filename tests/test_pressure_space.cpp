// A segment's pressure space (fem/reduced/pressure_space.hpp): the canonical form of a pressure
// triple and the map of its responses, checked on closed-form responses with the section's symmetry
// (a beam's pressure moment, made nonlinear), and the direction grid's interpolation.
#include <catch2/catch.hpp>
#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <random>

#include "fem/reduced/pressure_space.hpp"

using namespace softarm::fem;

namespace {
constexpr double kPi = 3.14159265358979323846;

Eigen::Vector2d chamber_direction(int k) { return {std::cos(2 * kPi * k / 3), std::sin(2 * kPi * k / 3)}; }

/// Chamber k's force, any function of its own pressure and of the three's symmetric invariants.
double force(const std::array<double, 3>& p, int k) {
  const double sum = p[0] + p[1] + p[2];
  return p[k] + 0.003 * p[k] * p[k] + 0.001 * p[k] * sum;
}

/// The moment of the chambers' forces (along z, at the chambers' centres) about the axis: an axial
/// vector, M = Σ F_k (y_k, −x_k).
Eigen::Vector2d moment(const std::array<double, 3>& p) {
  Eigen::Vector2d m = Eigen::Vector2d::Zero();
  for (int k = 0; k < 3; ++k) m += force(p, k) * Eigen::Vector2d(chamber_direction(k).y(), -chamber_direction(k).x());
  return m;
}

/// A compliance of axial vectors with the same symmetry: I + Σ F_k m_k m_kᵀ.
Eigen::Matrix2d compliance(const std::array<double, 3>& p) {
  Eigen::Matrix2d c = Eigen::Matrix2d::Identity();
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector2d m(chamber_direction(k).y(), -chamber_direction(k).x());
    c += 0.01 * force(p, k) * m * m.transpose();
  }
  return c;
}

std::array<double, 3> canonical_triple(const CanonicalPressures& c) {
  return {c.peak_kPa, c.a * c.peak_kPa, c.b * c.peak_kPa};
}
}  // namespace

TEST_CASE("A pressure triple's canonical form and map give its responses from the canonical ones", "[pressure-space]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> pressure(0, 345);
  std::vector<std::array<double, 3>> triples = {{0, 0, 0}, {100, 0, 0}, {0, 100, 0}, {0, 0, 100}, {0, 345, 345},
                                                {345, 0, 345}, {200, 200, 200}, {0, 86, 345}, {59, 0, 0}};
  for (int i = 0; i < 200; ++i) triples.push_back({pressure(rng), pressure(rng), pressure(rng)});
  for (const auto& p : triples) {
    const CanonicalPressures c = canonical_pressures(p);
    INFO("p = " << p[0] << ", " << p[1] << ", " << p[2] << "; peak " << c.peak_kPa << ", a " << c.a << ", b " << c.b);
    REQUIRE(c.peak_kPa == Approx(std::max({p[0], p[1], p[2]})));
    REQUIRE(c.a <= 1);
    REQUIRE(c.b <= c.a);
    REQUIRE(c.b >= 0);
    // T is orthogonal and takes each canonical chamber onto the one holding its pressure.
    CHECK((c.section_map.transpose() * c.section_map - Eigen::Matrix2d::Identity()).norm() < 1e-12);
    CHECK((c.axial_map - c.section_map.determinant() * c.section_map).norm() < 1e-12);
    const auto q = canonical_triple(c);
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector2d image = c.section_map * chamber_direction(j);
      int k = 0;
      for (int m = 1; m < 3; ++m)
        if ((chamber_direction(m) - image).norm() < (chamber_direction(k) - image).norm()) k = m;
      CHECK((chamber_direction(k) - image).norm() < 1e-12);
      CHECK(p[k] == Approx(q[j]).margin(1e-12));
    }
    // The responses: an axial vector by A, its compliance by A·C·Aᵀ.
    CHECK((moment(p) - c.axial_map * moment(q)).norm() < 1e-9 * (1 + moment(p).norm()));
    CHECK((compliance(p) - c.axial_map * compliance(q) * c.axial_map.transpose()).norm() < 1e-12 * compliance(p).norm());
  }
  // The polar map alone (no sign under a mirror) would be wrong: the test can tell them apart.
  const std::array<double, 3> mirrored = {0, 86, 345};
  const CanonicalPressures c = canonical_pressures(mirrored);
  REQUIRE(c.section_map.determinant() < 0);
  CHECK((moment(mirrored) - c.section_map * moment(canonical_triple(c))).norm() > 1);
}

TEST_CASE("The direction grid's interpolation is a partition of unity exact for linear responses", "[pressure-space]") {
  for (int n = 1; n <= 4; ++n) {
    const auto grid = direction_grid(n);
    REQUIRE(grid.size() == static_cast<std::size_t>((n + 1) * (n + 2) / 2));
    for (std::size_t g = 0; g < grid.size(); ++g) {
      const auto w = direction_weights(n, grid[g].x(), grid[g].y());
      REQUIRE(w.size() == 1);
      CHECK(w[0].first == static_cast<int>(g));
      CHECK(w[0].second == Approx(1));
    }
    std::mt19937 rng(n);
    std::uniform_real_distribution<double> unit(0, 1);
    for (int t = 0; t < 500; ++t) {
      const double a = unit(rng), b = a * unit(rng);
      const auto w = direction_weights(n, a, b);
      double sum = 0, fa = 0, fb = 0, linear = 0;
      for (const auto& [index, weight] : w) {
        CHECK(weight >= 0);
        sum += weight;
        fa += weight * grid[index].x();
        fb += weight * grid[index].y();
        linear += weight * (3 - 2 * grid[index].x() + 5 * grid[index].y());
      }
      CHECK(sum == Approx(1).epsilon(1e-12));
      CHECK(fa == Approx(a).margin(1e-12));
      CHECK(fb == Approx(b).margin(1e-12));
      CHECK(linear == Approx(3 - 2 * a + 5 * b).epsilon(1e-12));
    }
  }
  CHECK_THROWS(direction_grid(0));
}

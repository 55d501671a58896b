// The spatial cell rod (fem/reduced/spatial_cell_rod.hpp) on synthetic cell tables: a
// constant free curvature and stretch give a circular arc (closed form); a tip load on a
// straight rod gives the linear cantilever's deflection and rotation, towards the load; in one
// plane it poses a 3CA as the planar cell rod (cell_rod.hpp) does, weight and caps included;
// past its cells' tables it says so.
#include <catch2/catch.hpp>
#include <Eigen/Geometry>
#include <cmath>

#include "fem/reduced/cell_rod.hpp"
#include "fem/reduced/spatial_cell_rod.hpp"

using namespace softarm::fem;

namespace {
/// A cell whose response is linear in the level: curvature κ·t, stretch 1 + ε·t, compliance c.
SpatialCellTable linear_cell(double z, const Eigen::Vector2d& curvature, double strain, double compliance,
                             double mass_per_length) {
  SpatialCellTable t;
  t.z_mm = z;
  t.mass_per_length_kg_per_mm = mass_per_length;
  for (double level : {0.0, 0.5, 1.0}) {
    t.level.push_back(level);
    t.stretch.push_back(1 + strain * level);
    t.curvature_per_mm.push_back(curvature * level);
    t.bending_compliance_per_Nmm2.push_back(compliance * Eigen::Matrix2d::Identity());
    t.axial_compliance_per_N.push_back(0);
  }
  return t;
}

SpatialCellPiece segment(double length, const std::vector<SpatialCellTable>& cells, double cap = 0) {
  SpatialCellPiece p;
  p.length_mm = length;
  p.cells = cells;
  p.cap_mm = cap;
  return p;
}
}  // namespace

TEST_CASE("A constant free curvature and stretch pose the spatial cell rod as a circular arc", "[cell][rod]") {
  const double L = 160, k = 0.01, strain = 0.2;  // 1.6 rad
  SpatialCellRodSpec spec;
  // About +y the section turns so that, going down from the clamp, the axis leans to +x.
  spec.pieces = {segment(L, {linear_cell(20, {0, k}, strain, 1e-6, 0), linear_cell(140, {0, k}, strain, 1e-6, 0)})};
  const SpatialCellRodState s = solve_spatial_cell_rod(spec, 1.0);
  REQUIRE(s.ok);
  const double theta = k * L, lambda = 1 + strain;
  const Eigen::Vector3d tip = s.position.back();
  CHECK(tip.x() == Approx(lambda * (1 - std::cos(theta)) / k).epsilon(1e-5));
  CHECK(tip.y() == Approx(0).margin(1e-9));
  CHECK(tip.z() == Approx(L - lambda * std::sin(theta) / k).epsilon(1e-5));
  // The tip's frame: turned by −θ about y.
  CHECK(s.frame.back()(0, 2) == Approx(-std::sin(theta)).margin(1e-9));
  // Halfway up the ramp: half the curvature.
  const SpatialCellRodState half = solve_spatial_cell_rod(spec, 0.5);
  REQUIRE(half.ok);
  CHECK(half.position.back().x() == Approx((1 + strain / 2) * (1 - std::cos(theta / 2)) / (k / 2)).epsilon(1e-5));
}

TEST_CASE("A tip load bends the spatial cell rod as the linear cantilever, towards the load", "[cell][rod]") {
  const double L = 100, c = 1e-6, m = 0.01;  // 1/EI in 1/(N·mm²), tip mass kg
  for (const Eigen::Vector3d& g : {Eigen::Vector3d(9.81, 0, 0), Eigen::Vector3d(0, -9.81, 0)}) {
    SpatialCellRodSpec spec;
    spec.pieces = {segment(L, {linear_cell(10, {0, 0}, 0, c, 0), linear_cell(90, {0, 0}, 0, c, 0)})};
    spec.gravity_m_s2 = g;
    spec.tip_mass_kg = m;
    const SpatialCellRodState s = solve_spatial_cell_rod(spec, 0.0);
    REQUIRE(s.ok);
    const Eigen::Vector3d F = m * g;  // N
    // δ = F L³ / 3EI = 3.27e-4 L: the geometric nonlinearity is ~1e-7 of it.
    const Eigen::Vector3d deflection = s.position.back() - Eigen::Vector3d::Zero();
    CHECK(deflection.dot(F.normalized()) == Approx(F.norm() * L * L * L * c / 3).epsilon(1e-4));
    const double delta = F.norm() * L * L * L * c / 3;
    CHECK(std::abs(deflection.dot(F.normalized().cross(Eigen::Vector3d(0, 0, 1)))) < 1e-9);  // in the plane
    // The tip rises by the arc's shortening, ∫ w'²/2 = (3/5) δ²/L for the cubic deflection.
    CHECK(deflection.z() == Approx(0.6 * delta * delta / L).epsilon(1e-3));
    // The tip's axis (−d3) turns towards the load by F L² / 2EI.
    CHECK((-s.frame.back().col(2)).dot(F.normalized()) == Approx(F.norm() * L * L * c / 2).epsilon(1e-4));
  }
}

TEST_CASE("A large tip load bends the spatial cell rod into Euler's elastica", "[cell][rod]") {
  // A hanging rod, clamped at the top, a weight P across it at the tip, P L²/EI = 3: the tip moves
  // across by 0.6 L. The elastica: θ(s) from the rest axis, EI θ'' = −P cos θ, θ(0) = 0,
  // θ'(L) = 0, solved here by shooting on θ'(0) with RK4 (10⁴ steps).
  const double L = 100, c = 1e-5, P = 30;  // 1/EI in 1/(N·mm²); N
  const double a = P * c;                  // P/EI, 1/mm²
  struct Tip {
    double slope_end, x, z;
  };
  const auto shoot = [&](double k0) {
    const int steps = 10000;
    const double h = L / steps;
    Eigen::Vector4d y(0, k0, 0, 0);  // θ, θ', x, z
    const auto f = [&](const Eigen::Vector4d& v) {
      return Eigen::Vector4d(v[1], -a * std::cos(v[0]), std::sin(v[0]), -std::cos(v[0]));
    };
    for (int i = 0; i < steps; ++i) {
      const Eigen::Vector4d k1 = f(y), k2 = f(y + 0.5 * h * k1), k3 = f(y + 0.5 * h * k2), k4 = f(y + h * k3);
      y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    }
    return Tip{y[1], y[2], y[3]};
  };
  double lo = 0, hi = a * L;  // θ'(0) = M(0)/EI lies between 0 and the straight rod's P L/EI
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    (shoot(mid).slope_end > 0 ? hi : lo) = mid;
  }
  const Tip elastica = shoot(0.5 * (lo + hi));
  SpatialCellRodSpec spec;
  spec.pieces = {segment(L, {linear_cell(10, {0, 0}, 0, c, 0), linear_cell(90, {0, 0}, 0, c, 0)})};
  spec.gravity_m_s2 = Eigen::Vector3d(10, 0, 0);
  spec.tip_mass_kg = P / 10;
  spec.interval_mm = 0.25;
  const SpatialCellRodState s = solve_spatial_cell_rod(spec, 0.0);
  INFO("elastica tip (" << elastica.x << ", " << elastica.z << ") mm; rod (" << s.position.back().x() << ", "
                        << s.position.back().z() - L << ") mm after " << s.iterations << " iterations");
  REQUIRE(s.ok);
  CHECK(elastica.x > 0.5 * L);  // a large deflection indeed
  CHECK(s.position.back().x() == Approx(elastica.x).epsilon(1e-4));
  CHECK(s.position.back().z() - L == Approx(elastica.z).epsilon(1e-4));
  CHECK(std::abs(s.position.back().y()) < 1e-9);
}

TEST_CASE("In one plane the spatial cell rod poses a 3CA as the planar cell rod does", "[cell][rod]") {
  // Cells with curvature and stretch varying along the height, heavy, with caps, under gravity
  // against the bend and down the axis: the planar rod's bend is the spatial +x; with end tables
  // over both ends (turning towards the bend at the clamp, against it at the free end) and without.
  const double L = 160, cap = 3;
  const std::vector<double> z = {2.7, 80, 157.3}, k = {0.012, 0.010, 0.007}, c = {2e-5, 1.5e-5, 1e-5};
  std::vector<CellTable> planar;
  std::vector<SpatialCellTable> spatial;
  for (int i = 0; i < 3; ++i) {
    spatial.push_back(linear_cell(z[i], {0, k[i]}, 0.1 - 0.02 * i, c[i], 2e-4 + 1e-4 * i));
    CellTable t;
    t.z_mm = z[i];
    t.mass_per_length_kg_per_mm = spatial.back().mass_per_length_kg_per_mm;
    t.pressure_kPa = {0, 150, 300};
    for (int j = 0; j < 3; ++j) {
      t.stretch.push_back(spatial.back().stretch[j]);
      t.curvature_per_mm.push_back(spatial.back().curvature_per_mm[j].y());
      t.bending_compliance_per_Nmm2.push_back(c[i]);
    }
    planar.push_back(t);
  }
  CellRodSpec p;
  p.length_mm = L;
  p.cap_mm = cap;
  p.cells = planar;
  p.gravity_along_bend_m_s2 = -9.81;
  p.gravity_along_axis_m_s2 = -9.81;
  p.intervals = 1280;
  SpatialCellRodSpec s;
  s.pieces = {segment(L, spatial, cap)};
  s.gravity_m_s2 = Eigen::Vector3d(-9.81, 0, -9.81);
  s.interval_mm = L / 1280;
  double tilt_with_ends = 0;
  for (bool with_ends : {false, true}) {
    if (with_ends) {
      // Lengths that end inside an interval (1280 intervals of 0.125 mm): shares of it.
      for (bool at_clamp : {true, false}) {
        const double length = at_clamp ? 10.71 : 7.43, turn = at_clamp ? 0.06 : -0.02, longer = at_clamp ? 0.4 : 0.9;
        p.ends.push_back({at_clamp, length, {0, 150, 300}, {0, 0.3 * turn, turn}, {0, 0.6 * longer, longer}});
        s.pieces[0].ends.push_back({at_clamp, length, {0, 0.5, 1}, {0, 0.6 * longer, longer},
                                    {Eigen::Vector2d::Zero(), {0, 0.3 * turn}, {0, turn}}});
      }
    }
    for (double level : {0.0, 0.5, 1.0}) {
      const CellRodState a = solve_cell_rod(p, 300 * level);
      const SpatialCellRodState b = solve_spatial_cell_rod(s, level);
      REQUIRE(a.ok);
      REQUIRE(b.ok);
      INFO((with_ends ? "end tables, " : "") << "level " << level << ": planar tip (" << a.tip_along_bend_mm << ", "
                                             << a.tip_z_mm << "), spatial (" << b.position.back().transpose() << ")");
      CHECK(b.position.back().x() == Approx(a.tip_along_bend_mm).margin(1e-3));
      CHECK(b.position.back().z() == Approx(a.tip_z_mm).margin(1e-3));
      CHECK(std::abs(b.position.back().y()) < 1e-9);
      const double tilt = std::atan2(-b.frame.back()(0, 2), b.frame.back()(2, 2)) * 180 / 3.14159265358979323846;
      CHECK(tilt == Approx(a.bending_angle_deg).margin(1e-3));
      if (with_ends) tilt_with_ends = tilt;
    }
  }
  // The end tables were read: at full pressure the cells (caps excluded) turn the clamp's 10.71 mm
  // by about 0.054 rad and the free end's 7.43 mm by about 0.053, the end tables by 0.06 and −0.02:
  // 3.8° less (3.92° measured: the weight's moment follows the shape).
  p.ends.clear();
  CHECK(solve_cell_rod(p, 300).bending_angle_deg - tilt_with_ends == Approx(3.8).margin(0.3));
  CHECK(spatial_cell_rod_mass_kg(s) == Approx(3e-4 * L).epsilon(1e-9));  // linear in z: its mid-height value
}

TEST_CASE("Past its cells' tables the spatial cell rod stops and says where", "[cell][rod]") {
  SpatialCellRodSpec spec;
  SpatialCellTable short_cell = linear_cell(50, {0, 0.01}, 0.1, 1e-5, 0);
  short_cell.level.pop_back(), short_cell.stretch.pop_back(), short_cell.curvature_per_mm.pop_back();
  short_cell.bending_compliance_per_Nmm2.pop_back(), short_cell.axial_compliance_per_N.pop_back();
  spec.pieces = {segment(100, {short_cell})};
  CHECK(solve_spatial_cell_rod(spec, 0.5).ok);
  const SpatialCellRodState s = solve_spatial_cell_rod(spec, 0.75);
  CHECK_FALSE(s.ok);
  CHECK(s.diagnosis.find("z = 50") != std::string::npos);
}

TEST_CASE("Where the direct iteration does not settle, the weights raised from none find the equilibrium", "[cell][rod]") {
  // Three segments bent every way by their free curvature (1.8, 3.5 and 1.3 rad), compliant (1/EI =
  // 4.8e-5 per N·mm²), 1.02 kg at the tip, hanging under gravity: the arm curls up and holds the weight
  // above its bends. Here, from no moments, the shape and the weights' moments chase each other through
  // the direct iteration's 400 steps (for tip masses from 0.98 to 1.06 kg; around them it settles or
  // not as erratically as a chaotic map does).
  const double c = 4.8e-5, mass = 4.8e-5;
  const std::vector<Eigen::Vector2d> k = {1.2 * Eigen::Vector2d(0.0097, 0.0116), 1.2 * Eigen::Vector2d(0.0208, 0.0197),
                                          1.2 * Eigen::Vector2d(0.0104, 0.0033)};
  SpatialCellRodSpec spec;
  for (const Eigen::Vector2d& ki : k) spec.pieces.push_back(segment(100, {linear_cell(10, ki, 0, c, mass), linear_cell(90, ki, 0, c, mass)}));
  spec.gravity_m_s2 = Eigen::Vector3d(0, 0, -9.81);
  spec.tip_mass_kg = 1.02;
  spec.interval_mm = 1;
  const SpatialCellRodState s = solve_spatial_cell_rod(spec, 1.0);
  INFO(s.diagnosis);
  REQUIRE(s.ok);
  INFO("tip " << s.position.back().transpose() << " mm after " << s.iterations << " iterations");
  CHECK(s.iterations > 400);  // the direct iteration's 400 did not settle: the weights were raised
  // A fixed point of the full weights: started from its own moments, the iteration stays there.
  const SpatialCellRodState again = solve_spatial_cell_rod(spec, 1.0, &s);
  REQUIRE(again.ok);
  CHECK(again.iterations <= 3);
  CHECK((again.position.back() - s.position.back()).norm() < 1e-8);
  // The branch the weightless shape bends into: the weights raised in twenty equal steps, each from
  // the last, end at the same tip.
  SpatialCellRodState path = solve_spatial_cell_rod([&] { auto w = spec; w.gravity_m_s2.setZero(); return w; }(), 1.0);
  for (int step = 1; step <= 20 && path.ok; ++step) {
    SpatialCellRodSpec part = spec;
    part.gravity_m_s2 = step / 20.0 * spec.gravity_m_s2;
    path = solve_spatial_cell_rod(part, 1.0, &path);
  }
  REQUIRE(path.ok);
  CHECK((path.position.back() - s.position.back()).norm() < 1e-6);
}

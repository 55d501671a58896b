// The planar cell rod's end tables (fem/reduced/cell_rod.hpp, EndTable): over each end's length
// the end's own turn and elongation replace the cells' κ₀ and λ₀. With constant cells and no
// weight the rod is three circular arcs, so its tip angle and position are closed-form; an end
// table that stops short of a pressure stops the rod and names the end.
#include <catch2/catch.hpp>
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "fem/reduced/cell_rod.hpp"

using namespace softarm::fem;

namespace {
constexpr double kDeg = 180 / 3.14159265358979323846;

/// A cell whose curvature and strain grow linearly with pressure to κ and ε at 300 kPa.
CellTable linear_cell(double z, double curvature, double strain) {
  CellTable t;
  t.z_mm = z;
  for (double p : {0.0, 150.0, 300.0}) {
    t.pressure_kPa.push_back(p);
    t.curvature_per_mm.push_back(curvature * p / 300);
    t.stretch.push_back(1 + strain * p / 300);
    t.bending_compliance_per_Nmm2.push_back(1e-5);
  }
  return t;
}

EndTable linear_end(bool at_clamp, double length, double turn, double elongation) {
  EndTable e;
  e.at_clamp = at_clamp;
  e.length_mm = length;
  for (double p : {0.0, 300.0}) {
    e.pressure_kPa.push_back(p);
    e.rotation_rad.push_back(turn * p / 300);
    e.elongation_mm.push_back(elongation * p / 300);
  }
  return e;
}

/// The tip of arcs in series from the clamp at (0, L), each (reference length, curvature per
/// reference length, stretch): dθ/dS = κ, dr/dS = λ (sin θ, −cos θ).
Eigen::Vector2d arcs_tip(double L, const std::vector<std::array<double, 3>>& arcs, double& theta) {
  Eigen::Vector2d r(0, L);
  theta = 0;
  for (const auto& [S, k, lambda] : arcs) {
    const double t1 = theta + k * S;
    r += k == 0 ? Eigen::Vector2d(lambda * S * std::sin(theta), -lambda * S * std::cos(theta))
                : Eigen::Vector2d(lambda / k * (std::cos(theta) - std::cos(t1)), -lambda / k * (std::sin(t1) - std::sin(theta)));
    theta = t1;
  }
  return r;
}
}  // namespace

TEST_CASE("End tables replace the cells' curvature and stretch over each end: three circular arcs", "[cell][rod]") {
  const double L = 160, k = 0.01, strain = 0.15;
  const double free_length = 10.5, clamp_length = 7.3;  // neither on the rod's interval grid
  const double free_turn = 0.02, free_longer = 0.9, clamp_turn = 0.09, clamp_longer = 1.7;
  CellRodSpec spec;
  spec.length_mm = L;
  spec.cap_mm = 2;  // inside both ends: the end tables hold there
  spec.cells = {linear_cell(2.7, k, strain), linear_cell(157.3, k, strain)};
  spec.ends = {linear_end(false, free_length, free_turn, free_longer), linear_end(true, clamp_length, clamp_turn, clamp_longer)};
  spec.intervals = 1280;
  for (double p : {150.0, 300.0}) {
    const double f = p / 300;
    const CellRodState s = solve_cell_rod(spec, p);
    REQUIRE(s.ok);
    double theta = 0;
    const Eigen::Vector2d tip = arcs_tip(
        L, {{clamp_length, f * clamp_turn / clamp_length, 1 + f * clamp_longer / clamp_length},
            {L - clamp_length - free_length, f * k, 1 + f * strain},
            {free_length, f * free_turn / free_length, 1 + f * free_longer / free_length}},
        theta);
    INFO(p << " kPa: rod " << s.bending_angle_deg << "°, tip (" << s.tip_along_bend_mm << ", " << s.tip_z_mm
           << "); arcs " << theta * kDeg << "°, (" << tip.transpose() << ")");
    CHECK(s.bending_angle_deg == Approx(theta * kDeg).epsilon(1e-12));  // the turns add exactly
    CHECK(s.tip_along_bend_mm == Approx(tip.x()).margin(2e-3));
    CHECK(s.tip_z_mm == Approx(tip.y()).margin(2e-3));
  }
}

TEST_CASE("An end table short of a pressure stops the cell rod and names the end", "[cell][rod]") {
  CellRodSpec spec;
  spec.length_mm = 160;
  spec.cells = {linear_cell(80, 0.01, 0.1)};
  EndTable clamp = linear_end(true, 10, 0.05, 0.5);
  clamp.pressure_kPa.back() = 200;  // reached 200 kPa only
  spec.ends = {clamp};
  CHECK(solve_cell_rod(spec, 150).ok);
  const CellRodState s = solve_cell_rod(spec, 250);
  CHECK_FALSE(s.ok);
  CHECK(s.diagnosis.find("clamped end") != std::string::npos);
  CHECK(s.diagnosis.find("200") != std::string::npos);
}

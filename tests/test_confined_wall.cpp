// The ring-confined tube wall (fem/reduced/confined_wall.hpp) against closed
// forms: its law is the derivative of the wall's strain energy under the
// confined kinematics (checked by finite differences of an independent radial
// quadrature of the energy), a thin confined wall is in planar tension (small-
// strain modulus 4μ against the free fibre's 3μ), and the rod's section with
// confinement keeps the tube's area while moving the chamber's force area to
// the rings' inner radius on the ringed length only.
#include <catch2/catch.hpp>
#include <cmath>

#include "fem/materials/material.hpp"
#include "fem/reduced/arm_rod.hpp"
#include "fem/reduced/confined_wall.hpp"
#include "fem/reduced/rod_section.hpp"

using namespace softarm::fem;

namespace {
constexpr double kPi = 3.14159265358979323846;

// Π(λ) = ∫ W 2πR dR over [R_c, R_i] by the midpoint rule in R (not the law's Gauss rule in R²).
double wall_energy(const HyperelasticLaw& law, double rc, double ri, double l, int n = 20000) {
  double sum = 0;
  const double dr = (ri - rc) / n;
  for (int k = 0; k < n; ++k) {
    const double R = rc + (k + 0.5) * dr, r2 = ri * ri - (ri * ri - R * R) / l;
    sum += law.principal_energy(l * l, r2 / (R * R), R * R / (l * l * r2)).v * 2 * kPi * R * dr;
  }
  return sum;
}
}  // namespace

TEST_CASE("the confined wall's law is the derivative of its strain energy", "[reduced][confined]") {
  for (const std::string name : {"dragon_skin_20", "dragon_skin_30"}) {
    const Material m = builtin_material(name, "test");
    const double rc = 4.81, ri = 7.93;  // thesis distal RRA at its bottom: chamber and grooves' bottom
    const FibreLaw law = confined_wall_law(*m.law, rc, ri);
    const double area = kPi * (ri * ri - rc * rc);
    INFO(name);
    CHECK(std::abs(law.stress(1.0)) < 1e-8);  // the reference state is stress free (table roundoff ~1e-9 MPa)
    for (double l : {0.8, 1.05, 1.4, 2.0}) {
      const double h = 1e-4;
      const double fd = (wall_energy(*m.law, rc, ri, l + h) - wall_energy(*m.law, rc, ri, l - h)) / (2 * h) / area;
      INFO("stretch " << l);
      CHECK(law.stress(l) == Approx(fd).epsilon(2e-4));
    }
  }
}

TEST_CASE("a thin confined wall is in planar tension: small-strain modulus 4 mu", "[reduced][confined]") {
  const Material m = builtin_material("dragon_skin_30", "test");
  const double mu = m.law->initial_shear_modulus();
  const FibreLaw thin = confined_wall_law(*m.law, 9.99, 10.0);
  CHECK(thin.initial_modulus() == Approx(4 * mu).epsilon(2e-3));
  CHECK(FibreLaw(*m.law).initial_modulus() == Approx(3 * mu).epsilon(1e-4));
  // A thick wall is stiffer still: its inner fibres must widen in hoop as the wall thins.
  CHECK(confined_wall_law(*m.law, 4.81, 7.93).initial_modulus() > 4.5 * mu);
  CHECK(confined_wall_min_stretch(4.81, 7.93) == Approx(1 - 4.81 * 4.81 / (7.93 * 7.93)));
}

TEST_CASE("confinement keeps the tube's area and moves the force area to the rings' inner radius", "[reduced][confined]") {
  TcaDesign d;  // the thesis 3CA (tca_design.hpp defaults)
  const Material m = builtin_material("dragon_skin_30", "test");
  const RraDesign& a = d.actuator;
  const double z = 0.5 * a.length_mm, cap = 0.5 * a.end_cap_thickness_mm;
  const RodSection free = tca_section(d, z, 0.0), held = tca_section(d, z, 0.0, 48, 6, m.law.get());
  const double ri = a.outer_radius(z) - a.ring_section_radius();
  CHECK(confinement_radius(a, z) == Approx(ri));
  CHECK(held.tube_area + held.confined_area == Approx(free.tube_area).epsilon(1e-12));
  CHECK(held.confined_area == Approx(3 * kPi * (ri * ri - std::pow(a.chamber_radius(z), 2))).epsilon(1e-9));
  CHECK(held.sheath_area == Approx(free.sheath_area).epsilon(1e-12));
  REQUIRE(held.confined_law);
  for (double area : held.chamber_force_area) CHECK(area == Approx(kPi * ri * ri));
  // In an end cap nothing is confined and the force acts on the cap's inner face.
  const RodSection in_cap = tca_section(d, cap, 0.0, 48, 6, m.law.get());
  CHECK(confinement_radius(a, cap) == 0.0);
  CHECK(in_cap.confined_area == 0.0);
  CHECK_FALSE(in_cap.confined_law);
  for (double area : in_cap.chamber_force_area) CHECK(area == Approx(kPi * std::pow(chamber_force_radius(a, cap), 2)));
}

TEST_CASE("only rigid rings confine: rings of the tube's silicone leave the rod free", "[reduced][confined]") {
  const auto bending_deg = [](const std::string& rings, bool confined) {
    ArmRodSpec spec;
    RodPiece piece;
    piece.kind = RodPiece::Kind::tca;
    spec.pieces = {piece};
    spec.tube = spec.sheath = builtin_material("dragon_skin_30", "tube");
    spec.rings = builtin_material(rings, "rings");
    spec.nodes_per_segment = 9;
    spec.ring_confinement = confined;
    const ArmRod rod(spec);
    RodLoad load;
    load.chamber_pressure_kPa = {{0.0, 50.0, 50.0}};
    load.clamp_angle_rad = -kPi / 2;
    return rod.tip_rotation(rod.follow(load, 4), load) * 180 / kPi;
  };
  CHECK(bending_deg("dragon_skin_30", true) == Approx(bending_deg("dragon_skin_30", false)).epsilon(1e-12));
  // ABS rings: the pressure acts on π R_i² instead of π r_c² (2.7x at the thesis RRA's bottom), against a stiffer wall.
  CHECK(bending_deg("digital_abs", true) > 1.5 * bending_deg("digital_abs", false));
}

// Torsion at rest with the ends held as in an arm (fem/scenes/twist_compliance.hpp): a closed
// form for the face supports, and a short 3CA bonded at both ends against the spatial cell rod.
#include <catch2/catch.hpp>

#include <cmath>
#include <iomanip>
#include <vector>

#include "fem/mesh/quadratic_mesh.hpp"
#include "fem/mesh/structured_mesh.hpp"
#include "fem/scenes/tca_cell.hpp"
#include "fem/scenes/twist_compliance.hpp"
#include "support/test_problems.hpp"
#include "support/tube_meshes.hpp"
#include "support/untapered_3ca.hpp"

using namespace softarm::fem;

TEST_CASE("A tube held at one end and turned at the other twists as Saint-Venant's torsion says", "[twist]") {
  // A circular tube's sections stay plane and turn rigidly under torsion, so the held face and
  // the turned one (either support: warping free or held) carry the exact solution, and
  // C = L / (μ J), J = π (B⁴ − A⁴) / 2. Hex27 with its nodes on the cylinders: only the arcs'
  // interpolation differs, (2π/nc)⁴ small. A = 5, B = 10, L = 20 mm, μ = 1 MPa, K = 1000 μ.
  const double A = 5, B = 10, L = 20, mu = 1;
  Mesh mesh = to_quadratic_3d(hollow_cylinder_mesh(A, B, L, 2, 32, 4));
  softarm::test::snap_to_cylinders(mesh, 32);
  const double exact = L / (mu * M_PI * (std::pow(B, 4) - std::pow(A, 4)) / 2);
  for (const TwistedFace face : {TwistedFace::warping_free, TwistedFace::warping_held}) {
    const double c = face_twist_compliance(mesh, {softarm::test::neo_hookean(mu, 1000 * mu)}, ElementIntegration::full,
                                           "z1", "z0", face);
    INFO("compliance " << c << " rad/(N mm), exact " << exact);
    CHECK(std::abs(c / exact - 1) < 1e-4);
  }
}

TEST_CASE("Bonded end cells twist a short 3CA as its 3D model does, where the cells' GJ alone does not", "[twist][long]") {
  // Seven ring pitches of the thesis 3CA's distal section (untapered, r = 9 mm, caps 2.25 mm),
  // bonded at both ends: the top held, the bottom on a rigid connector turned about the axis.
  // The cells' GJ is Saint-Venant's (sections warping freely); the bonded faces cannot warp and
  // the caps are solid, so the whole 3CA is stiffer. Measured (level 2's layers): the
  // 3D model 1.1471e-3 rad/(N mm); the rod on its cells' GJ alone +3.78 %; with end cells through
  // 1, 2 and 3 rings +0.92 %, +0.42 %, +0.18 %.
  const TcaSceneSpec spec = softarm::test::untapered_3ca(7, 2, 2);
  const double solid = tca_twist_compliance(spec);
  REQUIRE(solid > 0);
  const std::vector<double> rod = tca_rod_twist_compliances(spec, {0, 2, 3});
  REQUIRE(rod.size() == 3);
  for (double c : rod) REQUIRE((std::isfinite(c) && c > 0));  // an end's twist is positive or NaN
  const double cells_only = rod[0];
  const std::vector<double> error = {rod[1] / solid - 1, rod[2] / solid - 1};
  INFO("3D " << solid << " rad/(N mm); the rod: cells alone " << 100 * (cells_only / solid - 1)
             << " %, end cells through 2 rings " << 100 * error[0] << " %, through 3 " << 100 * error[1] << " %");
  CHECK(cells_only / solid - 1 > 0.03);
  CHECK(std::abs(error[0]) < 0.01);
  CHECK(std::abs(error[1]) < std::abs(error[0]));
}

TEST_CASE("A twist at rest on the antisymmetric half model is the full model's, to round-off", "[twist][cell]") {
  // A twist is odd under the mirror through the axis and chamber 1: the half model, held on its
  // plane in x and z and free across it, carries half the full model's torque. Here against the
  // full model (symmetry turned off), whose chambers keep the scene's angle: the half model's
  // are turned to put chamber 1 on the plane, which leaves the torsion as it is. A tapered 3CA
  // (5 rings, level 1) so that the ends differ; both end cells (warping free) and the whole 3CA
  // bonded at both ends (warping held).
  TcaSceneSpec half = softarm::test::untapered_3ca(5, 1, 2);
  half.design.actuator.top_radius_mm = 10;  // from 9 mm at the bottom
  half.chamber_pressure_kPa = {150, 0, 0};  // any load: the twist is taken at rest
  TcaSceneSpec full = half;
  full.allow_symmetry = false;
  const auto agree = [](double a, double b) {  // rad/(N mm) for the twists, 1/(N mm²) for 1/GJ
    INFO("half model " << std::setprecision(15) << a << ", full model " << b);
    REQUIRE(std::isfinite(b));
    CHECK(b > 0);
    CHECK(a == Approx(b).epsilon(1e-10));
  };
  agree(end_cell_twist_compliance(half, TcaEnd::bottom, 1), end_cell_twist_compliance(full, TcaEnd::bottom, 1));
  agree(end_cell_twist_compliance(half, TcaEnd::top, 1), end_cell_twist_compliance(full, TcaEnd::top, 1));
  agree(tca_twist_compliance(half), tca_twist_compliance(full));
  // The ring-pitch cells' GJ (periodic faces; on the half model the plane's pairs at half weight),
  // at the bottom, middle and top rings.
  for (int ring : {1, 3, 5}) {
    INFO("ring " << ring);
    agree(1 / cell_torsion_stiffness(half, ring), 1 / cell_torsion_stiffness(full, ring));
  }
}

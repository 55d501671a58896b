// The ring-pitch cell of a 3CA (fem/scenes/tca_cell.hpp): at small end loads a cell of
// one silicone is the linear beam EA, EI of its section (closed form, with A and I from
// the rod's exact section, rod_section.hpp); under pressure, rigid rings are what make
// it stretch and bend (a closed tube of incompressible silicone does neither, Lamé); and under
// pressure a cell bends as the inside of a long 3D 3CA does (the difference of two lengths), between
// the 3D meshes that share its layers through the gap and through the ring.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "fem/core/angles.hpp"
#include "fem/reduced/rod_section.hpp"
#include "fem/scenes/scene_config.hpp"
#include "fem/scenes/tca_cell_rod.hpp"
#include "support/untapered_3ca.hpp"

using namespace softarm::fem;

namespace {
/// The thesis 3CA scene on its 3D mesh (configs/convergence/tca_thesis_hex20r.json: Hex20 at 2×2×2 points, level 1).
TcaSceneSpec thesis_cell_spec() {
  return load_scene_config(std::string(SOFTARM_SOURCE_DIR) + "/configs/convergence/tca_thesis_hex20r.json").tca;
}
}  // namespace

TEST_CASE("A silicone cell under small end loads is the section's EA and EI", "[cell]") {
  TcaSceneSpec spec = thesis_cell_spec();
  spec.ring_material = spec.tube_material;  // one material: a prism with three bores
  spec.chamber_pressure_kPa = {0, 0, 0};
  const int ring = 15;
  const double z = spec.design.actuator.ring_centre_z(ring);
  // A and I about the 3CA axis (the centroid, by the section's three-fold symmetry) from the
  // rod's section, which integrates the circles exactly (strips of width Δy add Δy²/12 each).
  const RodSection section = tca_section(spec.design, z, 0.0, 96);
  double A = 0, I = 0;
  const double dy = section.strips[1].y - section.strips[0].y;
  for (const auto& s : section.strips) {
    A += s.tube_area + s.sheath_area;
    I += (s.y * s.y + dy * dy / 12) * (s.tube_area + s.sheath_area);
  }
  const auto& law = *spec.tube_material.law;
  const double mu = law.initial_shear_modulus(), K = law.initial_bulk_modulus(), E = 9 * K * mu / (3 * K + mu);
  // Strains of 10⁻³: the cell answers linearly to ~10⁻³ of itself.
  CellEndLoad pull;
  pull.axial_force_N = 1e-3 * E * A;
  const TcaCellResult stretched = run_tca_cell(spec, ring, pull);
  REQUIRE(stretched.path.outcome == PathOutcome::completed);
  CellEndLoad bend;
  bend.moment_Nmm = Eigen::Vector2d(0, 1e-3 * E * I / 10.0);  // κ = 10⁻⁴ /mm, about the mirror plane's normal
  const TcaCellResult bent = run_tca_cell(spec, ring, bend);
  REQUIRE(bent.path.outcome == PathOutcome::completed);
  CHECK(bent.model.half);
  const TcaCellState& s = stretched.states.back();
  const TcaCellState& b = bent.states.back();
  INFO("A " << A << " mm², I " << I << " mm⁴, E " << E << " MPa; stretch " << s.stretch << ", curvature "
            << b.curvature_per_mm << " /mm, plane gaps " << s.plane_gap_mm << ", " << b.plane_gap_mm << " mm");
  // The mesh's polygons of 8 quadratic edges per bore, and the faces' penalty, against exact circles: 1 %.
  CHECK(s.stretch - 1 == Approx(1e-3).epsilon(0.01));
  CHECK(b.curvature_per_mm == Approx(1e-4).epsilon(0.01));
  CHECK(std::abs(b.stretch - 1) < 1e-3 * 1e-2);  // no coupling about the centroid
  // The tangent's compliances at the loaded states: the same beam.
  CHECK(s.axial_compliance_per_N * E * A == Approx(1).epsilon(0.01));
  CHECK(b.bending_compliance_per_Nmm2 * E * I == Approx(1).epsilon(0.01));
  // A moment about x turns out of the mirror plane: the full cell, the same I (three-fold symmetry).
  CellEndLoad across;
  across.moment_Nmm = Eigen::Vector2d(1e-3 * E * I / 10.0, 0);
  const TcaCellResult full = run_tca_cell(spec, ring, across);
  REQUIRE(full.path.outcome == PathOutcome::completed);
  CHECK_FALSE(full.model.half);
  CHECK(full.states.back().curvature_per_mm == Approx(1e-4).epsilon(0.01));
  CHECK(full.states.back().bending_compliance_per_Nmm2 * E * I == Approx(1).epsilon(0.01));
  // As vectors in the user frame (the spatial cell rod's inputs): a moment about +y turns the
  // section about +y, one about +x about +x; the compliance is 1/EI on the diagonal, ~nothing across.
  const auto vector_is = [&](const TcaCellState& state, double kx, double ky) {
    CHECK(state.curvature_vector_per_mm.x() == Approx(kx).margin(1e-6));
    CHECK(state.curvature_vector_per_mm.y() == Approx(ky).margin(1e-6));
    const Eigen::Matrix2d c = state.bending_compliance_matrix_per_Nmm2 * E * I;
    CHECK(c(0, 0) == Approx(1).epsilon(0.01));
    CHECK(c(1, 1) == Approx(1).epsilon(0.01));
    CHECK(std::abs(c(0, 1)) < 5e-3);  // the full mesh is not quite mirror-symmetric: 0.18 % measured
    CHECK(std::abs(c(1, 0)) < 5e-3);
  };
  vector_is(b, 0, 1e-4);
  vector_is(full.states.back(), 1e-4, 0);
  CHECK(s.plane_gap_mm < 2e-3 * (s.stretch - 1) * stretched.pitch_mm);  // the penalty holds the plane to ~10⁻³
}

TEST_CASE("Rigid rings make a pressurised cell stretch and bend, silicone ones barely", "[cell]") {
  TcaSceneSpec spec = thesis_cell_spec();
  spec.chamber_pressure_kPa = {0, 20, 20};
  spec.output_pressures_kPa = {20};
  const TcaCellResult abs_rings = run_tca_cell(spec, 15);
  spec.ring_material = spec.tube_material;
  const TcaCellResult silicone_rings = run_tca_cell(spec, 15);
  REQUIRE(abs_rings.path.outcome == PathOutcome::completed);
  REQUIRE(silicone_rings.path.outcome == PathOutcome::completed);
  const TcaCellState& r = abs_rings.states.back();
  const TcaCellState& s = silicone_rings.states.back();
  INFO("ABS rings: stretch " << r.stretch << ", " << r.curvature_per_mm * kDeg << " deg/mm; silicone: "
                             << s.stretch << ", " << s.curvature_per_mm * kDeg << " deg/mm");
  CHECK(r.pressure_kPa == Approx(20));
  // Towards the unpressurised chamber, and longer: the rings hold the chambers' width, the
  // squeezed wall lengthens (docs/reduced-model.md, What the rings do).
  CHECK(r.curvature_per_mm > 0);
  CHECK(r.stretch > 1.005);
  CHECK(std::abs(s.stretch - 1) < 0.05 * (r.stretch - 1));
  CHECK(std::abs(s.curvature_per_mm) < 0.05 * r.curvature_per_mm);
}

TEST_CASE("A cell's torsional stiffness: under the polar moment of a silicone cell, raised by rigid rings", "[cell]") {
  TcaSceneSpec spec = thesis_cell_spec();
  const int ring = 15;
  const double z = spec.design.actuator.ring_centre_z(ring);
  // The polar moment of the silicone section, I_p = 2 I by its threefold symmetry (strips as above).
  const RodSection section = tca_section(spec.design, z, 0.0, 96);
  double I = 0;
  const double dy = section.strips[1].y - section.strips[0].y;
  for (const auto& s : section.strips) I += (s.y * s.y + dy * dy / 12) * (s.tube_area + s.sheath_area);
  const double mu = spec.tube_material.law->initial_shear_modulus();
  const double abs_rings = cell_torsion_stiffness(spec, ring);
  spec.ring_material = spec.tube_material;
  const double silicone_rings = cell_torsion_stiffness(spec, ring);
  INFO("GJ: silicone rings " << silicone_rings << ", ABS rings " << abs_rings << ", mu I_p " << mu * 2 * I << " N mm2");
  // Saint-Venant: warping only lowers the torsion constant below the polar moment (equal for a
  // circular annulus); three off-centre bores warp the section, but not by half.
  CHECK(silicone_rings < mu * 2 * I);
  CHECK(silicone_rings > 0.5 * mu * 2 * I);
  CHECK(abs_rings > 1.1 * silicone_rings);  // the rings hold the tube walls against shear
}

TEST_CASE("Gravity across the bend takes the 3CA's cell rod through the spatial rod, consistently with the planar one",
          "[cell][long]") {
  TcaSceneSpec spec = thesis_cell_spec();
  use_cell_rod_rung(spec);
  spec.chamber_pressure_kPa = {0, 60, 60};  // bends towards +x
  spec.output_pressures_kPa = {30, 60};
  // One set of cells for the three: gravity has no part in them, only in the rod.
  spec.gravity_m_s2 = Eigen::Vector3d(0, 9.80665, 0);  // across the bend
  REQUIRE(tca_needs_spatial_rod(spec));
  const TcaRodCells cells = run_tca_rod_cells(spec, true);
  const CellRodTcaResult across = pose_cell_rod_tca(spec, cells);
  spec.gravity_m_s2 = Eigen::Vector3d(9.80665, 0, 0);  // along it: one plane
  const CellRodTcaResult along = pose_cell_rod_tca(spec, cells);
  spec.gravity_m_s2.setZero();
  const CellRodTcaResult weightless = pose_cell_rod_tca(spec, cells);
  REQUIRE(along.converged);
  REQUIRE(across.converged);
  REQUIRE(weightless.converged);
  CHECK_FALSE(along.spatial);
  CHECK(across.spatial);
  // At rest the cells are straight and bend alike about x and y: the weight sags the 3CA as far
  // across the bend as along it (the spatial rod's tip leaves the bend plane by exactly that).
  const double sag = along.curve.front().tip_along_bend_mm;
  INFO("sag along the bend " << sag << " mm; across: tip along the bend " << across.curve.front().tip_along_bend_mm
                             << " mm, tilt " << across.curve.front().bending_angle_deg << "°");
  CHECK(sag > 0.5);
  CHECK(std::abs(across.curve.front().tip_along_bend_mm) < 1e-9);
  CHECK(across.curve.front().tip_across_bend_mm == Approx(sag).epsilon(2e-4));  // towards +y, where gravity pulls
  CHECK(along.curve.front().tip_across_bend_mm == 0);  // the planar rod stays in its plane
  // (to 5·10⁻⁵: the spatial rod also stretches under the weight's tension, the planar one does not)
  CHECK(std::abs(across.curve.front().bending_angle_deg) ==
        Approx(std::abs(along.curve.front().bending_angle_deg)).epsilon(2e-4));
  // At 60 kPa the weight across the bend leaves the bend itself nearly as without weight.
  const CellRodState& a = across.curve.back();
  const CellRodState& w = weightless.curve.back();
  INFO("60 kPa: across " << a.bending_angle_deg << "°, tip along the bend " << a.tip_along_bend_mm << " mm; weightless "
                         << w.bending_angle_deg << "°, " << w.tip_along_bend_mm << " mm");
  CHECK(a.tip_along_bend_mm == Approx(w.tip_along_bend_mm).epsilon(0.02));
  CHECK(a.bending_angle_deg > w.bending_angle_deg);  // the sideways sag adds to the tip's tilt
  CHECK(a.bending_angle_deg < w.bending_angle_deg + std::abs(along.curve.front().bending_angle_deg));
}

TEST_CASE("A ring-pitch cell bends as the inside of a long 3CA does, at the 3D mesh's layers through the gap",
          "[cell][long]") {
  // The inside of a long 3CA, free of its ends: the bend that six more ring pitches add (12 against
  // 6 rings), per pitch. A cell cut at mid-gap has level L's layers in each half gap, so 2L through a
  // gap, as the 3D mesh at level 2L has, and L through the ring, as at level L: its bend lies between
  // the two meshes'. Measured: 0.7998 °/pitch at 75 kPa against 0.7932 (level 1) and 0.8097 (level 2),
  // 1.6360 at 150 kPa against 1.6037 and 1.6675. So an "equal mesh" comparison of a cell rod at level L
  // with the 3D model at level L sets a finer model against a coarser one (docs/cell-rod.md, Matched
  // layers).
  const double p = softarm::test::untapered_3ca(6, 1, 2).design.actuator.pitch();
  std::vector<std::vector<double>> inside;  // per 3D level, per output
  for (int level : {1, 2}) {
    const TcaResult short_one = run_tca_scene(softarm::test::untapered_3ca(6, level, 2));
    const TcaResult long_one = run_tca_scene(softarm::test::untapered_3ca(12, level, 2));
    REQUIRE(short_one.path.outcome == PathOutcome::completed);
    REQUIRE(long_one.path.outcome == PathOutcome::completed);
    REQUIRE(short_one.curve.size() == long_one.curve.size());
    inside.emplace_back();
    for (std::size_t i = 1; i < long_one.curve.size(); ++i)
      inside.back().push_back((long_one.curve[i].bending_angle_deg - short_one.curve[i].bending_angle_deg) / 6);
  }
  const TcaCellResult cell = run_tca_cell(softarm::test::untapered_3ca(6, 1, 2), 3);
  REQUIRE(cell.path.outcome == PathOutcome::completed);
  std::vector<double> per_pitch;
  for (const auto& s : cell.states)
    if (s.is_output && s.pressure_kPa > 0) per_pitch.push_back(s.curvature_per_mm * p * kDeg);
  REQUIRE(per_pitch.size() == inside[0].size());
  for (std::size_t i = 0; i < per_pitch.size(); ++i) {
    INFO("output " << i << ": cell " << per_pitch[i] << "°/pitch; 3D inside, level 1's layers " << inside[0][i]
                   << ", level 2's " << inside[1][i]);
    CHECK(per_pitch[i] > inside[0][i]);
    CHECK(per_pitch[i] < inside[1][i]);
    CHECK(per_pitch[i] == Approx(0.5 * (inside[0][i] + inside[1][i])).epsilon(0.01));
  }
}

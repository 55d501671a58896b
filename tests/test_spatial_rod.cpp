// The spatial rod (fem/reduced/spatial_rod.hpp) against the planar rod where
// the loads lie in one plane, against the 3CA's threefold symmetry, and against
// global equilibrium where they do not; its cell sections against the planar
// rod's exact strip sections.
#include <catch2/catch.hpp>
#include <Eigen/Geometry>
#include <cmath>

#include "fem/core/angles.hpp"
#include "fem/core/json_reader.hpp"
#include "fem/reduced/arm_rod.hpp"
#include "fem/scenes/reduced_scenes.hpp"
#include "fem/reduced/spatial_rod.hpp"

using namespace softarm::fem;

namespace {

ArmRodSpec thesis_3ca_spec(int nodes) {
  ArmRodSpec spec;
  spec.pieces = {RodPiece{}};  // Table 7 / Table 11 defaults: the thesis 3CA
  spec.tube = spec.sheath = builtin_material("dragon_skin_30", "test");
  spec.rings = builtin_material("digital_abs", "test");
  spec.nodes_per_segment = nodes;
  return spec;
}

SplDesign thesis_spl_design() {
  nlohmann::json geometry = {{"wall_thickness_normalised", 0.466}, {"end_cap_thickness_normalised", 0.25},
                             {"ring_count_normalised", 0.375}, {"ring_thickness_normalised", 0.4}};
  JsonReader reader(geometry, "geometry");
  return read_spl_design(reader);
}

// ∫ ξ ξᵀ dA over both materials.
Eigen::Matrix2d second_moments(const CellSection& s) {
  Eigen::Matrix2d i = Eigen::Matrix2d::Zero();
  for (const auto& c : s.cells) i += (c.tube_area + c.sheath_area) * c.xi * c.xi.transpose();
  return i;
}
}  // namespace

TEST_CASE("cell sections keep the strip sections' areas and isotropic second moments", "[reduced][spatial]") {
  const TcaDesign tca;
  for (double z : {1.0, 80.0, 159.5}) {  // in a cap, mid-chamber, in the other cap
    const RodSection strips = tca_section(tca, z, 0.0);
    const CellSection cells = tca_cell_section(tca, z);
    CHECK(cells.tube_area == Approx(strips.tube_area).epsilon(2e-3));
    CHECK(cells.sheath_area == Approx(strips.sheath_area).epsilon(2e-3));
    double i_strips = 0;
    for (const auto& f : strips.strips) i_strips += f.y * f.y * (f.tube_area + f.sheath_area);
    // The section has threefold symmetry, so its second moment is the same about every axis.
    const Eigen::Matrix2d i = second_moments(cells);
    CHECK(i(0, 0) == Approx(i_strips).epsilon(5e-3));
    CHECK(i(1, 1) == Approx(i_strips).epsilon(5e-3));
    CHECK(std::abs(i(0, 1)) < 2e-3 * i_strips);
  }
}

TEST_CASE("in one plane the spatial rod poses the thesis 3CA as the planar rod does", "[reduced][spatial]") {
  // Chambers 2 and 3 at 300 kPa bend the 3CA towards chamber 1 (+x); gravity against the bend.
  const ArmRodSpec spec = thesis_3ca_spec(17);
  const ArmRod planar(spec);
  RodLoad pl;
  pl.chamber_pressure_kPa = {{0, 300, 300}};
  pl.gravity_m_s2 = {-9.80665, 0};
  const RodState ps = planar.follow(pl, 8);
  REQUIRE(ps.converged);

  const SpatialRod spatial(spec);
  SpatialRodLoad sl;
  sl.chamber_pressure_kPa = {{0, 300, 300}};
  sl.gravity_m_s2 = {-9.80665, 0, 0};
  const SpatialRodState ss = spatial.follow(sl, 8);
  REQUIRE(ss.converged);
  const Eigen::Vector3d tip = ss.position.back();
  const double planar_deg = planar.tip_rotation(ps, pl) * 180 / kPi;
  INFO("planar " << planar_deg << " deg, tip (" << ps.x.back() << ", " << ps.z.back() << "); spatial "
                 << spatial.tilt_deg(ss, sl, spatial.node_count() - 1) << " deg, tip " << tip.transpose());
  CHECK(planar_deg > 60);
  CHECK(spatial.tilt_deg(ss, sl, spatial.node_count() - 1) == Approx(planar_deg).epsilon(5e-3));
  CHECK(tip.x() == Approx(ps.x.back()).epsilon(5e-3));
  CHECK(tip.z() == Approx(ps.z.back()).epsilon(5e-3));
  CHECK(std::abs(tip.y()) < 1e-6 * std::abs(tip.z()));
  CHECK(spatial.mass_kg() == Approx(planar.mass_kg()).epsilon(1e-12));
}

TEST_CASE("the spatial rod respects the 3CA's threefold symmetry", "[reduced][spatial]") {
  // Chamber 1 alone and chamber 2 alone at 250 kPa: the same bend, turned by 120° about z.
  const SpatialRod rod(thesis_3ca_spec(17));
  std::array<Eigen::Vector3d, 2> tip;
  for (int k = 0; k < 2; ++k) {
    SpatialRodLoad load;
    load.chamber_pressure_kPa = {{0, 0, 0}};
    load.chamber_pressure_kPa[0][k] = 250;
    const SpatialRodState s = rod.follow(load, 6);
    REQUIRE(s.converged);
    tip[k] = s.position.back();
  }
  const Eigen::Vector3d turned = Eigen::AngleAxisd(2 * kPi / 3, Eigen::Vector3d::UnitZ()) * tip[0];
  INFO("chamber 1: " << tip[0].transpose() << "; chamber 2: " << tip[1].transpose());
  CHECK(tip[0].x() < -20);  // away from chamber 1 (+x)
  CHECK((tip[1] - turned).norm() < 2e-3 * tip[0].norm());
}

TEST_CASE("an out-of-plane pose is in global equilibrium", "[reduced][spatial]") {
  // Chambers 2 and 3 bend the 3CA towards +x while a 2 N tip load pulls along +y and gravity acts
  // along −z: a pose out of every plane. The clamp moment must balance the moments of every weight
  // about the clamp at their deformed positions, and the tip's moment must vanish.
  ArmRodSpec spec = thesis_3ca_spec(33);
  const SpatialRod rod(spec);
  SpatialRodLoad load;
  load.chamber_pressure_kPa = {{0, 200, 200}};
  load.gravity_m_s2 = {0, 9.80665, -9.80665};
  load.tip_mass_kg = 0.1;
  const SpatialRodState s = rod.follow(load, 6);
  REQUIRE(s.converged);
  const Eigen::Vector3d tip = s.position.back();
  INFO("tip " << tip.transpose());
  CHECK(tip.x() > 10);
  CHECK(tip.y() > 5);
  const auto& lay = rod.layout();
  Eigen::Vector3d m = (tip - s.position[0]).cross(load.tip_mass_kg * load.gravity_m_s2);
  for (int j = 0; j + 1 < rod.node_count(); ++j)
    m += (0.5 * (s.position[j] + s.position[j + 1]) - s.position[0]).cross(lay.interval_mass[j] * load.gravity_m_s2);
  // The moment of the interval weights at their chords' midpoints: second order in the node spacing.
  CHECK((s.moment.front() - m).norm() < 2e-3 * m.norm());
  CHECK(s.moment.back().norm() < 1e-8 * m.norm());
  // The frames stay orthonormal.
  for (const auto& r : s.frame) CHECK((r.transpose() * r - Eigen::Matrix3d::Identity()).norm() < 1e-10);
}

TEST_CASE("the reduced SPL in one plane poses the arm as the planar rod does", "[reduced][spatial]") {
  // Chambers 2 and 3 of every segment at 150 kPa and gravity along −z: every segment bends
  // towards +x in the x–z plane, where the planar rod (the design optimiser's) applies.
  SplSceneSpec spec;
  spec.tube_material = spec.sheath_material = builtin_material("dragon_skin_30", "test");
  spec.ring_material = spec.connector_material = builtin_material("digital_abs", "test");
  spec.design = thesis_spl_design();
  spec.chamber_pressure_kPa = {0, 150, 150, 0, 150, 150, 0, 150, 150};
  const ReducedSplResult spatial = run_reduced_spl(spec);
  REQUIRE(spatial.final_state.converged);
  REQUIRE(spatial.joints.size() == 6);

  ArmRodSpec arm;
  arm.pieces = spl_rod_pieces(spec.design, spec.connector_material);
  arm.tube = arm.sheath = spec.tube_material;
  arm.rings = spec.ring_material;
  arm.nodes_per_segment = 17;
  const ArmRod planar(arm);
  RodLoad load;
  for (const RodPiece& piece : arm.pieces)
    load.chamber_pressure_kPa.push_back(piece.kind == RodPiece::Kind::connector ? std::array<double, 3>{0, 0, 0}
                                                                                 : std::array<double, 3>{0, 150, 150});
  load.gravity_m_s2 = {0, -9.80665};
  const RodState ps = planar.follow(load, 8);
  REQUIRE(ps.converged);
  // The planar rod's clamp is at its origin, the scene's shoulder at z = L.
  const Eigen::Vector3d tip = spatial.joints.back().pose.position_mm;
  const double length = planar.length_mm();
  INFO("spatial tip " << tip.transpose() << "; planar tip (" << ps.x.back() << ", " << ps.z.back() + length << ")");
  CHECK(tip.x() > 100);
  CHECK(std::abs(tip.x() - ps.x.back()) < 3e-3 * length);
  CHECK(std::abs(tip.z() - (ps.z.back() + length)) < 3e-3 * length);
  CHECK(std::abs(tip.y()) < 1e-6 * length);
  CHECK(spatial.mass_kg == Approx(planar.mass_kg()).epsilon(1e-12));
  // The joints follow the arm from the shoulder: segment 1's top is the shoulder connector's bottom.
  CHECK(spatial.joints.front().pose.position_mm.z() == Approx(length - spec.design.connector_thickness_mm).epsilon(1e-3));
}

TEST_CASE("both rods stop unconverged past their limit, never with a half-integrated shape", "[reduced][spatial]") {
  // A Dragon Skin 10 arm carrying 0.5 kg at its tip, pressurised to 600 kPa: the rods find no
  // equilibrium early on and must stop with a diagnosis. Before the fix, a solve warm-started from a
  // converged state inherited its 'converged' flag, so a failed step came back converged, with the
  // shape integrated only up to the failing section (the spatial rod's tip left at the shoulder).
  ArmRodSpec spec = thesis_3ca_spec(17);
  spec.tube = spec.sheath = builtin_material("dragon_skin_10", "test");
  spec.pieces = spl_rod_pieces(thesis_spl_design(), spec.rings);
  std::vector<std::array<double, 3>> pressures;
  for (const RodPiece& piece : spec.pieces)
    pressures.push_back(piece.kind == RodPiece::Kind::connector ? std::array<double, 3>{0, 0, 0}
                                                                : std::array<double, 3>{0, 600, 600});
  const ArmRod planar(spec);
  RodLoad pl;
  pl.chamber_pressure_kPa = pressures;
  pl.gravity_m_s2 = {0, -9.80665};
  pl.tip_mass_kg = 0.5;
  const RodState ps = planar.follow(pl, 8);
  INFO("planar: " << ps.diagnosis);
  CHECK_FALSE(ps.converged);
  CHECK((ps.diagnosis.find("limit point") != std::string::npos || ps.diagnosis.find("section failure") != std::string::npos));

  const SpatialRod spatial(spec);
  SpatialRodLoad sl;
  sl.chamber_pressure_kPa = pressures;
  sl.gravity_m_s2 = {0, 0, -9.80665};
  sl.tip_mass_kg = 0.5;
  const SpatialRodState ss = spatial.follow(sl, 8);
  INFO("spatial: " << ss.diagnosis);
  CHECK_FALSE(ss.converged);
  CHECK((ss.diagnosis.find("limit point") != std::string::npos || ss.diagnosis.find("section failure") != std::string::npos));
  // What is returned is the last converged state: hanging, its tip a full arm's length below the clamp.
  REQUIRE_FALSE(ss.position.empty());
  CHECK(ss.position.back().z() < -550);
}

TEST_CASE("the reduced 3CA takes the spatial rod where the loads leave the x-z plane", "[reduced][spatial]") {
  TcaSceneSpec spec;
  spec.tube_material = spec.sheath_material = builtin_material("dragon_skin_30", "test");
  spec.ring_material = builtin_material("digital_abs", "test");
  spec.chamber_pressure_kPa = {0, 200, 200};
  const ReducedTcaResult in_plane = run_reduced_tca(spec);
  CHECK_FALSE(in_plane.spatial);
  REQUIRE(in_plane.converged);
  // Chambers 1 and 2 at 200 and 100 kPa: their forces' centroid lies at 30° from chamber 1, so the
  // 3CA bends away from it, towards −150°.
  spec.chamber_pressure_kPa = {200, 100, 0};
  const ReducedTcaResult skew = run_reduced_tca(spec);
  INFO(skew.diagnosis);
  CHECK(skew.spatial);
  REQUIRE(skew.converged);
  const Eigen::Vector3d tip = skew.centreline_mm.back();
  CHECK(std::atan2(tip.y(), tip.x()) * 180 / kPi == Approx(-150).margin(1.5));
  CHECK(skew.bending_deg.back() > 20);
  CHECK(skew.mass_kg == Approx(in_plane.mass_kg).epsilon(1e-12));
}

// Meshes of the 3D actuators against exact volumes: the lone RRA's chamber (a
// frustum) and rings (their volume is the thesis' tori, by construction of the
// equal-area square), the 3CA's outline (convex envelope of three circles) and
// its chambers, full and half models; every element has a positive Jacobian.
#include <catch2/catch.hpp>
#include <cmath>
#include <numeric>
#include <set>

#include "fem/core/angles.hpp"
#include "fem/elements/reference_quadrature.hpp"
#include "fem/forms/chamber_pressure_form.hpp"
#include "fem/mesh/tca_mesher.hpp"

using namespace softarm::fem;

namespace {

double chamber_volume(const Mesh& mesh, int chamber) {
  const LoadState load;
  const ChamberPressureForm form(mesh, chamber, load);
  return form.volume(flattened_positions(mesh));
}

double frustum(double h, double r1, double r2) { return kPi * h / 3 * (r1 * r1 + r1 * r2 + r2 * r2); }

/// Area of the convex envelope of three circles of radius R on a triangle of side d.
double envelope_area(double R, double d) { return kPi * R * R + 3 * d * R + std::sqrt(3.0) / 4 * d * d; }
}  // namespace

TEST_CASE("3D RRA mesh: chamber frustum and ring tori have their exact volumes", "[tca_mesh]") {
  RraDesign d;  // the thesis RRA
  for (int order : {1, 2}) {
    const Mesh mesh = mesh_rra_3d(d, {1, order, false, 0});
    const auto volumes = part_volumes_mm3(mesh);
    CAPTURE(order, mesh.num_nodes(), mesh.num_elements());
    // Quadratic elements put every node on the circles (and stay within 2e-3 of
    // them between nodes); linear ones are exact polygons inscribed in them: N = 8
    // rays at level 1, area factor (N/2π)·sin(2π/N) for every circle.
    const double polygon = order == 2 ? 1.0 : 8 / (2 * kPi) * std::sin(2 * kPi / 8);
    const double tol = order == 2 ? 2e-3 : 1e-9;
    CHECK(volumes[1] == Approx(polygon * ring_volume_mm3(d)).epsilon(tol));
    REQUIRE(mesh.chambers.size() == 1);
    // The cap interfaces may snap onto ring faces: measure the chamber's actual extent.
    double z_lo = 1e9, z_hi = -1e9;
    for (const auto& f : mesh.chambers[0].facets)
      for (int n : f) z_lo = std::min(z_lo, mesh.X(n, 2)), z_hi = std::max(z_hi, mesh.X(n, 2));
    CHECK(chamber_volume(mesh, 0) ==
          Approx(polygon * frustum(z_hi - z_lo, d.chamber_radius(z_lo), d.chamber_radius(z_hi))).epsilon(tol));
  }
}

TEST_CASE("3CA mesh: outline and chamber volumes, full and half models", "[tca_mesh]") {
  TcaDesign d;
  const RraDesign& a = d.actuator;
  const Mesh full = mesh_tca(d, {1, 2, false, 0});
  const auto volumes = part_volumes_mm3(full);
  const double solid = std::accumulate(volumes.begin(), volumes.end(), 0.0);
  double cavities = 0;
  for (int c = 0; c < 3; ++c) cavities += chamber_volume(full, c);
  // The outline area is quadratic in z: Simpson's rule is exact.
  const auto area = [&](double z) {
    return envelope_area(a.outer_radius(z) + d.sheath_thickness_mm, 2 * a.outer_radius(z) + d.actuator_spacing_mm);
  };
  const double l = a.length_mm;
  const double outline = l / 6 * (area(0) + 4 * area(l / 2) + area(l));
  CHECK(solid + cavities == Approx(outline).epsilon(1e-3));
  CHECK(chamber_volume(full, 1) == Approx(chamber_volume(full, 0)).epsilon(1e-9));
  CHECK(chamber_volume(full, 2) == Approx(chamber_volume(full, 0)).epsilon(1e-9));

  const Mesh half = mesh_tca(d, {1, 2, true, 0});
  CHECK(half.num_elements() * 2 == full.num_elements());
  // Chamber 1 is cut by the symmetry plane: its open facets still give half its volume.
  CHECK(chamber_volume(half, 0) == Approx(chamber_volume(full, 0) / 2).epsilon(1e-9));
  CHECK(chamber_volume(half, 1) == Approx(chamber_volume(full, 1)).epsilon(1e-9));
  CHECK(half.chambers[2].facets.empty());
  REQUIRE(half.node_sets.count("symmetry"));
  for (int n : half.node_sets.at("symmetry")) CHECK(std::abs(half.X(n, 1)) < 1e-9);
}

TEST_CASE("3CA mesh with a centre hole: solid, chambers and bore fill the outline", "[tca_mesh]") {
  TcaDesign d;
  d.centre_hole_diameter_mm = 4;
  const RraDesign& a = d.actuator;
  for (int level : {1, 2}) {
    const Mesh mesh = mesh_tca(d, {level, 2, false, 0});
    const auto v = part_volumes_mm3(mesh);
    double total = std::accumulate(v.begin(), v.end(), 0.0) + kPi * 4 * a.length_mm;
    for (int c = 0; c < 3; ++c) total += chamber_volume(mesh, c);
    const auto area = [&](double z) {
      return envelope_area(a.outer_radius(z) + d.sheath_thickness_mm, 2 * a.outer_radius(z) + d.actuator_spacing_mm);
    };
    const double l = a.length_mm;
    CAPTURE(level);
    CHECK(total == Approx(l / 6 * (area(0) + 4 * area(l / 2) + area(l))).epsilon(1e-3));
  }
}

TEST_CASE("3CA serendipity mesh: the Hex27 mesh without face and body centres", "[tca_mesh]") {
  // Hex20 keeps every edge of the Hex27 mesh, so the mesh is the same body: part
  // and chamber volumes agree to the quadratic geometry's interpolation error
  // (the face centres that Hex27 puts on the circles are interpolated instead,
  // 2e-3 as against the exact volumes above), the half model still halves, and
  // ~45 % of the nodes go.
  TcaDesign d;
  SolidMeshOptions options{1, 2, false, 0};
  const Mesh hex27 = mesh_tca(d, options);
  options.serendipity = true;
  const Mesh hex20 = mesh_tca(d, options);
  REQUIRE(hex20.nodes_per_element == 20);
  CHECK(hex20.num_elements() == hex27.num_elements());
  CAPTURE(hex27.num_nodes(), hex20.num_nodes());
  CHECK(hex20.num_nodes() < 0.6 * hex27.num_nodes());
  const auto v27 = part_volumes_mm3(hex27), v20 = part_volumes_mm3(hex20);
  for (std::size_t p = 0; p < v27.size(); ++p) CHECK(v20[p] == Approx(v27[p]).epsilon(2e-3));
  for (int c = 0; c < 3; ++c) CHECK(chamber_volume(hex20, c) == Approx(chamber_volume(hex27, c)).epsilon(2e-3));
  for (const auto& [name, nodes] : hex27.node_sets) CHECK(hex20.node_sets.count(name) == 1);
  options.half = true;
  const Mesh half = mesh_tca(d, options);
  CHECK(chamber_volume(half, 0) == Approx(chamber_volume(hex20, 0) / 2).epsilon(1e-9));
  CHECK(chamber_volume(half, 1) == Approx(chamber_volume(hex20, 1)).epsilon(1e-9));
}

TEST_CASE("3CA mesh refined along the axis alone: twice the layers, the same cross-section and volumes",
          "[tca_mesh]") {
  // mesh.axial_level splits every element layer and nothing else: the body and its
  // chambers are unchanged (every layer boundary is kept and the axial node positions
  // are exact), each cross-section keeps its node count, and a level given twice
  // over (axial_level = level) is the uniform mesh.
  TcaDesign d;
  SolidMeshOptions options{1, 2, false, 0};
  const Mesh uniform = mesh_tca(d, options);
  options.axial_level = 1;
  CHECK(mesh_tca(d, options).num_nodes() == uniform.num_nodes());
  options.axial_level = 2;
  const Mesh axial = mesh_tca(d, options);
  CHECK(axial.num_elements() == 2 * uniform.num_elements());
  const auto bottom = [](const Mesh& m) { return m.node_sets.at("bottom").size(); };
  CHECK(bottom(axial) == bottom(uniform));
  // Hex27: a mesh of n layers has 2n + 1 node planes z = const, so doubling n adds 2n of them.
  const auto planes = [](const Mesh& m) {
    std::set<long long> z;
    for (int n = 0; n < m.num_nodes(); ++n) z.insert(std::llround(m.X(n, 2) * 1e6));
    return z.size();
  };
  CHECK(planes(axial) == 2 * planes(uniform) - 1);
  const auto v1 = part_volumes_mm3(uniform), v2 = part_volumes_mm3(axial);
  for (std::size_t p = 0; p < v1.size(); ++p) CHECK(v2[p] == Approx(v1[p]).epsilon(1e-9));
  for (int c = 0; c < 3; ++c) CHECK(chamber_volume(axial, c) == Approx(chamber_volume(uniform, c)).epsilon(1e-9));
}

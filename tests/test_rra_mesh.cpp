// RRA design input, the axisymmetric RRA mesher, the structured test mesher
// and the VTU writer (spec §1: geometry "our definition").
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numbers>
#include <numeric>
#include <set>
#include <sstream>
#include <unistd.h>

#include "fem/core/input_error.hpp"
#include "fem/core/json_reader.hpp"
#include "fem/elements/axisymmetric_quad.hpp"
#include "fem/io/vtu_writer.hpp"
#include "fem/mesh/quadratic_mesh.hpp"
#include "fem/mesh/rra_design.hpp"
#include "fem/mesh/rra_mesher.hpp"
#include "fem/mesh/structured_mesh.hpp"
#include "support/text_file.hpp"

using namespace softarm::fem;

namespace {

constexpr double pi = std::numbers::pi;

RraDesign thesis_rra() {  // Table 7, in physical units
  RraDesign d;
  d.length_mm = 160;
  d.bottom_radius_mm = 9;
  d.top_radius_mm = 12;
  d.wall_thickness_mm = 0.466 * 9;
  d.end_cap_thickness_mm = 0.25 * 9;
  d.ring_count = 30;
  d.ring_diameter_mm = 0.4 * 160.0 / 30;
  return d;
}

/// The thesis RRA and the extremes of the thesis' parameter studies (spec §5).
std::vector<std::pair<std::string, RraDesign>> test_designs() {
  std::vector<std::pair<std::string, RraDesign>> designs{{"thesis", thesis_rra()}};
  auto variant = [&](const std::string& name, const std::function<void(RraDesign&)>& change) {
    RraDesign d = thesis_rra();
    change(d);
    designs.emplace_back(name, d);
  };
  variant("no rings", [](RraDesign& d) { d.ring_count = 0; d.ring_diameter_mm = 0; });
  variant("ring thickness 0.95", [](RraDesign& d) { d.ring_diameter_mm = 0.95 * d.pitch(); });
  variant("ring count 0.625 (50 rings)", [](RraDesign& d) { d.ring_count = 50; d.ring_diameter_mm = 0.4 * d.pitch(); });
  variant("cap 0.05", [](RraDesign& d) { d.end_cap_thickness_mm = 0.05 * 9; });
  variant("cap 0.75", [](RraDesign& d) { d.end_cap_thickness_mm = 0.75 * 9; });
  variant("wall 0.733", [](RraDesign& d) { d.wall_thickness_mm = 0.733 * 9; });
  variant("wall 0.2", [](RraDesign& d) { d.wall_thickness_mm = 0.2 * 9; });
  variant("reverse taper", [](RraDesign& d) { std::swap(d.bottom_radius_mm, d.top_radius_mm); });
  return designs;
}

/// Wall 0.2 with rings 0.67: the grooves leave 0.7 % of the wall under them.
RraDesign deep_groove_rra() {
  RraDesign d = thesis_rra();
  d.wall_thickness_mm = 0.2 * 9;
  d.ring_diameter_mm = 0.67 * d.pitch();
  return d;
}

Eigen::Vector2d node(const Mesh& m, int n) { return m.X.row(n).transpose(); }

/// Calls f(r, det J) at the 2×2 Gauss points of element e (weights 1).
template <class F>
void at_gauss_points(const Mesh& m, int e, F f) {
  const int* n = m.element(e);
  const Eigen::Vector2d p0 = node(m, n[0]), p1 = node(m, n[1]), p2 = node(m, n[2]), p3 = node(m, n[3]);
  const double g = 1 / std::sqrt(3.0);
  for (double xi : {-g, g})
    for (double eta : {-g, g}) {
      const Eigen::Vector2d d_xi = 0.25 * ((1 - eta) * (p1 - p0) + (1 + eta) * (p2 - p3));
      const Eigen::Vector2d d_eta = 0.25 * ((1 - xi) * (p3 - p0) + (1 + xi) * (p2 - p1));
      const double r = 0.25 * ((1 - xi) * (1 - eta) * p0.x() + (1 + xi) * (1 - eta) * p1.x() +
                               (1 + xi) * (1 + eta) * p2.x() + (1 - xi) * (1 + eta) * p3.x());
      f(r, d_xi.x() * d_eta.y() - d_xi.y() * d_eta.x());
    }
}

double min_jacobian(const Mesh& m) {
  double lowest = 1e300;
  for (int e = 0; e < m.num_elements(); ++e) at_gauss_points(m, e, [&](double, double det) { lowest = std::min(lowest, det); });
  return lowest;
}

/// 2π ∫ r dA of the elements accepted by `keep` (exact for bilinear quads with 2×2 Gauss).
double volume(const Mesh& m, const std::function<bool(int)>& keep) {
  double v = 0;
  for (int e = 0; e < m.num_elements(); ++e)
    if (keep(e)) at_gauss_points(m, e, [&](double r, double det) { v += 2 * pi * r * det; });
  return v;
}
double part_volume(const Mesh& m, int part) { return volume(m, [&](int e) { return m.part[e] == part; }); }

double frustum(double height, double r1, double r2) { return pi * height * (r1 * r1 + r1 * r2 + r2 * r2) / 3; }

double exact_tube_volume(const RraDesign& d) { return tube_volume_mm3(d); }

/// Largest relative error over the rings of the ring volumes 2π² R_k ρ².
double worst_ring_volume_error(const Mesh& m, const RraDesign& d) {
  std::vector<double> v(static_cast<std::size_t>(d.ring_count), 0.0);
  for (int e = 0; e < m.num_elements(); ++e) {
    if (m.part[e] != 1) continue;
    double z = 0;
    for (int a = 0; a < 4; ++a) z += 0.25 * m.X(m.element(e)[a], 1);
    const auto k = static_cast<std::size_t>(z / d.pitch());
    at_gauss_points(m, e, [&](double r, double det) { v[k] += 2 * pi * r * det; });
  }
  double worst = 0;
  const double rho = d.ring_section_radius();
  for (int k = 1; k <= d.ring_count; ++k) {
    const double exact = 2 * pi * pi * d.outer_radius(d.ring_centre_z(k)) * rho * rho;
    worst = std::max(worst, std::abs(v[static_cast<std::size_t>(k - 1)] - exact) / exact);
  }
  return worst;
}

/// Volume enclosed by an axisymmetric chamber chain (mesh.hpp's formula), and a
/// check that its edges form one chain from the axis back to the axis.
double chain_volume(const Mesh& m, const Chamber& c) {
  double v = 0;
  for (std::size_t i = 0; i < c.facets.size(); ++i) {
    const auto& f = c.facets[i];
    REQUIRE(f.size() == 2);
    if (i > 0) REQUIRE(c.facets[i - 1][1] == f[0]);
    const double ra = m.X(f[0], 0), za = m.X(f[0], 1), rb = m.X(f[1], 0), zb = m.X(f[1], 1);
    v += pi * (zb - za) * (ra * ra + ra * rb + rb * rb) / 3;
  }
  REQUIRE(m.X(c.facets.front()[0], 0) == 0.0);
  REQUIRE(m.X(c.facets.back()[1], 0) == 0.0);
  return v;
}

/// Number of connected pieces of the mesh (elements linked through shared nodes).
int connected_pieces(const Mesh& m) {
  std::vector<int> parent(static_cast<std::size_t>(m.num_nodes()));
  std::iota(parent.begin(), parent.end(), 0);
  std::function<int(int)> root = [&](int n) { return parent[n] == n ? n : parent[n] = root(parent[n]); };
  for (int e = 0; e < m.num_elements(); ++e)
    for (int a = 1; a < 4; ++a) parent[root(m.element(e)[a])] = root(m.element(e)[0]);
  std::set<int> roots;
  for (int e = 0; e < m.num_elements(); ++e) roots.insert(root(m.element(e)[0]));
  return static_cast<int>(roots.size());
}

std::set<int> part_nodes(const Mesh& m, int part) {
  std::set<int> nodes;
  for (int e = 0; e < m.num_elements(); ++e)
    if (m.part[e] == part) nodes.insert(m.element(e), m.element(e) + 4);
  return nodes;
}

nlohmann::json thesis_geometry_json() {
  return nlohmann::json::parse(R"({
    "length_mm": 160, "bottom_radius_mm": 9, "top_radius_mm": 12,
    "wall_thickness_normalised": 0.466, "end_cap_thickness_normalised": 0.25,
    "ring_count_normalised": 0.375, "ring_reference_diameter_mm": 2,
    "ring_thickness_normalised": 0.4, "fixed_end": "top" })");
}

RraDesign read_geometry(const nlohmann::json& j) {
  JsonReader reader(j, "geometry");
  return read_rra_design(reader);
}

/// The InputError message for `j`, or "" when it reads fine.
std::string input_error(const nlohmann::json& j) {
  try {
    read_geometry(j);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

using softarm::test::read_text;

/// The whitespace-separated values of the DataArray named `name` in a .vtu text.
std::vector<double> data_array(const std::string& text, const std::string& name) {
  const auto tag = text.find("Name=\"" + name + "\"");
  REQUIRE(tag != std::string::npos);
  const auto begin = text.find('>', tag) + 1, end = text.find("</DataArray>", begin);
  std::istringstream values(text.substr(begin, end - begin));
  std::vector<double> out;
  for (double x; values >> x;) out.push_back(x);
  return out;
}

long count_of(const std::string& text, const std::string& what) {
  long n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace

TEST_CASE("RRA design: the thesis' normalised values give 30 rings of 2.1333 mm", "[rra_mesh]") {
  const RraDesign d = read_geometry(thesis_geometry_json());
  CHECK(d.ring_count == 30);
  CHECK(d.ring_diameter_mm == Approx(2.1333).epsilon(1e-4));
  CHECK(d.wall_thickness_mm == Approx(0.466 * 9));
  CHECK(d.end_cap_thickness_mm == Approx(2.25));
  CHECK(d.fixed_end == RraDesign::FixedEnd::top);
  CHECK(d.pitch() == Approx(160.0 / 30));
  CHECK(d.ring_centre_z(1) == Approx(80.0 / 30));

  const auto j = to_json(d);
  CHECK(j["normalised"]["wall_thickness_normalised"].get<double>() == Approx(0.466));
  CHECK(j["normalised"]["ring_count_normalised"].get<double>() == Approx(0.375));
  CHECK(j["normalised"]["ring_thickness_normalised"].get<double>() == Approx(0.4));
  const RraDesign again = read_geometry(j["physical"]);  // "physical" is itself a valid input
  CHECK(again.ring_count == 30);
  CHECK(again.ring_diameter_mm == Approx(d.ring_diameter_mm));
  CHECK(again.wall_thickness_mm == Approx(d.wall_thickness_mm));
}

TEST_CASE("RRA design: bad input names the field", "[rra_mesh]") {
  auto with = [](const std::string& key, const nlohmann::json& value) {
    auto j = thesis_geometry_json();
    j[key] = value;
    return j;
  };
  auto without = [](nlohmann::json j, const std::string& key) {
    j.erase(key);
    return j;
  };
  CHECK_THAT(input_error(with("length_mm", -160)), Catch::Contains("geometry.length_mm"));
  CHECK_THAT(input_error(with("wall_thickness_normalised", 1.0)),
             Catch::Contains("geometry.wall_thickness_normalised") && Catch::Contains("no chamber"));
  CHECK_THAT(input_error(with("top_radius_mm", 3)), Catch::Contains("geometry.wall_thickness_normalised"));
  CHECK_THAT(input_error(with("end_cap_thickness_normalised", 9)), Catch::Contains("geometry.end_cap_thickness_normalised"));
  CHECK_THAT(input_error(with("ring_thickness_normalised", 1.0)),
             Catch::Contains("geometry.ring_thickness_normalised") && Catch::Contains("pitch"));
  auto deep_groove = without(with("ring_diameter_mm", 9.0), "ring_thickness_normalised");  // 30 rings: pitch 5.33
  CHECK_THAT(input_error(deep_groove), Catch::Contains("geometry.ring_diameter_mm"));
  deep_groove = without(with("ring_count", 10), "ring_count_normalised");  // pitch 16 mm: d_r = 6.4 fits axially
  deep_groove["ring_thickness_normalised"] = 0.55;                          // d_r/2 = 4.4 mm > t_w = 4.19 mm
  CHECK_THAT(input_error(deep_groove), Catch::Contains("geometry.ring_thickness_normalised") && Catch::Contains("groove"));
  CHECK_THAT(input_error(with("wall_thickness_mm", 4)), Catch::Contains("geometry.wall_thickness_mm") &&
                                                            Catch::Contains("exactly one"));
  CHECK_THAT(input_error(without(thesis_geometry_json(), "end_cap_thickness_normalised")),
             Catch::Contains("geometry.end_cap_thickness_mm"));
  CHECK_THAT(input_error(with("lenght_mm", 160)), Catch::Contains("geometry.lenght_mm") && Catch::Contains("unknown key"));
  CHECK_THAT(input_error(with("fixed_end", "left")), Catch::Contains("geometry.fixed_end"));
  CHECK(input_error(with("ring_count_normalised", 0.0)) == "");  // a plain tube: the ring size is ignored

  RraDesign d = thesis_rra();
  d.wall_thickness_mm = 9.5;
  CHECK_THROWS_WITH(validate(d), Catch::Contains("geometry.wall_thickness_mm"));
  d = thesis_rra();
  d.bottom_radius_mm = 14;  // reverse taper: valid
  CHECK_NOTHROW(validate(d));
}

TEST_CASE("RRA mesh: every element has a positive Jacobian at its Gauss points", "[rra_mesh]") {
  auto designs = test_designs();
  designs.emplace_back("deep groove", deep_groove_rra());
  for (const auto& [name, design] : designs)
    for (int level = 1; level <= 3; ++level) {
      INFO(name << ", level " << level);
      const Mesh m = mesh_rra(design, level);
      CHECK(m.dim == 2);
      CHECK(m.nodes_per_element == 4);
      CHECK(m.part.size() == static_cast<std::size_t>(m.num_elements()));
      CHECK(min_jacobian(m) > 0);
    }
  const Mesh level1 = mesh_rra(thesis_rra(), 1);
  CHECK(level1.num_elements() > 300);
  CHECK(level1.num_elements() < 1500);
}

TEST_CASE("RRA mesh: cap faces anywhere along a pitch, also over deep grooves", "[rra_mesh]") {
  // The cap's inner face may fall between grooves, next to a lip (where the
  // lip's line takes it over) or inside a groove (where, over a deep groove, a
  // groove node is pinned above it): every case must give a valid mesh.
  for (const RraDesign& base : {thesis_rra(), deep_groove_rra()})
    for (int step = 0; step < 24; ++step) {
      RraDesign d = base;
      d.end_cap_thickness_mm = 0.3 + d.pitch() * step / 24.0;
      for (int level : {1, 2}) {
        INFO("cap " << d.end_cap_thickness_mm << " mm, wall " << d.wall_thickness_mm << " mm, level " << level);
        const Mesh m = mesh_rra(d, level);
        CHECK(min_jacobian(m) > 0);
        const double t_c = d.end_cap_thickness_mm;
        const double exact = frustum(d.length_mm - 2 * t_c, d.chamber_radius(t_c), d.chamber_radius(d.length_mm - t_c));
        CHECK(chain_volume(m, m.chambers[0]) == Approx(exact).epsilon(1e-12));
        CHECK(part_volume(m, 0) == Approx(exact_tube_volume(d)).epsilon(0.02));
      }
    }
  // Found by random search: the top cap face ends 0.17 mm off the bottom of a
  // groove that leaves 0.0036 mm of wall; a straight line to the nearest groove
  // node would shear that wall inside out.
  RraDesign d;
  d.length_mm = 187.457;
  d.bottom_radius_mm = 5.57334;
  d.top_radius_mm = 5.97139;
  d.wall_thickness_mm = 1.36443;
  d.end_cap_thickness_mm = 2.75174;
  d.ring_count = 32;
  d.ring_diameter_mm = 2.72159;
  for (int level : {1, 2, 3}) CHECK(min_jacobian(mesh_rra(d, level)) > 0);
}

TEST_CASE("RRA mesh: tube and ring volumes converge at second order", "[rra_mesh]") {
  for (const auto& d : {test_designs()[0].second, test_designs()[2].second}) {
    const double tube = exact_tube_volume(d);
    std::vector<double> tube_error, ring_error;
    for (int level = 1; level <= 3; ++level) {
      const Mesh m = mesh_rra(d, level);
      tube_error.push_back(std::abs(part_volume(m, 0) - tube) / tube);
      ring_error.push_back(worst_ring_volume_error(m, d));
    }
    for (std::size_t i = 1; i < tube_error.size(); ++i) {
      CHECK(std::log2(tube_error[i - 1] / tube_error[i]) == Approx(2).margin(0.1));
      CHECK(std::log2(ring_error[i - 1] / ring_error[i]) == Approx(2).margin(0.1));
    }
    CHECK(tube_error.back() < 5e-3);
  }
  // Without rings the geometry is polygonal, so the mesh is exact.
  const auto plain = test_designs()[1].second;
  CHECK(part_volume(mesh_rra(plain, 1), 0) == Approx(exact_tube_volume(plain)).epsilon(1e-12));
}

TEST_CASE("RRA mesh: the chamber chain encloses the frustum exactly", "[rra_mesh]") {
  for (const auto& [name, d] : test_designs())
    for (int level : {1, 2}) {
      INFO(name << ", level " << level);
      const Mesh m = mesh_rra(d, level);
      REQUIRE(m.chambers.size() == 1);
      CHECK(m.chambers[0].id == 1);
      CHECK(m.chambers[0].name == "chamber");
      const double t_c = d.end_cap_thickness_mm;
      const double exact = frustum(d.length_mm - 2 * t_c, d.chamber_radius(t_c), d.chamber_radius(d.length_mm - t_c));
      CHECK(chain_volume(m, m.chambers[0]) == Approx(exact).epsilon(1e-12));
    }
}

TEST_CASE("RRA mesh: rings are bonded to the tube through the groove nodes", "[rra_mesh]") {
  const RraDesign d = thesis_rra();
  for (int level : {1, 2}) {
    const Mesh m = mesh_rra(d, level);
    const auto sizes = rra_mesh_sizes(d, level);
    CHECK(connected_pieces(m) == 1);
    REQUIRE(m.part_names == std::vector<std::string>{"tube", "rings"});
    const auto tube = part_nodes(m, 0), rings = part_nodes(m, 1);
    std::vector<int> shared;
    std::set_intersection(tube.begin(), tube.end(), rings.begin(), rings.end(), std::back_inserter(shared));
    CHECK(shared.size() == static_cast<std::size_t>(d.ring_count * (sizes.groove_segments + 1)));
    const double rho = d.ring_section_radius();
    for (int n : shared) {  // every shared node lies on a groove
      const double z = m.X(n, 1);
      const int k = static_cast<int>(z / d.pitch()) + 1;
      const double R = d.outer_radius(d.ring_centre_z(k));
      CHECK(std::hypot(m.X(n, 0) - R, z - d.ring_centre_z(k)) == Approx(rho).epsilon(1e-12));
      CHECK(m.X(n, 0) <= R + 1e-12);
    }
  }
  const Mesh plain = mesh_rra(test_designs()[1].second, 1);
  CHECK(part_nodes(plain, 1).empty());
}

TEST_CASE("RRA mesh: node sets", "[rra_mesh]") {
  RraDesign d = thesis_rra();
  for (auto fixed : {RraDesign::FixedEnd::top, RraDesign::FixedEnd::bottom}) {
    d.fixed_end = fixed;
    const Mesh m = mesh_rra(d, 2);
    const auto sizes = rra_mesh_sizes(d, 2);
    const auto& sets = m.node_sets;
    auto count_where = [&](const std::function<bool(int)>& test) {
      int n = 0;
      for (int i = 0; i < m.num_nodes(); ++i) n += test(i);
      return n;
    };
    const double l = d.length_mm;
    CHECK(sets.at("bottom").size() == static_cast<std::size_t>(sizes.core_layers_bottom + sizes.wall_layers + 1));
    CHECK(sets.at("top").size() == static_cast<std::size_t>(sizes.core_layers_top + sizes.wall_layers + 1));
    CHECK(sets.at("bottom").size() == static_cast<std::size_t>(count_where([&](int n) { return m.X(n, 1) == 0.0; })));
    CHECK(sets.at("top").size() == static_cast<std::size_t>(count_where([&](int n) { return m.X(n, 1) == l; })));
    CHECK(sets.at("axis").size() == static_cast<std::size_t>(count_where([&](int n) { return m.X(n, 0) == 0.0; })));
    for (int n : sets.at("axis")) CHECK(m.X(n, 0) == 0.0);
    for (int n : sets.at("bottom")) CHECK(m.X(n, 1) == 0.0);
    for (int n : sets.at("top")) CHECK(m.X(n, 1) == l);
    const bool top_fixed = fixed == RraDesign::FixedEnd::top;
    CHECK(sets.at("fixed_end") == sets.at(top_fixed ? "top" : "bottom"));
    REQUIRE(sets.at("free_end_centre").size() == 1);
    const int centre = sets.at("free_end_centre")[0];
    CHECK(m.X(centre, 0) == 0.0);
    CHECK(m.X(centre, 1) == (top_fixed ? 0.0 : l));
  }
}

TEST_CASE("RRA mesh: element counts grow fourfold per level", "[rra_mesh]") {
  const RraDesign d = thesis_rra();
  const Mesh l1 = mesh_rra(d, 1), l2 = mesh_rra(d, 2);
  CHECK(l2.num_elements() == 4 * l1.num_elements());
  CHECK_THROWS_AS(mesh_rra(d, 0), std::invalid_argument);
}

TEST_CASE("rectangle_mesh: counts, node sets, chamber and distortion", "[rra_mesh]") {
  const Mesh m = rectangle_mesh(2, 5, -1, 3, 3, 4, 0.8);
  CHECK(m.num_nodes() == 4 * 5);
  CHECK(m.num_elements() == 12);
  CHECK(m.part_names == std::vector<std::string>{"solid"});
  CHECK(min_jacobian(m) > 0);
  CHECK(m.node_sets.at("inner").size() == 5);
  CHECK(m.node_sets.at("outer").size() == 5);
  CHECK(m.node_sets.at("bottom").size() == 4);
  CHECK(m.node_sets.at("top").size() == 4);
  CHECK(m.node_sets.at("boundary").size() == 14);
  CHECK(m.node_sets.count("axis") == 0);
  CHECK(volume(m, [](int) { return true; }) == Approx(pi * (25 - 4) * 4));  // boundary nodes do not move
  REQUIRE(m.chambers.size() == 1);
  double v = 0;
  for (const auto& f : m.chambers[0].facets) {
    CHECK(m.X(f[1], 1) > m.X(f[0], 1));
    v += pi * (m.X(f[1], 1) - m.X(f[0], 1)) * 3 * 4 / 3;
  }
  CHECK(v == Approx(pi * 4 * 4));

  const Mesh solid = rectangle_mesh(0, 1, 0, 1, 2, 2);
  CHECK(solid.node_sets.at("axis") == solid.node_sets.at("inner"));
  CHECK(solid.chambers.empty());
  CHECK_THROWS_AS(rectangle_mesh(1, 1, 0, 1, 2, 2), std::invalid_argument);
}

TEST_CASE("write_vtu: well-formed ParaView file with the right counts", "[rra_mesh]") {
  namespace fs = std::filesystem;
  const fs::path folder = fs::temp_directory_path() / ("softarm_vtu_test_" + std::to_string(::getpid()));
  fs::remove_all(folder);
  const Mesh m = mesh_rra(thesis_rra(), 1);
  Eigen::MatrixXd x = m.X;
  x.col(1) *= 1.01;  // a stretched configuration
  NamedField pressure{"pressure", 1, std::vector<double>(static_cast<std::size_t>(m.num_nodes()), 0.2)};
  NamedField stress{"stress", 4, std::vector<double>(static_cast<std::size_t>(m.num_elements()) * 4, 1.5)};
  const fs::path file = folder / "rra.vtu";
  write_vtu(file.string(), m, x, {pressure}, {stress});

  const std::string text = read_text(file);
  CHECK(text.rfind("<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\"", 0) == 0);
  CHECK(text.find("</VTKFile>") == text.size() - std::string("</VTKFile>\n").size());
  CHECK(count_of(text, "<DataArray") == count_of(text, "</DataArray>"));
  CHECK(count_of(text, "<DataArray") == 8);
  CHECK_THAT(text, Catch::Contains("NumberOfPoints=\"" + std::to_string(m.num_nodes()) + "\" NumberOfCells=\"" +
                                   std::to_string(m.num_elements()) + "\""));
  const auto connectivity = data_array(text, "connectivity");
  CHECK(connectivity.size() == m.connectivity.size());
  CHECK(connectivity[5] == m.connectivity[5]);
  const auto offsets = data_array(text, "offsets"), types = data_array(text, "types");
  CHECK(offsets.size() == static_cast<std::size_t>(m.num_elements()));
  CHECK(offsets.back() == 4.0 * m.num_elements());
  CHECK(std::count(types.begin(), types.end(), 9.0) == m.num_elements());
  const auto parts = data_array(text, "part");
  CHECK(std::count(parts.begin(), parts.end(), 1.0) == std::count(m.part.begin(), m.part.end(), 1));
  const auto u = data_array(text, "displacement");
  REQUIRE(u.size() == 3 * static_cast<std::size_t>(m.num_nodes()));
  const int top = m.node_sets.at("top")[0];
  CHECK(u[3 * top + 1] == 0.0);                   // y = 0: the axisymmetric plane is x–z
  CHECK(u[3 * top + 2] == Approx(0.01 * 160.0));  // z displacement
  CHECK(data_array(text, "stress").size() == 4 * static_cast<std::size_t>(m.num_elements()));
  for (const auto& entry : fs::directory_iterator(folder)) CHECK(entry.path().filename() == "rra.vtu");  // no temp file left

  NamedField wrong{"pressure", 1, {1.0, 2.0}};
  CHECK_THROWS_AS(write_vtu(file.string(), m, x, {wrong}, {}), std::invalid_argument);
  NamedField reserved{"part", 1, std::vector<double>(static_cast<std::size_t>(m.num_elements()), 0.0)};
  CHECK_THROWS_AS(write_vtu(file.string(), m, x, {}, {reserved}), std::invalid_argument);

  Mesh cube;  // one hexahedron: dim 3 is written as VTK_HEXAHEDRON
  cube.dim = 3;
  cube.nodes_per_element = 8;
  cube.X.resize(8, 3);
  cube.X << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1;
  cube.connectivity = {0, 1, 2, 3, 4, 5, 6, 7};
  cube.part = {0};
  cube.part_names = {"block"};
  write_vtu((folder / "cube.vtu").string(), cube, cube.X, {}, {});
  CHECK(data_array(read_text(folder / "cube.vtu"), "types") == std::vector<double>{12.0});
  // Quadratic elements: VTK_BIQUADRATIC_QUAD (28) and VTK_TRIQUADRATIC_HEXAHEDRON (29), all nodes written.
  const Mesh q2 = to_quadratic(m);
  write_vtu((folder / "q2.vtu").string(), q2, q2.X, {}, {});
  const auto q2_types = data_array(read_text(folder / "q2.vtu"), "types");
  CHECK(std::count(q2_types.begin(), q2_types.end(), 28.0) == q2.num_elements());
  CHECK(data_array(read_text(folder / "q2.vtu"), "offsets").back() == 9.0 * q2.num_elements());
  const Mesh hex27 = to_quadratic_3d(cube);
  write_vtu((folder / "hex27.vtu").string(), hex27, hex27.X, {}, {});
  CHECK(data_array(read_text(folder / "hex27.vtu"), "types") == std::vector<double>{29.0});
  CHECK(data_array(read_text(folder / "hex27.vtu"), "connectivity").size() == 27);
  fs::remove_all(folder);
}

TEST_CASE("write_polyline_vtu: a rod's centrelines as poly-lines with a value per line", "[rra_mesh]") {
  namespace fs = std::filesystem;
  const fs::path file = fs::temp_directory_path() / ("softarm_polyline_" + std::to_string(::getpid()) + ".vtu");
  const std::vector<std::vector<Eigen::Vector3d>> lines = {
      {{0, 0, 100}, {0, 0, 50}, {0, 0, 0}},                        // at rest, hanging from z = 100
      {{0, 0, 100}, {5, 0, 52}, {18, 1, 6}, {30, 2, -30}}};        // bent: another node count
  write_polyline_vtu(file.string(), lines, {"pressure_kPa", 1, {0.0, 206.8}});
  const std::string text = read_text(file);
  CHECK_THAT(text, Catch::Contains("NumberOfPoints=\"7\" NumberOfCells=\"2\""));
  CHECK(data_array(text, "types") == std::vector<double>{4.0, 4.0});  // VTK_POLY_LINE
  CHECK(data_array(text, "offsets") == std::vector<double>{3.0, 7.0});
  CHECK(data_array(text, "connectivity") == std::vector<double>{0, 1, 2, 3, 4, 5, 6});
  CHECK(data_array(text, "pressure_kPa") == std::vector<double>{0.0, 206.8});
  const auto points_at = text.find('>', text.find("<DataArray", text.find("<Points>"))) + 1;
  std::istringstream points(text.substr(points_at, text.find("</DataArray>", points_at) - points_at));
  std::vector<double> xyz;
  for (double v; points >> v;) xyz.push_back(v);
  REQUIRE(xyz.size() == 21);
  CHECK(xyz[18] == 30.0);  // the bent line's tip, written exactly
  CHECK(xyz[20] == -30.0);
  CHECK_THROWS_AS(write_polyline_vtu(file.string(), lines, {"pressure_kPa", 1, {0.0}}), std::invalid_argument);
  fs::remove(file);
}

TEST_CASE("RRA Q2 mesh: mid-edge nodes on the ring circles make the ring volume O(h^4)", "[rra_mesh]") {
  // Volume of revolution of the rings with the 9-node map (3×3 Gauss), against
  // the exact tori. Polygonal (chord) rings lose ~10 % at level 1 (see above);
  // curved Q2 edges leave only the O(h⁴) error of the quadratic arc.
  const RraDesign d = thesis_rra();
  const double rho = d.ring_section_radius();
  double exact = 0.0;
  for (int k = 1; k <= d.ring_count; ++k) exact += 2 * pi * pi * d.outer_radius(d.ring_centre_z(k)) * rho * rho;
  std::vector<double> errors;
  for (int level : {1, 2}) {
    const Mesh m = mesh_rra_quadratic(d, level);
    double v = 0.0;
    for (int e = 0; e < m.num_elements(); ++e) {
      if (m.part[e] != m.part_index("rings")) continue;
      axisym::NodalCoordinates<axisym::Quad9> X;
      for (int a = 0; a < 9; ++a) X.row(a) = m.X.row(m.element(e)[a]);
      std::array<axisym::ReferencePoint<axisym::Quad9>, 9> points;
      REQUIRE(axisym::reference_points<axisym::Quad9>(X, points));
      for (const auto& p : points) v += p.dV;
    }
    errors.push_back(std::abs(v - exact) / exact);
    INFO("level " << level << ": ring volume error " << errors.back());
    CHECK(errors.back() < 2e-3);
  }
  CHECK(errors[0] / errors[1] > 8.0);  // ≥ third order (O(h⁴) expected: ratio 16)
}


// ---- Square ring section (RraDesign::RingSection::square): the equal-area
// square of side a = d_r·√π/2 centred on the outer surface, half sunk in a
// rectangular groove. Its geometry is polygonal, so the mesh is exact.
namespace {

RraDesign squared(RraDesign d) {
  d.ring_section = RraDesign::RingSection::square;
  return d;
}

/// Ring k (1-based) whose band |z − z_k| ≤ a/2 holds z, or 0.
int square_ring_at(const RraDesign& d, double z) {
  const int k = std::clamp(static_cast<int>(z / d.pitch()) + 1, 1, d.ring_count);
  return std::abs(z - d.ring_centre_z(k)) <= d.ring_square_side_mm() / 2 * (1 + 1e-12) ? k : 0;
}

/// 2π ∫ r dA of one part of a 9-node mesh (3×3 Gauss on the element's own map).
double q2_part_volume(const Mesh& m, int part) {
  double v = 0.0;
  for (int e = 0; e < m.num_elements(); ++e) {
    if (m.part[e] != part) continue;
    axisym::NodalCoordinates<axisym::Quad9> X;
    for (int a = 0; a < 9; ++a) X.row(a) = m.X.row(m.element(e)[a]);
    std::array<axisym::ReferencePoint<axisym::Quad9>, 9> points;
    REQUIRE(axisym::reference_points<axisym::Quad9>(X, points));  // false: a non-positive Jacobian
    for (const auto& p : points) v += p.dV;
  }
  return v;
}

}  // namespace

TEST_CASE("RRA design: ring_section reads, round-trips and validates square rings", "[rra_mesh]") {
  CHECK(read_geometry(thesis_geometry_json()).ring_section == RraDesign::RingSection::circle);  // the default
  auto j = thesis_geometry_json();
  j["ring_section"] = "square";
  const RraDesign d = read_geometry(j);
  CHECK(d.ring_section == RraDesign::RingSection::square);
  CHECK(d.ring_square_side_mm() == Approx(d.ring_diameter_mm * std::sqrt(pi) / 2).epsilon(1e-15));
  CHECK(d.ring_square_side_mm() * d.ring_square_side_mm() == Approx(pi * std::pow(d.ring_section_radius(), 2)));
  const auto out = to_json(d);
  CHECK(out["physical"]["ring_section"] == "square");
  CHECK(to_json(thesis_rra())["physical"]["ring_section"] == "circle");
  CHECK(out["derived"]["ring_square_side_mm"].get<double>() == Approx(1.8906).epsilon(1e-4));
  CHECK(read_geometry(out["physical"]).ring_section == RraDesign::RingSection::square);

  auto with = [&](const std::string& key, const nlohmann::json& value) {
    auto g = j;
    g[key] = value;
    return g;
  };
  CHECK_THAT(input_error(with("ring_section", "hexagon")), Catch::Contains("geometry.ring_section"));
  // a = 0.886 d_r: a square fits where the circle does not (d_r/pitch = 1.1), up to a < pitch.
  CHECK(input_error(with("ring_thickness_normalised", 1.1)) == "");
  CHECK_THAT(input_error(with("ring_thickness_normalised", 1.2)),
             Catch::Contains("geometry.ring_thickness_normalised") && Catch::Contains("square") &&
                 Catch::Contains("pitch"));
  // Groove depth a/2 against the wall t_w = 4.194 mm: 10 rings (pitch 16 mm), d_r = 8.8 mm
  // (a/2 = 3.90 mm) fits, d_r = 9.6 mm (a/2 = 4.25 mm) does not.
  auto deep = with("ring_count", 10);
  deep.erase("ring_count_normalised");
  deep["ring_thickness_normalised"] = 0.55;
  CHECK(input_error(deep) == "");
  deep["ring_thickness_normalised"] = 0.6;
  CHECK_THAT(input_error(deep), Catch::Contains("geometry.ring_thickness_normalised") && Catch::Contains("groove"));
  RraDesign bad = squared(thesis_rra());
  bad.ring_count = 10;  // pitch 16 mm
  bad.ring_diameter_mm = 2 * bad.wall_thickness_mm / (std::sqrt(pi) / 2);  // a/2 = t_w exactly
  CHECK_THROWS_WITH(validate(bad), Catch::Contains("geometry.ring_diameter_mm") && Catch::Contains("wall thickness"));

  // Equal areas, same centroid radius R_k: the same ring volume as the circle.
  CHECK(ring_volume_mm3(d) == Approx(ring_volume_mm3(thesis_rra())).epsilon(1e-12));
}

TEST_CASE("RRA mesh, square rings: positive Jacobians, exact volumes, bonded rings, node sets", "[rra_mesh]") {
  auto designs = test_designs();
  designs.emplace_back("deep groove", deep_groove_rra());
  designs.emplace_back("rings 1.1 (square fits)", [] {
    RraDesign d = thesis_rra();
    d.ring_diameter_mm = 1.1 * d.pitch();
    return d;
  }());
  for (auto [name, design] : designs) {
    design = squared(design);
    for (int level = 1; level <= 3; ++level) {
      INFO(name << ", square rings, level " << level);
      const Mesh m = mesh_rra(design, level);
      REQUIRE(m.part_names == std::vector<std::string>{"tube", "rings"});
      CHECK(min_jacobian(m) > 0);
      CHECK(connected_pieces(m) == 1);
      // Every edge is straight and every block a parallelogram: the volumes of
      // revolution are exact at every level.
      CHECK(part_volume(m, 0) == Approx(tube_volume_mm3(design)).epsilon(1e-11));
      CHECK(part_volume(m, 1) == Approx(ring_volume_mm3(design)).margin(1e-9));
      const double t_c = design.end_cap_thickness_mm;
      const double exact = frustum(design.length_mm - 2 * t_c, design.chamber_radius(t_c),
                                   design.chamber_radius(design.length_mm - t_c));
      CHECK(chain_volume(m, m.chambers[0]) == Approx(exact).epsilon(1e-12));

      // Bond: the shared nodes are exactly those on the groove (its bottom r_o − a/2
      // and its two faces z_k ± a/2), at least segments + 1 + 2·groove_layers per ring.
      const auto sizes = rra_mesh_sizes(design, level);
      const auto tube = part_nodes(m, 0), rings = part_nodes(m, 1);
      std::vector<int> shared;
      std::set_intersection(tube.begin(), tube.end(), rings.begin(), rings.end(), std::back_inserter(shared));
      const std::size_t per_ring = static_cast<std::size_t>(sizes.groove_segments + 1 + 2 * sizes.groove_layers);
      CHECK(shared.size() >= design.ring_count * per_ring);
      CHECK(shared.size() <= design.ring_count * per_ring + 2);  // + a cap face's column inside a groove
      const double a = design.ring_square_side_mm();
      for (int n : shared) {
        const double r = m.X(n, 0), z = m.X(n, 1);
        const int k = square_ring_at(design, z);
        REQUIRE(k > 0);
        const bool on_face = std::abs(std::abs(z - design.ring_centre_z(k)) - a / 2) < 1e-12 * design.length_mm;
        const bool on_bottom = std::abs(r - (design.outer_radius(z) - a / 2)) < 1e-12 * design.top_radius_mm;
        CHECK((on_face || on_bottom));
        CHECK(r <= design.outer_radius(z) * (1 + 1e-14));
        CHECK(r >= (design.outer_radius(z) - a / 2) * (1 - 1e-14));
      }
      // Ring elements lie inside their squares.
      for (int e = 0; e < m.num_elements(); ++e)
        if (m.part[e] == 1)
          for (int c = 0; c < 4; ++c) {
            const double r = m.X(m.element(e)[c], 0), z = m.X(m.element(e)[c], 1);
            REQUIRE(square_ring_at(design, z) > 0);
            CHECK(std::abs(r - design.outer_radius(z)) <= a / 2 * (1 + 1e-12));
          }

      if (level == 2) {  // node sets as for circular rings
        const auto& sets = m.node_sets;
        CHECK(sets.at("bottom").size() == static_cast<std::size_t>(sizes.core_layers_bottom + sizes.wall_layers + 1));
        CHECK(sets.at("top").size() == static_cast<std::size_t>(sizes.core_layers_top + sizes.wall_layers + 1));
        for (int n : sets.at("axis")) CHECK(m.X(n, 0) == 0.0);
        for (int n : sets.at("bottom")) CHECK(m.X(n, 1) == 0.0);
        for (int n : sets.at("top")) CHECK(m.X(n, 1) == design.length_mm);
        CHECK(sets.at("fixed_end") == sets.at("top"));
        REQUIRE(sets.at("free_end_centre").size() == 1);
        CHECK(m.X(sets.at("free_end_centre")[0], 0) == 0.0);
        CHECK(m.X(sets.at("free_end_centre")[0], 1) == 0.0);
      }
    }
  }
}

TEST_CASE("RRA mesh, square rings: cap faces anywhere along a pitch", "[rra_mesh]") {
  for (const RraDesign& base : {squared(thesis_rra()), squared(deep_groove_rra())})
    for (int step = 0; step < 48; ++step) {
      RraDesign d = base;
      d.end_cap_thickness_mm = 0.3 + d.pitch() * step / 48.0;
      for (int level : {1, 2}) {
        INFO("cap " << d.end_cap_thickness_mm << " mm, wall " << d.wall_thickness_mm << " mm, level " << level);
        const Mesh m = mesh_rra(d, level);
        CHECK(min_jacobian(m) > 0);
        const double t_c = d.end_cap_thickness_mm;
        const double exact = frustum(d.length_mm - 2 * t_c, d.chamber_radius(t_c), d.chamber_radius(d.length_mm - t_c));
        CHECK(chain_volume(m, m.chambers[0]) == Approx(exact).epsilon(1e-12));
        CHECK(part_volume(m, 0) == Approx(tube_volume_mm3(d)).epsilon(1e-11));
      }
    }
}

TEST_CASE("RRA Q2 mesh, square rings: valid 9-node elements and exact volumes", "[rra_mesh]") {
  const RraDesign d = squared(thesis_rra());
  for (int level : {1, 2}) {
    INFO("level " << level);
    const Mesh m = mesh_rra_quadratic(d, level);
    CHECK(m.nodes_per_element == 9);
    CHECK(m.part_names == std::vector<std::string>{"tube", "rings"});
    CHECK(q2_part_volume(m, m.part_index("rings")) == Approx(ring_volume_mm3(d)).epsilon(1e-11));
    CHECK(q2_part_volume(m, m.part_index("tube")) == Approx(tube_volume_mm3(d)).epsilon(1e-11));
    REQUIRE(m.chambers.size() == 1);
  }
  RraDesign plain = thesis_rra();
  plain.ring_count = 0;
  CHECK(mesh_rra(squared(plain), 1).X == mesh_rra(plain, 1).X);  // no rings: the section does not matter
}

#include "fem/io/abaqus_writer.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

namespace softarm::fem {
namespace {

// ccx reads D = 0 as a small compressibility; Abaqus (and softarm) as "no term".
constexpr double kNoVolumetricTerm = 1e30;

// Abaqus data lines hold at most 8 values.
void write_values(std::ostream& out, const std::vector<double>& values) {
  for (std::size_t i = 0; i < values.size(); ++i)
    out << values[i] << ((i + 1) % 8 == 0 || i + 1 == values.size() ? "\n" : ", ");
}

std::vector<double> volumetric_coefficients(const nlohmann::json& m, std::size_t count) {
  std::vector<double> D = m.value("D_per_MPa", std::vector<double>{});
  D.resize(count, 0.0);
  for (double& d : D)
    if (d == 0.0) d = kNoVolumetricTerm;
  return D;
}

void write_material(std::ostream& out, const std::string& name, const Material& material, bool with_density) {
  const nlohmann::json m = material_to_json(material);
  const std::string law = m.at("law");
  out << "*MATERIAL, NAME=" << name << "\n";
  if (law == "ogden") {
    const auto mu = m.at("mu_MPa").get<std::vector<double>>();
    const auto alpha = m.at("alpha").get<std::vector<double>>();
    out << "*HYPERELASTIC, OGDEN, N=" << mu.size() << "\n";
    std::vector<double> values;
    for (std::size_t i = 0; i < mu.size(); ++i) values.insert(values.end(), {mu[i], alpha[i]});
    const auto D = volumetric_coefficients(m, mu.size());
    values.insert(values.end(), D.begin(), D.end());
    write_values(out, values);
  } else if (law == "neo_hookean") {
    out << "*HYPERELASTIC, NEO HOOKE\n";
    write_values(out, {m.at("C10_MPa").get<double>(), volumetric_coefficients(m, 1)[0]});
  } else if (law == "mooney_rivlin") {
    out << "*HYPERELASTIC, MOONEY-RIVLIN\n";
    write_values(out, {m.at("C10_MPa").get<double>(), m.at("C01_MPa").get<double>(), volumetric_coefficients(m, 1)[0]});
  } else if (law == "yeoh") {
    out << "*HYPERELASTIC, YEOH\n";
    std::vector<double> values{m.at("C10_MPa").get<double>(), m.value("C20_MPa", 0.0), m.value("C30_MPa", 0.0)};
    const auto D = volumetric_coefficients(m, 3);
    values.insert(values.end(), D.begin(), D.end());
    write_values(out, values);
  } else if (law == "saint_venant_kirchhoff") {
    out << "*ELASTIC\n";
    write_values(out, {m.at("E_MPa").get<double>(), m.at("poisson_ratio").get<double>()});
  } else {
    throw std::invalid_argument("write_abaqus_deck: no Abaqus card for law '" + law + "'");
  }
  if (with_density) out << "*DENSITY\n" << material.density_g_cm3 * 1e-9 << "\n";  // g/cm³ → t/mm³ (mm-N-s units)
}

void write_node_set(std::ostream& out, const std::string& name, const std::vector<int>& nodes) {
  out << "*NSET, NSET=" << name << "\n";
  for (std::size_t i = 0; i < nodes.size(); ++i) out << nodes[i] + 1 << ((i + 1) % 8 == 0 || i + 1 == nodes.size() ? "\n" : ", ");
}

// Abaqus hexahedron faces S1..S6 as corner indices (0-based; VTK = Abaqus corner order).
constexpr int kHexFaces[6][4] = {{0, 1, 2, 3}, {4, 7, 6, 5}, {0, 4, 5, 1}, {1, 5, 6, 2}, {2, 6, 7, 3}, {3, 7, 4, 0}};

// Chamber facets → "element, Pn" lines: (0-based element, 0-based face) per facet.
std::vector<std::pair<int, int>> chamber_faces_3d(const Mesh& mesh, const Chamber& chamber) {
  std::map<std::array<int, 4>, std::vector<std::pair<int, int>>> faces;  // sorted corners → (element, face)
  for (int e = 0; e < mesh.num_elements(); ++e)
    for (int f = 0; f < 6; ++f) {
      std::array<int, 4> key;
      for (int k = 0; k < 4; ++k) key[k] = mesh.element(e)[kHexFaces[f][k]];
      std::sort(key.begin(), key.end());
      faces[key].push_back({e, f});
    }
  auto point = [&](int n) -> Eigen::Vector3d { return mesh.X.row(n).transpose(); };
  std::vector<std::pair<int, int>> result;
  for (const auto& facet : chamber.facets) {
    if (facet.size() != 4 && facet.size() != 8 && facet.size() != 9)
      throw std::invalid_argument("write_abaqus_deck: a 3D chamber facet must have 4, 8 or 9 nodes");
    std::array<int, 4> key{facet[0], facet[1], facet[2], facet[3]};
    std::sort(key.begin(), key.end());
    const auto it = faces.find(key);
    if (it == faces.end())
      throw std::invalid_argument("write_abaqus_deck: chamber '" + chamber.name + "' has a facet that is no element face");
    // The facet's normal (x_s × x_t ∝ diagonal 0→2 × diagonal 1→3) points out of the
    // cavity, into the wall: the loaded element is the one on that side.
    const Eigen::Vector3d normal = (point(facet[2]) - point(facet[0])).cross(point(facet[3]) - point(facet[1]));
    const Eigen::Vector3d centre = 0.25 * (point(facet[0]) + point(facet[1]) + point(facet[2]) + point(facet[3]));
    int chosen = -1;
    for (std::size_t k = 0; k < it->second.size(); ++k) {
      Eigen::Vector3d element_centre = Eigen::Vector3d::Zero();
      for (int a = 0; a < 8; ++a) element_centre += point(mesh.element(it->second[k].first)[a]) / 8.0;
      if (normal.dot(element_centre - centre) > 0.0) chosen = static_cast<int>(k);
    }
    if (chosen < 0)
      throw std::invalid_argument("write_abaqus_deck: chamber '" + chamber.name +
                                  "' has a facet whose normal points out of the wall (facets must point out of the cavity)");
    result.push_back(it->second[static_cast<std::size_t>(chosen)]);
  }
  return result;
}

double gravity_norm_m_s2(const AbaqusDeck& deck) {
  const auto& g = deck.gravity_m_s2;
  return std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
}

/// The element the deck writes for the mesh's, after the checks on what a deck can hold.
struct DeckElement {
  std::string type;   // CAX4/CAX8(R), C3D8I/C3D8R, C3D20(R)
  int written_nodes;  // of each element's: CAX8 drops the Q2 centre node, C3D20 the Hex27 face and body centres
};
DeckElement deck_element(const AbaqusDeck& deck) {
  const Mesh& mesh = *deck.mesh;
  const bool axisymmetric = mesh.dim == 2;
  if (axisymmetric ? (mesh.nodes_per_element != 4 && mesh.nodes_per_element != 9)
                   : (mesh.dim != 3 || (mesh.nodes_per_element != 8 && mesh.nodes_per_element != 20 &&
                                        mesh.nodes_per_element != 27)))
    throw std::invalid_argument("write_abaqus_deck: only axisymmetric Q1/Q2 and 3D Hex8/Hex20/Hex27 meshes");
  const bool quadratic = axisymmetric ? mesh.nodes_per_element == 9 : mesh.nodes_per_element != 8;
  if (axisymmetric && gravity_norm_m_s2(deck) != 0.0)
    throw std::invalid_argument("write_abaqus_deck: gravity is exported for 3D meshes only");
  if (!axisymmetric && !deck.axis_node_sets.empty())
    throw std::invalid_argument("write_abaqus_deck: axis node sets are for axisymmetric meshes; use fixed_components");
  for (const auto& [set, component] : deck.fixed_components)
    if (component < 1 || component > mesh.dim)
      throw std::invalid_argument("write_abaqus_deck: fixed component " + std::to_string(component) + " of node set '" +
                                  set + "' is not in 1.." + std::to_string(mesh.dim));
  if (axisymmetric)
    return {std::string(quadratic ? "CAX8" : "CAX4") + (deck.reduced_integration ? "R" : ""), quadratic ? 8 : 4};
  if (quadratic) return {std::string("C3D20") + (deck.reduced_integration ? "R" : ""), 20};
  return {deck.reduced_integration ? "C3D8R" : "C3D8I", 8};
}

double chamber_pressure_MPa(const AbaqusDeck& deck, std::size_t c) {
  return c < deck.chamber_pressure_MPa.size() ? deck.chamber_pressure_MPa[c] : 0.0;
}

/// Each pressurised chamber's facets as (element, face) pairs; CAX faces 1..4 join corners (1,2),
/// (2,3), (3,4), (4,1).
std::vector<std::vector<std::pair<int, int>>> pressurised_faces(const AbaqusDeck& deck) {
  const Mesh& mesh = *deck.mesh;
  std::vector<std::vector<std::pair<int, int>>> faces(mesh.chambers.size());
  if (mesh.dim == 3) {
    for (std::size_t c = 0; c < mesh.chambers.size(); ++c)
      if (chamber_pressure_MPa(deck, c) != 0.0) faces[c] = chamber_faces_3d(mesh, mesh.chambers[c]);
    return faces;
  }
  constexpr int corners = 4;
  std::map<std::pair<int, int>, std::pair<int, int>> face_of;
  for (int e = 0; e < mesh.num_elements(); ++e)
    for (int f = 0; f < corners; ++f) {
      const int a = mesh.element(e)[f], b = mesh.element(e)[(f + 1) % corners];
      face_of[{std::min(a, b), std::max(a, b)}] = {e, f};
    }
  for (std::size_t c = 0; c < mesh.chambers.size(); ++c) {
    if (chamber_pressure_MPa(deck, c) == 0.0) continue;
    for (const auto& facet : mesh.chambers[c].facets) {
      const int a = facet.front(), b = facet.back();
      const auto it = face_of.find({std::min(a, b), std::max(a, b)});
      if (it == face_of.end()) throw std::invalid_argument("write_abaqus_deck: a chamber edge is not an element face");
      faces[c].push_back(it->second);
    }
  }
  return faces;
}

/// *NODE: the nodes the written elements use (a Q2 centre node, Hex27 face and body centres are not);
/// returns which those are.
std::vector<char> write_nodes(std::ostream& out, const Mesh& mesh, int written_nodes) {
  out << "*NODE, NSET=NALL\n";
  std::vector<char> used(mesh.num_nodes(), 0);
  for (int e = 0; e < mesh.num_elements(); ++e)
    for (int a = 0; a < written_nodes; ++a) used[mesh.element(e)[a]] = 1;
  for (int n = 0; n < mesh.num_nodes(); ++n)
    if (used[n]) {
      out << n + 1;
      for (int i = 0; i < mesh.dim; ++i) out << ", " << mesh.X(n, i);
      out << "\n";
    }
  return used;
}

/// *ELEMENT per part, then the mesh's node sets (their written nodes).
void write_elements_and_sets(std::ostream& out, const Mesh& mesh, const DeckElement& element, const std::vector<char>& used) {
  for (std::size_t p = 0; p < mesh.part_names.size(); ++p) {
    out << "*ELEMENT, TYPE=" << element.type << ", ELSET=E_" << mesh.part_names[p] << "\n";
    for (int e = 0; e < mesh.num_elements(); ++e) {
      if (mesh.part[e] != static_cast<int>(p)) continue;
      out << e + 1;
      // Abaqus data lines hold at most 16 entries: a C3D20 line continues after 15 nodes.
      for (int a = 0; a < element.written_nodes; ++a) out << (a == 15 ? ",\n" : ", ") << mesh.element(e)[a] + 1;
      out << "\n";
    }
  }
  for (const auto& [name, nodes] : mesh.node_sets) {
    std::vector<int> written;
    for (int n : nodes)
      if (used[n]) written.push_back(n);
    if (!written.empty()) write_node_set(out, name, written);
  }
}

/// The one *STEP: its increments, the chambers' pressures, gravity (its magnitude in mm/s², then the
/// unit direction) and the printed node sets.
void write_step(std::ostream& out, const AbaqusDeck& deck, const std::vector<std::vector<std::pair<int, int>>>& faces) {
  const Mesh& mesh = *deck.mesh;
  const auto& g = deck.gravity_m_s2;
  const double g_norm = gravity_norm_m_s2(deck);
  out << "*STEP, NLGEOM, INC=10000\n*STATIC\n"
      << deck.initial_increment << ", 1.0, " << deck.min_increment << ", " << deck.max_increment << "\n*DLOAD\n";
  for (std::size_t c = 0; c < mesh.chambers.size(); ++c)
    for (const auto& [e, f] : faces[c]) out << e + 1 << ", P" << f + 1 << ", " << chamber_pressure_MPa(deck, c) << "\n";
  if (g_norm != 0.0)
    for (std::size_t p = 0; p < mesh.part_names.size(); ++p)
      if (std::count(mesh.part.begin(), mesh.part.end(), static_cast<int>(p)) > 0)
        out << "E_" << mesh.part_names[p] << ", GRAV, " << 1000.0 * g_norm << ", " << g[0] / g_norm << ", "
            << g[1] / g_norm << ", " << g[2] / g_norm << "\n";
  for (const auto& s : deck.printed_node_sets) out << "*NODE PRINT, NSET=" << s << "\nU\n";
  out << "*END STEP\n";
}

}  // namespace

void write_abaqus_deck(const std::string& path, const AbaqusDeck& deck) {
  const Mesh& mesh = *deck.mesh;
  const DeckElement element = deck_element(deck);
  const auto faces = pressurised_faces(deck);
  if (const auto dir = std::filesystem::path(path).parent_path(); !dir.empty()) {
    std::error_code error;
    std::filesystem::create_directories(dir, error);  // a failure shows as the open below failing
  }
  std::ofstream out(path);
  if (!out) throw std::invalid_argument("write_abaqus_deck: cannot write '" + path + "'");
  out.precision(12);
  out << "*HEADING\n" << deck.heading << "\n";
  const std::vector<char> used = write_nodes(out, mesh, element.written_nodes);
  write_elements_and_sets(out, mesh, element, used);
  const bool gravity = gravity_norm_m_s2(deck) != 0.0;
  for (std::size_t p = 0; p < mesh.part_names.size(); ++p) {
    write_material(out, "M_" + mesh.part_names[p], deck.part_materials.at(p), gravity);
    out << "*SOLID SECTION, ELSET=E_" << mesh.part_names[p] << ", MATERIAL=M_" << mesh.part_names[p] << "\n";
  }
  out << "*BOUNDARY\n";
  for (const auto& s : deck.clamped_node_sets) out << s << ", 1, " << mesh.dim << "\n";
  for (const auto& s : deck.axis_node_sets) out << s << ", 1, 1\n";
  for (const auto& [set, component] : deck.fixed_components) out << set << ", " << component << ", " << component << "\n";
  write_step(out, deck, faces);
  if (!out) throw std::runtime_error("write_abaqus_deck: write failed for '" + path + "'");
}

}  // namespace softarm::fem

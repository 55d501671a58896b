#include "fem/io/abaqus_writer.hpp"

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

void write_material(std::ostream& out, const std::string& name, const Material& material) {
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
  out << "*DENSITY\n" << material.density_g_cm3 * 1e-9 << "\n";  // g/cm³ → t/mm³ (mm-N-s units)
}

void write_node_set(std::ostream& out, const std::string& name, const std::vector<int>& nodes) {
  out << "*NSET, NSET=" << name << "\n";
  for (std::size_t i = 0; i < nodes.size(); ++i) out << nodes[i] + 1 << ((i + 1) % 8 == 0 || i + 1 == nodes.size() ? "\n" : ", ");
}

}  // namespace

void write_abaqus_deck(const std::string& path, const AbaqusDeck& deck) {
  const Mesh& mesh = *deck.mesh;
  if (mesh.dim != 2 || (mesh.nodes_per_element != 4 && mesh.nodes_per_element != 9))
    throw std::invalid_argument("write_abaqus_deck: only axisymmetric Q1/Q2 meshes so far");
  const bool quadratic = mesh.nodes_per_element == 9;
  const int corners = 4, written_nodes = quadratic ? 8 : 4;  // CAX8 drops the centre node

  if (const auto dir = std::filesystem::path(path).parent_path(); !dir.empty()) {
    std::error_code error;
    std::filesystem::create_directories(dir, error);  // a failure shows as the open below failing
  }
  std::ofstream out(path);
  if (!out) throw std::invalid_argument("write_abaqus_deck: cannot write '" + path + "'");
  out.precision(12);
  out << "*HEADING\n" << deck.heading << "\n";

  // Nodes used by the written elements (a Q2 centre node is not).
  out << "*NODE, NSET=NALL\n";
  std::vector<char> used(mesh.num_nodes(), 0);
  for (int e = 0; e < mesh.num_elements(); ++e)
    for (int a = 0; a < written_nodes; ++a) used[mesh.element(e)[a]] = 1;
  for (int n = 0; n < mesh.num_nodes(); ++n)
    if (used[n]) out << n + 1 << ", " << mesh.X(n, 0) << ", " << mesh.X(n, 1) << "\n";

  for (std::size_t p = 0; p < mesh.part_names.size(); ++p) {
    out << "*ELEMENT, TYPE=" << (quadratic ? "CAX8" : "CAX4") << (deck.reduced_integration ? "R" : "")
        << ", ELSET=E_" << mesh.part_names[p] << "\n";
    for (int e = 0; e < mesh.num_elements(); ++e) {
      if (mesh.part[e] != static_cast<int>(p)) continue;
      out << e + 1;
      for (int a = 0; a < written_nodes; ++a) out << ", " << mesh.element(e)[a] + 1;
      out << "\n";
    }
  }
  for (const auto& [name, nodes] : mesh.node_sets) {
    std::vector<int> written;
    for (int n : nodes)
      if (used[n]) written.push_back(n);
    if (!written.empty()) write_node_set(out, name, written);
  }
  for (std::size_t p = 0; p < mesh.part_names.size(); ++p) {
    write_material(out, "M_" + mesh.part_names[p], deck.part_materials.at(p));
    out << "*SOLID SECTION, ELSET=E_" << mesh.part_names[p] << ", MATERIAL=M_" << mesh.part_names[p] << "\n";
  }
  out << "*BOUNDARY\n";
  for (const auto& s : deck.clamped_node_sets) out << s << ", 1, 2\n";
  for (const auto& s : deck.axis_node_sets) out << s << ", 1, 1\n";

  // Chamber edges → (element, face): CAX faces 1..4 join corners (1,2), (2,3), (3,4), (4,1).
  std::map<std::pair<int, int>, std::pair<int, int>> face_of;
  for (int e = 0; e < mesh.num_elements(); ++e)
    for (int f = 0; f < corners; ++f) {
      const int a = mesh.element(e)[f], b = mesh.element(e)[(f + 1) % corners];
      face_of[{std::min(a, b), std::max(a, b)}] = {e, f};
    }
  out << "*STEP, NLGEOM, INC=10000\n*STATIC\n"
      << deck.initial_increment << ", 1.0, " << deck.min_increment << ", " << deck.max_increment << "\n*DLOAD\n";
  for (std::size_t c = 0; c < mesh.chambers.size(); ++c) {
    const double p = c < deck.chamber_pressure_MPa.size() ? deck.chamber_pressure_MPa[c] : 0.0;
    if (p == 0.0) continue;
    for (const auto& facet : mesh.chambers[c].facets) {
      const int a = facet.front(), b = facet.back();
      const auto it = face_of.find({std::min(a, b), std::max(a, b)});
      if (it == face_of.end()) throw std::invalid_argument("write_abaqus_deck: a chamber edge is not an element face");
      out << it->second.first + 1 << ", P" << it->second.second + 1 << ", " << p << "\n";
    }
  }
  for (const auto& s : deck.printed_node_sets) out << "*NODE PRINT, NSET=" << s << "\nU\n";
  out << "*END STEP\n";
  if (!out) throw std::runtime_error("write_abaqus_deck: write failed for '" + path + "'");
}

}  // namespace softarm::fem

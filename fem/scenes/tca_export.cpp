#include "fem/scenes/tca_export.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>

namespace softarm::fem {
namespace {

void set_common(AbaqusDeck& deck, const Mesh& mesh, const Eigen::Vector3d& gravity_m_s2) {
  deck.mesh = &mesh;
  if (!mesh.node_sets.count("top") || !mesh.node_sets.count("bottom"))
    throw std::invalid_argument("actuator deck: the mesh needs the node sets \"top\" and \"bottom\"");
  deck.clamped_node_sets = {"top"};
  // A node of "top" on the plane is clamped already; fixing u_y again is harmless.
  if (mesh.node_sets.count("symmetry")) deck.fixed_components = {{"symmetry", 2}};
  deck.gravity_m_s2 = {gravity_m_s2.x(), gravity_m_s2.y(), gravity_m_s2.z()};
  deck.printed_node_sets = {"bottom"};
}

}  // namespace

AbaqusDeck tca_abaqus_deck(const TcaSceneSpec& spec, const Mesh& solver_frame_mesh, const ModelChoice& model,
                           double pressure_scale) {
  AbaqusDeck deck;
  deck.heading = "softarm 3CA scene (" + model.name + ") exported for CalculiX/Abaqus";
  set_common(deck, solver_frame_mesh, tca_solver_gravity(spec, model));
  deck.part_materials = tca_part_materials(spec);
  if (solver_frame_mesh.part_names.size() != deck.part_materials.size())
    throw std::invalid_argument("tca_abaqus_deck: the mesh is not a 3CA mesh (parts tube, rings, sheath)");
  deck.chamber_pressure_MPa.assign(solver_frame_mesh.chambers.size(), 0.0);
  for (std::size_t c = 0; c < solver_frame_mesh.chambers.size() && c < 3; ++c)
    if (!solver_frame_mesh.chambers[c].facets.empty())
      deck.chamber_pressure_MPa[c] = spec.chamber_pressure_kPa[c] * pressure_scale * 1e-3;
  return deck;
}

AbaqusDeck rra_3d_abaqus_deck(const Mesh& mesh, const Material& tube, const Material& rings, double pressure_kPa,
                              const Eigen::Vector3d& gravity_m_s2) {
  AbaqusDeck deck;
  deck.heading = std::string("softarm 3D RRA (") + (mesh.node_sets.count("symmetry") ? "half" : "full") +
                 " model) exported for CalculiX/Abaqus";
  set_common(deck, mesh, gravity_m_s2);
  if (mesh.chambers.size() != 1) throw std::invalid_argument("rra_3d_abaqus_deck: a lone RRA has one chamber");
  deck.part_materials = {tube, rings};
  deck.part_materials.resize(mesh.part_names.size(), tube);  // a ringless RRA has no "rings" elements
  deck.chamber_pressure_MPa = {pressure_kPa * 1e-3};
  return deck;
}

DirichletConstraints actuator_3d_constraints(const Mesh& mesh) { return clamped_with_symmetry(mesh, "top"); }

std::vector<int> exported_nodes(const Mesh& mesh, const std::vector<int>& nodes) {
  const int written = std::min(mesh.nodes_per_element, 20);
  std::vector<char> used(mesh.num_nodes(), 0);
  for (int e = 0; e < mesh.num_elements(); ++e)
    for (int a = 0; a < written; ++a) used[mesh.element(e)[a]] = 1;
  std::vector<int> out;
  for (int n : nodes)
    if (used[n]) out.push_back(n);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

Eigen::Vector3d mean_displacement(const std::vector<int>& nodes, const Eigen::VectorXd& u) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int n : nodes) sum += u.segment<3>(3 * n);
  return nodes.empty() ? sum : Eigen::Vector3d(sum / static_cast<double>(nodes.size()));
}

std::map<int, Eigen::Vector3d> read_ccx_displacements(const std::string& dat_file) {
  std::ifstream in(dat_file);
  std::map<int, Eigen::Vector3d> u;
  std::string line;
  const std::regex row(R"(^\s*(\d+)\s+(\S+)\s+(\S+)\s+(\S+)\s*$)");
  while (std::getline(in, line)) {
    if (line.find("displacements") != std::string::npos) {
      u.clear();  // a new increment's block
      continue;
    }
    std::smatch m;
    if (std::regex_match(line, m, row))
      u[std::stoi(m[1]) - 1] = Eigen::Vector3d(std::stod(m[2]), std::stod(m[3]), std::stod(m[4]));
  }
  return u;
}

CcxStatistics read_ccx_statistics(const std::string& sta_file) {
  // Rows: STEP INC ATT ITRS TOT-TIME STEP-TIME INC-TIME.
  std::ifstream in(sta_file);
  CcxStatistics s;
  std::string line;
  const std::regex row(R"(^\s*(\d+)\s+(\d+)\s+(\d+)\s+(\d+)\s+(\S+)\s+(\S+)\s+(\S+)\s*$)");
  while (std::getline(in, line)) {
    std::smatch m;
    if (!std::regex_match(line, m, row)) continue;
    ++s.increments;
    s.iterations += std::stoi(m[4]);
    s.reached_time = std::stod(m[6]);
  }
  return s;
}

}  // namespace softarm::fem

#include "engine/tca_report.hpp"

#include <iomanip>
#include <set>

#include "engine/path_summary.hpp"
#include "engine/report/deformed_series.hpp"
#include "engine/report/output_files.hpp"
#include "fem/io/vtu_writer.hpp"
#include "fem/mesh/tca_mesher.hpp"

namespace softarm::engine {
namespace {

nlohmann::json vector_json(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::json state_json(const fem::TcaState& s) {
  return {{"pressure_kPa", s.pressure_kPa},
          {"bending_angle_deg", s.bending_angle_deg},
          {"tip_position_mm", vector_json(s.tip_position_mm)},
          {"tip_displacement_mm", vector_json(s.tip_displacement_mm)},
          {"chamber_volume_mm3", s.chamber_volume_mm3},
          {"newton_iterations", s.newton_iterations}};
}

/// Cell data "chamber_wall": the chamber (1–3) an element bounds with one of its faces, else 0.
std::vector<double> chamber_wall_ids(const fem::Mesh& mesh) {
  std::vector<double> ids(mesh.num_elements(), 0.0);
  for (const auto& chamber : mesh.chambers) {
    std::set<int> nodes;
    for (const auto& f : chamber.facets) nodes.insert(f.begin(), f.end());
    for (int e = 0; e < mesh.num_elements(); ++e) {
      int on = 0;
      for (int a = 0; a < mesh.nodes_per_element; ++a) on += nodes.count(mesh.element(e)[a]) ? 1 : 0;
      if (on >= 4) ids[e] = chamber.id;
    }
  }
  return ids;
}

void write_vtu(const std::string& path, const fem::TcaResult& r) {
  const auto& mesh = r.mesh;
  Eigen::MatrixXd x(mesh.num_nodes(), 3);
  for (int n = 0; n < mesh.num_nodes(); ++n) x.row(n) = r.final_positions.segment<3>(3 * n).transpose();
  std::vector<double> stretch, stress, dilatation;
  for (const auto& e : r.final_element_results) {
    stretch.push_back(e.max_principal_stretch);
    stress.push_back(e.max_principal_cauchy_MPa);
    dilatation.push_back(e.dilatation);
  }
  fem::write_vtu(path, mesh, x, {},
                 {{"max_principal_stretch", 1, stretch},
                  {"max_principal_cauchy_stress_MPa", 1, stress},
                  {"element_dilatation_J", 1, dilatation},
                  {"chamber_wall", 1, chamber_wall_ids(mesh)}});
}

}  // namespace

TcaCurveWriter::TcaCurveWriter(const std::string& directory, std::ostream& out)
    : csv_(open_output_file(directory, "curve.csv")), out_(out) {
  csv_ << "pressure_kPa,bending_angle_deg,tip_x_mm,tip_y_mm,tip_z_mm,tip_dx_mm,tip_dy_mm,tip_dz_mm,"
          "chamber_volume_mm3,newton_iterations\n";
  out_ << "  pressure_kPa  bending_deg   tip_x_mm   tip_y_mm   tip_z_mm  volume_mm3  newton\n";
}

void TcaCurveWriter::add(const fem::TcaState& s) {
  const auto& p = s.tip_position_mm;
  const auto& d = s.tip_displacement_mm;
  csv_ << std::setprecision(10) << s.pressure_kPa << ',' << s.bending_angle_deg << ',' << p.x() << ',' << p.y() << ','
       << p.z() << ',' << d.x() << ',' << d.y() << ',' << d.z() << ',' << s.chamber_volume_mm3 << ','
       << s.newton_iterations << '\n';
  csv_.flush();
  out_ << std::fixed << std::setprecision(2) << std::setw(14) << s.pressure_kPa << std::setprecision(3)
       << std::setw(13) << s.bending_angle_deg << std::setw(11) << p.x() << std::setw(11) << p.y() << std::setw(11)
       << p.z() << std::setprecision(1) << std::setw(12) << s.chamber_volume_mm3 << std::setw(8)
       << s.newton_iterations << std::endl;
}

nlohmann::json write_tca_summary(const fem::SceneConfig& config, const fem::TcaResult& r, std::ostream& out) {
  const auto& spec = config.tca;
  const auto& dir = config.output.directory;
  nlohmann::json curve = nlohmann::json::array(), peaks = nlohmann::json::object(), mass = nlohmann::json::object();
  for (const auto& s : r.curve) curve.push_back(state_json(s));
  for (const auto& p : r.final_peaks)
    peaks[p.part] = {{"max_principal_stretch", p.max_principal_stretch},
                     {"max_principal_stress_MPa", p.max_principal_stress_MPa},
                     {"max_principal_log_strain", p.max_principal_log_strain}};
  for (const auto& [part, kg] : r.part_mass_kg) mass[part] = kg;
  mass["total"] = r.mass_kg;
  nlohmann::json summary = {
      {"scene", "tca"},
      {"model", {{"name", r.model.name}, {"reason", r.model.reason}, {"element", r.element_name}}},
      {"design", fem::to_json(spec.design)},
      {"materials", {{"tube", spec.tube_material.name}, {"rings", spec.ring_material.name},
                     {"sheath", spec.sheath_material.name}}},
      {"load", {{"chamber_pressures_kPa", spec.chamber_pressure_kPa}, {"gravity_m_s2", vector_json(spec.gravity_m_s2)}}},
      {"mesh", {{"level", spec.mesh_level}, {"axial_level", fem::layers_level(spec.mesh_level, spec.axial_level)},
                {"element_order", spec.element_order}, {"elements", r.mesh.num_elements()},
                {"nodes", r.mesh.num_nodes()}, {"dofs", r.dofs}}},
      {"outcome", fem::to_string(r.path.outcome)},
      {"diagnosis", r.path.diagnosis},
      {"reached_pressure_kPa", r.path.reached_pressure_kPa},
      {"target_bending_deg", spec.target_bending_deg},
      {"pressure_at_target_bending_kPa", r.target_pressure_kPa ? nlohmann::json(*r.target_pressure_kPa) : nlohmann::json()},
      {"mass_kg", mass},
      {"final_peaks", peaks},
      {"curve", curve},
      {"solver", path_solver_json(r.path)},
      {"time_s", {{"mesh", r.timings.mesh_s}, {"setup", r.timings.setup_s}, {"solve", r.timings.solve_s},
                  {"assembly", r.timings.assembly_s}, {"factorize", r.path.factorize_s}, {"total", r.timings.total_s}}}};
  add_failure_json(summary, r.path);
  write_json_file(dir, "summary.json", summary);
  std::string series;
  if (config.output.vtu) {
    write_vtu(dir + "/deformed.vtu", r);
    series = write_deformed_series(dir, r.mesh, r.curve_positions, pressures_of(r.curve));
  }

  out << "\noutcome: " << fem::to_string(r.path.outcome) << " — " << r.path.diagnosis << "\n";
  out << std::fixed << std::setprecision(2);
  if (r.target_pressure_kPa)
    out << "bending reaches " << spec.target_bending_deg << "° at " << *r.target_pressure_kPa << " kPa\n";
  else if (!r.curve.empty())
    out << "bending does not reach " << spec.target_bending_deg << "°: " << r.curve.back().bending_angle_deg << "° at "
        << r.curve.back().pressure_kPa << " kPa\n";
  out << std::setprecision(1) << "mass: " << 1e3 * r.mass_kg << " g (";
  for (std::size_t i = 0; i < r.part_mass_kg.size(); ++i)
    out << (i ? ", " : "") << r.part_mass_kg[i].first << " " << 1e3 * r.part_mass_kg[i].second << " g";
  out << ")\npeaks at the last state:";
  for (const auto& p : r.final_peaks)
    out << std::setprecision(3) << " " << p.part << " stretch " << p.max_principal_stretch << ", stress "
        << p.max_principal_stress_MPa << " MPa;";
  out << "\nmodel: " << r.model.name << " — " << r.model.reason << "\n"
      << "       " << r.element_name << ", " << r.mesh.num_elements() << " elements, " << r.dofs << " dofs; "
      << r.path.path.stats.steps << " load steps, " << r.path.path.stats.newton_iterations << " Newton iterations, "
      << std::setprecision(1) << r.timings.total_s << " s\n"
      << "written: " << dir << "/curve.csv, " << dir << "/summary.json"
      << (config.output.vtu ? ", " + dir + "/deformed.vtu" : "") << series << "\n";
  return summary;
}

}  // namespace softarm::engine

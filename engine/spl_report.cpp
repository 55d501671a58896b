#include "engine/spl_report.hpp"

#include <Eigen/Geometry>
#include <iomanip>

#include "engine/path_summary.hpp"
#include "engine/report/deformed_series.hpp"
#include "engine/report/output_files.hpp"
#include "fem/io/vtu_writer.hpp"
#include "fem/mesh/tca_mesher.hpp"
#include "fem/core/angles.hpp"

namespace softarm::engine {
namespace {
nlohmann::json vector_json(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::json pose_json(const fem::FacePose& pose) {
  const Eigen::AngleAxisd aa(pose.rotation);
  return {{"position_mm", vector_json(pose.position_mm)},
          {"axis_tilt_deg", pose.tilt_deg},
          {"rotation_axis", vector_json(aa.axis())},
          {"rotation_angle_deg", aa.angle() * softarm::fem::kDeg},
          {"rotation_matrix", {{pose.rotation(0, 0), pose.rotation(0, 1), pose.rotation(0, 2)},
                               {pose.rotation(1, 0), pose.rotation(1, 1), pose.rotation(1, 2)},
                               {pose.rotation(2, 0), pose.rotation(2, 1), pose.rotation(2, 2)}}}};
}
}  // namespace

nlohmann::json joints_json(const std::vector<fem::SplJoint>& joints) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& j : joints) {
    auto entry = pose_json(j.pose);
    entry["joint"] = j.name;
    out.push_back(entry);
  }
  return out;
}

void print_joint_table(const std::vector<fem::SplJoint>& joints, std::ostream& out) {
  out << "joints (user frame: z along the arm, shoulder at the top):\n"
      << "  joint                               x_mm       y_mm       z_mm   tilt_deg\n";
  for (const auto& j : joints)
    out << "  " << std::left << std::setw(32) << j.name << std::right << std::fixed << std::setprecision(2)
        << std::setw(11) << j.pose.position_mm.x() << std::setw(11) << j.pose.position_mm.y() << std::setw(11)
        << j.pose.position_mm.z() << std::setw(11) << j.pose.tilt_deg << "\n";
}

SplCurveWriter::SplCurveWriter(const std::string& directory, std::ostream& out, const std::string& iterations)
    : csv_(open_output_file(directory, "curve.csv")), out_(out) {
  csv_ << "load_fraction,tip_x_mm,tip_y_mm,tip_z_mm,tip_tilt_deg," << iterations << "_iterations\n";
  out_ << "  load_fraction   tip_x_mm   tip_y_mm   tip_z_mm  tip_tilt_deg  " << iterations << "\n";
}

void SplCurveWriter::add(const fem::SplState& s) {
  const auto& p = s.tip_position_mm;
  csv_ << std::setprecision(10) << s.load_fraction << ',' << p.x() << ',' << p.y() << ',' << p.z() << ','
       << s.tip_tilt_deg << ',' << s.newton_iterations << '\n';
  csv_.flush();
  out_ << std::fixed << std::setprecision(3) << std::setw(15) << s.load_fraction << std::setw(11) << p.x()
       << std::setw(11) << p.y() << std::setw(11) << p.z() << std::setw(14) << s.tip_tilt_deg << std::setw(8)
       << s.newton_iterations << std::endl;
}

nlohmann::json write_spl_summary(const fem::SceneConfig& config, const fem::SplResult& r, std::ostream& out) {
  const auto& spec = config.spl;
  const auto& dir = config.output.directory;
  nlohmann::json peaks = nlohmann::json::object(), mass = nlohmann::json::object();
  for (const auto& p : r.final_peaks)
    peaks[p.part] = {{"max_principal_stretch", p.max_principal_stretch},
                     {"max_principal_stress_MPa", p.max_principal_stress_MPa}};
  for (const auto& [part, kg] : r.part_mass_kg) mass[part] = kg;
  mass["total"] = r.mass_kg;
  nlohmann::json summary = {
      {"scene", "spl"},
      {"model", {{"name", r.model.name}, {"reason", r.model.reason}, {"element", r.element_name}}},
      {"design", fem::to_json(spec.design)},
      {"load", {{"chamber_pressures_kPa", spec.chamber_pressure_kPa}, {"gravity_m_s2", vector_json(spec.gravity_m_s2)},
                {"tip_mass_kg", spec.tip_mass_kg}}},
      {"mesh", {{"level", spec.mesh_level}, {"axial_level", fem::layers_level(spec.mesh_level, spec.axial_level)},
                {"element_order", spec.element_order}, {"elements", r.mesh.num_elements()},
                {"nodes", r.mesh.num_nodes()}, {"dofs", r.dofs}}},
      {"outcome", fem::to_string(r.path.outcome)},
      {"diagnosis", r.path.diagnosis},
      {"reached_load_fraction", r.curve.empty() ? 0.0 : r.curve.back().load_fraction},
      {"joints", joints_json(r.joints)},
      {"mass_kg", mass},
      {"final_peaks", peaks},
      {"solver", path_solver_json(r.path)},
      {"time_s", {{"mesh", r.timings.mesh_s}, {"setup", r.timings.setup_s}, {"solve", r.timings.solve_s},
                  {"assembly", r.timings.assembly_s}, {"factorize", r.path.factorize_s}, {"total", r.timings.total_s}}}};
  add_failure_json(summary, r.path);
  write_json_file(dir, "summary.json", summary);
  std::string series;
  if (config.output.vtu) {
    std::vector<double> load_fractions;
    for (const auto& s : r.curve) load_fractions.push_back(s.load_fraction);
    series = write_deformed_series(dir, r.mesh, r.curve_positions, load_fractions);
    Eigen::MatrixXd x(r.mesh.num_nodes(), 3);
    for (int n = 0; n < r.mesh.num_nodes(); ++n) x.row(n) = r.final_positions.segment<3>(3 * n).transpose();
    std::vector<double> stretch, stress;
    for (const auto& e : r.final_element_results) {
      stretch.push_back(e.max_principal_stretch);
      stress.push_back(e.max_principal_cauchy_MPa);
    }
    fem::write_vtu(dir + "/deformed.vtu", r.mesh, x, {},
                   {{"max_principal_stretch", 1, stretch}, {"max_principal_cauchy_stress_MPa", 1, stress}});
  }
  out << "\noutcome: " << fem::to_string(r.path.outcome) << " — " << r.path.diagnosis << "\n";
  print_joint_table(r.joints, out);
  out << std::setprecision(1) << "mass: " << 1e3 * r.mass_kg << " g (";
  for (std::size_t i = 0; i < r.part_mass_kg.size(); ++i)
    out << (i ? ", " : "") << r.part_mass_kg[i].first << " " << 1e3 * r.part_mass_kg[i].second << " g";
  out << ")\nmodel: " << r.model.name << " — " << r.model.reason << "\n       " << r.element_name << ", "
      << r.mesh.num_elements() << " elements, " << r.dofs << " dofs; " << r.path.path.stats.steps << " load steps, "
      << r.path.path.stats.newton_iterations << " Newton iterations, " << r.timings.total_s << " s\n"
      << "written: " << dir << "/curve.csv, " << dir << "/summary.json"
      << (config.output.vtu ? ", " + dir + "/deformed.vtu" : "") << series << "\n";
  return summary;
}

}  // namespace softarm::engine

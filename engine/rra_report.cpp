#include "engine/rra_report.hpp"

#include <filesystem>
#include <iomanip>

#include "engine/path_summary.hpp"
#include "engine/report/deformed_series.hpp"
#include "engine/report/output_files.hpp"
#include "fem/io/vtu_writer.hpp"

namespace softarm::engine {
namespace {

nlohmann::json point_json(const fem::RraCurvePoint& p) {
  return {{"pressure_kPa", p.pressure_kPa},
          {"extension_mm", p.extension_mm},
          {"chamber_volume_mm3", p.chamber_volume_mm3},
          {"pv_stiffness_kPa_per_mm3", p.pv_stiffness_kPa_per_mm3},
          {"tube_max_principal_stretch", p.tube_max_stretch},
          {"tube_max_principal_log_strain", p.tube_max_log_strain},
          {"tube_max_principal_stress_MPa", p.tube_max_principal_stress_MPa},
          {"ring_max_principal_stress_MPa", p.ring_max_principal_stress_MPa},
          {"tube_averaged_principal_stretch", p.averaged.stretch},
          {"tube_averaged_principal_log_strain", p.averaged.log_strain},
          {"tube_averaged_principal_stress_MPa", p.averaged.stress_MPa},
          {"newton_iterations", p.newton_iterations}};
}

void write_vtu(const std::string& path, const fem::RraResult& r) {
  const auto& mesh = r.mesh;
  Eigen::MatrixXd x(mesh.num_nodes(), 2);
  for (int n = 0; n < mesh.num_nodes(); ++n) x.row(n) = r.final_positions.segment<2>(2 * n).transpose();
  std::vector<double> stretch, min_stretch, stress, dilatation;
  for (const auto& e : r.final_element_results) {
    stretch.push_back(e.max_principal_stretch);
    min_stretch.push_back(e.min_principal_stretch);
    stress.push_back(e.max_principal_cauchy_MPa);
    dilatation.push_back(e.dilatation);
  }
  fem::write_vtu(path, mesh, x, {},
                 {{"max_principal_stretch", 1, stretch},
                  {"min_principal_stretch", 1, min_stretch},
                  {"max_principal_cauchy_stress_MPa", 1, stress},
                  {"element_dilatation_J", 1, dilatation}});
}

}  // namespace

RraCurveWriter::RraCurveWriter(const std::string& directory, std::ostream& out)
    : csv_(open_output_file(directory, "curve.csv")), out_(out) {
  csv_ << "pressure_kPa,extension_mm,chamber_volume_mm3,pv_stiffness_kPa_per_mm3,tube_max_principal_stretch,"
          "tube_max_principal_stress_MPa,ring_max_principal_stress_MPa,newton_iterations,tube_averaged_principal_stretch,"
          "tube_averaged_principal_stress_MPa\n";
  out_ << "  pressure_kPa  extension_mm  volume_mm3  dp/dV_kPa/mm3  max_stretch  max_stress_MPa(tube/ring)\n";
}

void RraCurveWriter::add(const fem::RraCurvePoint& p) {
  csv_ << std::setprecision(10) << p.pressure_kPa << ',' << p.extension_mm << ',' << p.chamber_volume_mm3 << ','
       << p.pv_stiffness_kPa_per_mm3 << ',' << p.tube_max_stretch << ',' << p.tube_max_principal_stress_MPa << ','
       << p.ring_max_principal_stress_MPa << ',' << p.newton_iterations << ',' << p.averaged.stretch << ','
       << p.averaged.stress_MPa << '\n';
  csv_.flush();
  out_ << std::fixed << std::setprecision(2) << std::setw(14) << p.pressure_kPa << std::setprecision(3)
       << std::setw(14) << p.extension_mm << std::setprecision(1) << std::setw(12) << p.chamber_volume_mm3
       << std::scientific << std::setprecision(3) << std::setw(15) << p.pv_stiffness_kPa_per_mm3 << std::fixed
       << std::setprecision(4) << std::setw(13) << p.tube_max_stretch << std::setprecision(3) << std::setw(10)
       << p.tube_max_principal_stress_MPa << " / " << p.ring_max_principal_stress_MPa << std::endl;
}

nlohmann::json write_rra_summary(const fem::SceneConfig& config, const fem::RraResult& r, std::ostream& out) {
  const auto& dir = config.output.directory;
  nlohmann::json curve = nlohmann::json::array();
  for (const auto& p : r.curve) curve.push_back(point_json(p));
  nlohmann::json summary = {
      {"scene", "rra"},
      {"model", "axisymmetric FEM (a lone RRA under internal pressure is axisymmetric), " + r.element_name},
      {"design", fem::to_json(config.rra.design)},
      {"materials", {{"tube", config.rra.tube_material.name}, {"rings", config.rra.ring_material.name}}},
      {"mesh", {{"level", config.rra.mesh_level}, {"elements", r.mesh.num_elements()}, {"nodes", r.mesh.num_nodes()},
                {"dofs", r.dofs}}},
      {"outcome", fem::to_string(r.path.outcome)},
      {"diagnosis", r.path.diagnosis},
      {"reached_pressure_kPa", r.path.reached_pressure_kPa},
      {"mass_kg", {{"tube", r.tube_mass_kg}, {"rings", r.ring_mass_kg}, {"total", r.tube_mass_kg + r.ring_mass_kg}}},
      {"curve", curve},
      {"solver", path_solver_json(r.path)},
      {"time_s", {{"mesh", r.timings.mesh_s}, {"setup", r.timings.setup_s}, {"solve", r.timings.solve_s},
                  {"assembly", r.timings.assembly_s},
                  {"factorize", r.path.factorize_s}, {"total", r.timings.total_s}}}};
  summary["solver"]["energy_evaluations"] = r.timings.evaluations;
  add_failure_json(summary, r.path);
  write_json_file(dir, "summary.json", summary);
  std::string series;
  if (config.output.vtu) {
    write_vtu(dir + "/deformed.vtu", r);
    series = write_deformed_series(dir, r.mesh, r.curve_positions, pressures_of(r.curve));
  }

  out << "\noutcome: " << fem::to_string(r.path.outcome) << " — " << r.path.diagnosis << "\n";
  if (!r.curve.empty())
    out << std::fixed << std::setprecision(3) << "extension at " << r.curve.back().pressure_kPa
        << " kPa: " << r.curve.back().extension_mm << " mm\n";
  out << std::setprecision(4) << "mass: " << 1e3 * (r.tube_mass_kg + r.ring_mass_kg) << " g (tube "
      << 1e3 * r.tube_mass_kg << " g, rings " << 1e3 * r.ring_mass_kg << " g)\n"
      << "model: axisymmetric " << r.element_name << ", " << r.mesh.num_elements() << " elements, " << r.dofs << " dofs; "
      << r.path.path.stats.steps << " load steps, " << r.path.path.stats.newton_iterations << " Newton iterations, "
      << std::setprecision(3) << r.timings.total_s << " s\n"
      << "written: " << dir << "/curve.csv, " << dir << "/summary.json" << (config.output.vtu ? ", " + dir + "/deformed.vtu" : "") << series
      << "\n";
  return summary;
}

}  // namespace softarm::engine

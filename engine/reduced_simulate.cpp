#include "engine/reduced_simulate.hpp"

#include <iomanip>
#include <iostream>

#include "engine/path_summary.hpp"
#include "engine/report/output_files.hpp"
#include "engine/spl_report.hpp"
#include "fem/io/vtu_writer.hpp"
#include "fem/scenes/reduced_scenes.hpp"
#include "fem/scenes/solver_work_json.hpp"
#include "fem/scenes/spl_cell_rod.hpp"
#include "fem/scenes/tca_cell_rod.hpp"
#include "studies/progress_bar.hpp"

namespace softarm::engine {
namespace {

/// Prints and writes a two-column curve.
void write_curve(const fem::SceneConfig& config, const std::string& column, const std::vector<double>& p,
                 const std::vector<double>& y) {
  std::ofstream csv = open_output_file(config.output.directory, "curve.csv");
  csv << "pressure_kPa," << column << "\n";
  std::cout << std::setw(14) << "pressure_kPa" << std::setw(16) << column << "\n";
  for (std::size_t i = 0; i < p.size() && i < y.size(); ++i) {
    csv << p[i] << "," << y[i] << "\n";
    std::cout << std::fixed << std::setprecision(2) << std::setw(14) << p[i] << std::setprecision(3) << std::setw(16)
              << y[i] << "\n";
  }
  std::cout.unsetf(std::ios::floatfield);
}

/// centreline.vtu: the rod's centreline at each state, one polyline per state from the clamp to the
/// tip, with `field` (the state's pressure or load fraction) as cell data for ParaView to colour by.
/// A few kilobytes: written whatever output.vtu says (that switch is for the FEM's deformed mesh).
/// Returns the words for the "written:" line.
template <class State>
std::string write_centrelines(const fem::SceneConfig& config, const std::vector<State>& states, const std::string& field,
                              double (*value)(const State&)) {
  std::vector<std::vector<Eigen::Vector3d>> lines;
  fem::NamedField per_line{field, 1, {}};
  for (const State& s : states) {
    lines.push_back(s.centreline_mm);
    per_line.values.push_back(value(s));
  }
  fem::write_polyline_vtu(config.output.directory + "/centreline.vtu", lines, per_line);
  return ", " + config.output.directory + "/centreline.vtu";
}

double load_fraction_of(const fem::SplState& s) { return s.load_fraction; }
double pressure_of(const fem::CellRodState& s) { return s.pressure_kPa; }

nlohmann::json model_json(const fem::SceneConfig& config) {
  const auto& s = *config.selection;
  return {{"name", s.level.name},
          {"expected_error_percent", s.level.error_percent},
          {"error_measure", s.level.error_measure},
          {"reason", s.reason}};
}

int simulate_reduced_spl(const fem::SceneConfig& config) {
  const auto& dir = config.output.directory;
  SplCurveWriter writer(dir, std::cout);
  const fem::ReducedSplResult r = fem::run_reduced_spl(config.spl);
  for (const auto& s : r.curve) writer.add(s);
  const fem::SpatialRodState& f = r.final_state;
  std::cout << "\noutcome: " << (f.converged ? "completed" : "stopped — " + f.diagnosis) << "\n";
  print_joint_table(r.joints, std::cout);
  const auto& m = r.part_masses;
  std::cout << std::setprecision(1) << "mass: " << 1e3 * r.mass_kg << " g (tube " << 1e3 * m.tube << " g, rings "
            << 1e3 * m.rings << " g, sheath " << 1e3 * m.sheath << " g, connectors " << 1e3 * m.connectors
            << " g)\n" << std::setprecision(3) << "spatial rod, " << r.nodes << " nodes, " << r.seconds << " s\n";
  std::cout.unsetf(std::ios::floatfield);
  nlohmann::json segments = nlohmann::json::array();
  for (const auto& e : r.segment_extremes)
    segments.push_back({{"tube_max_stretch", e.tube_max_stretch}, {"tube_min_stretch", e.tube_min_stretch},
                        {"sheath_max_stretch", e.sheath_max_stretch}, {"sheath_min_stretch", e.sheath_min_stretch},
                        {"chamber_max_stretch", e.chamber_max_stretch}});
  write_json_file(dir, "summary.json",
                  {{"scene", "spl"}, {"model", model_json(config)}, {"outcome", f.converged ? "completed" : "stopped"},
                   {"diagnosis", f.diagnosis}, {"reached_load_fraction", r.curve.empty() ? 0.0 : r.curve.back().load_fraction},
                   {"joints", joints_json(r.joints)},
                   {"mass_kg", {{"tube", m.tube}, {"rings", m.rings}, {"sheath", m.sheath}, {"connectors", m.connectors},
                                {"total", r.mass_kg}}},
                   {"segment_fibre_extremes", segments}, {"rod_nodes", r.nodes}, {"seconds", r.seconds}});
  const std::string centrelines = write_centrelines(config, r.curve, "load_fraction", load_fraction_of);
  std::cout << "written: " << dir << "/curve.csv, " << dir << "/summary.json" << centrelines << "\n";
  return f.converged ? 0 : 1;
}

int simulate_cell_rod_tca(const fem::SceneConfig& config) {
  const auto& dir = config.output.directory;
  const fem::TcaSceneSpec& spec = config.tca;
  std::cout << "cell rod: the ring-pitch cells and end cells along the pressure ramp, side by side\n" << std::flush;
  const fem::CellRodTcaResult r = fem::run_cell_rod_tca(spec, studies::task_progress(std::cout, "cells"));
  std::cout << "cell rod: ring-pitch cells about rings";
  for (int ring : r.rings) std::cout << " " << ring;
  std::cout << " (" << r.cell_dofs << " dofs each";
  if (r.end_rings > 0)
    std::cout << "; both ends through " << r.end_rings << " rings, " << r.end_cell_dofs << " dofs each";
  std::cout << ", " << std::setprecision(3) << r.cell_seconds << " s), the rod " << r.rod_seconds << " s\n";
  if (r.spatial) std::cout << "(the loads leave one plane: the spatial cell rod, with the cells' torsion)\n";
  if (!r.end_cells_note.empty()) std::cout << "(" << r.end_cells_note << ")\n";
  std::ofstream csv = open_output_file(dir, "curve.csv");
  // The tip in the bend's frame: along the pressures' bend, across it (e_z × bend: the sideways sag
  // of a load out of the bend's plane, 0 on the planar rod) and along z.
  csv << "pressure_kPa,bending_angle_deg,tip_along_bend_mm,tip_across_bend_mm,tip_z_mm\n";
  std::cout << std::setw(14) << "pressure_kPa" << std::setw(14) << "bending_deg" << std::setw(18) << "tip_along_bend_mm"
            << std::setw(19) << "tip_across_bend_mm" << std::setw(12) << "tip_z_mm" << "\n";
  for (const auto& s : r.curve) {
    csv << s.pressure_kPa << "," << s.bending_angle_deg << "," << s.tip_along_bend_mm << "," << s.tip_across_bend_mm
        << "," << s.tip_z_mm << "\n";
    std::cout << std::fixed << std::setprecision(2) << std::setw(14) << s.pressure_kPa << std::setprecision(3)
              << std::setw(14) << s.bending_angle_deg << std::setw(18) << s.tip_along_bend_mm << std::setw(19)
              << s.tip_across_bend_mm << std::setw(12) << s.tip_z_mm << "\n";
  }
  std::cout.unsetf(std::ios::floatfield);
  std::cout << spec.target_bending_deg << "° ";
  if (r.target_pressure_kPa) std::cout << "at " << std::fixed << std::setprecision(2) << *r.target_pressure_kPa << " kPa\n";
  else std::cout << "not reached\n";
  std::cout.unsetf(std::ios::floatfield);
  // A cell's or an end's limit point is a result (the 3CA balloons there), as on the 3D model.
  if (!r.converged) std::cout << "outcome: " << fem::to_string(r.outcome) << " — " << r.diagnosis << "\n";
  nlohmann::json curve = nlohmann::json::array();
  for (const auto& s : r.curve)
    curve.push_back({{"pressure_kPa", s.pressure_kPa}, {"bending_angle_deg", s.bending_angle_deg},
                     {"tip_along_bend_mm", s.tip_along_bend_mm}, {"tip_across_bend_mm", s.tip_across_bend_mm},
                     {"tip_z_mm", s.tip_z_mm}});
  write_json_file(dir, "summary.json",
                  {{"scene", "tca"}, {"model", model_json(config)}, {"curve", curve},
                   {"target_pressure_kPa", r.target_pressure_kPa ? nlohmann::json(*r.target_pressure_kPa) : nlohmann::json()},
                   {"cell_rings", r.rings}, {"cell_dofs", r.cell_dofs},
                   {"end_cell_rings", r.end_rings}, {"end_cell_dofs", r.end_cell_dofs},
                   {"end_cells_note", r.end_cells_note}, {"rod", r.spatial ? "spatial" : "planar"},
                   {"outcome", fem::to_string(r.outcome)}, {"reached_pressure_kPa", r.reached_pressure_kPa},
                   {"diagnosis", r.diagnosis}, {"cell_seconds", r.cell_seconds}, {"rod_seconds", r.rod_seconds},
                   {"solver", fem::solver_work_to_json(r.work)}});
  const std::string centrelines = write_centrelines(config, r.curve, "pressure_kPa", pressure_of);
  std::cout << "written: " << dir << "/curve.csv, " << dir << "/summary.json" << centrelines << "\n";
  return fem::is_answer(r.outcome) ? 0 : 1;
}

int simulate_cell_rod_spl(const fem::SceneConfig& config) {
  const auto& dir = config.output.directory;
  std::cout << "cell rod: ring-pitch cells of each segment about its first, middle and last rings\n";
  std::cout << std::flush;
  const fem::SplCells c = fem::spl_cells(config.spl, fem::kDefaultCellLevels, {}, true, {}, studies::task_progress(std::cout, "cells"));
  const fem::SplCellRodResult r = fem::pose_spl_cell_rod(c, config.spl.output_levels);
  nlohmann::json cells = nlohmann::json::array();
  for (int n = 0; n < 3; ++n) {
    std::cout << "segment " << n + 1 << ": rings";
    for (int ring : c.rings[n]) std::cout << " " << ring;
    std::cout << (c.half_model[n] ? ", half model" : ", full model");
    if (c.end_rings[n] > 0)
      std::cout << "; end cells through " << c.end_rings[n] << " rings (top bonded to its connector, bottom "
                << (fem::spl_end_support(n, fem::TcaEnd::bottom) == fem::EndFaceSupport::bonded ? "bonded to its connector)"
                                                                                                 : "free: the tip)");
    nlohmann::json segment = {{"segment", n + 1}, {"rings", c.rings[n]}, {"half_model", c.half_model[n]},
                              {"end_rings", c.end_rings[n]}};
    // The segment's twist per torque at rest as the rod integrates it, with its bonded ends' own
    // twist (fem/scenes/twist_compliance.hpp) and on its cells' GJ alone: what the ends change.
    const std::size_t piece = 2 * n + 1;
    if (c.failure.empty() && piece < c.rod.pieces.size()) {
      fem::SpatialCellRodSpec cells_alone = c.rod;
      for (auto& e : cells_alone.pieces[piece].ends) e.twist_compliance_per_Nmm = 0;
      const double with_ends = fem::spatial_cell_rod_twist_compliance(c.rod, piece);
      const double alone = fem::spatial_cell_rod_twist_compliance(cells_alone, piece);
      std::cout << std::setprecision(4) << "; twist at rest " << with_ends << " rad/(N·mm) (cells' GJ alone " << alone << ")";
      std::cout.unsetf(std::ios::floatfield);
      segment["twist_compliance_at_rest_rad_per_Nmm"] = with_ends;
      segment["twist_compliance_cells_alone_rad_per_Nmm"] = alone;
    }
    std::cout << "\n";
    cells.push_back(segment);
  }
  if (!c.end_cells_note.empty()) std::cout << "(" << c.end_cells_note << ")\n";
  std::cout << std::setprecision(3) << c.cells << " cells (up to " << c.largest_cell_dofs << " dofs) and " << c.end_cells
            << " end cells (up to " << c.largest_end_cell_dofs << " dofs) in " << c.seconds << " s, the rod "
            << r.rod_seconds << " s\n";
  SplCurveWriter writer(dir, std::cout, "fixed_point");
  for (const auto& s : r.curve) writer.add(s);
  std::cout << "\noutcome: " << (r.converged ? "completed" : "stopped — " + r.diagnosis) << "\n";
  print_joint_table(r.joints, std::cout);
  std::cout << std::setprecision(1) << "mass: " << 1e3 * r.mass_kg << " g (cells' smeared mass and connectors)\n";
  std::cout.unsetf(std::ios::floatfield);
  write_json_file(dir, "summary.json",
                  {{"scene", "spl"}, {"model", model_json(config)}, {"outcome", fem::to_string(r.outcome)},
                   {"diagnosis", r.diagnosis}, {"reached_load_fraction", r.reached_level},
                   {"joints", joints_json(r.joints)}, {"mass_kg", r.mass_kg}, {"cells", cells},
                   {"largest_cell_dofs", c.largest_cell_dofs}, {"end_cells", c.end_cells},
                   {"largest_end_cell_dofs", c.largest_end_cell_dofs}, {"end_cells_note", c.end_cells_note},
                   {"cell_seconds", c.seconds},
                   {"rod_seconds", r.rod_seconds}, {"solver", fem::solver_work_to_json(c.work)}});
  const std::string centrelines = write_centrelines(config, r.curve, "load_fraction", load_fraction_of);
  std::cout << "written: " << dir << "/curve.csv, " << dir << "/summary.json" << centrelines << "\n";
  return r.converged ? 0 : 1;
}

}  // namespace

int simulate_reduced(const fem::SceneConfig& config) {
  if (config.scene == "tca" && config.cell_rod) return simulate_cell_rod_tca(config);
  if (config.scene == "spl" && config.cell_rod) return simulate_cell_rod_spl(config);
  if (config.scene == "spl") return simulate_reduced_spl(config);
  if (config.scene == "rra") {
    const fem::ReducedRraResult r = fem::run_reduced_rra(config.rra);
    write_curve(config, "extension_mm", r.pressure_kPa, r.extension_mm);
    std::cout << "extension at " << r.pressure_kPa.back() << " kPa: " << r.extension_mm.back() << " mm (rod, "
              << r.seconds << " s)\n";
    write_json_file(config.output.directory, "summary.json",
                    {{"scene", "rra"}, {"model", model_json(config)}, {"pressure_kPa", r.pressure_kPa},
                     {"extension_mm", r.extension_mm}, {"seconds", r.seconds}});
    std::cout << "written: " << config.output.directory << "/curve.csv, " << config.output.directory << "/summary.json\n";
    return 0;
  }
  const fem::ReducedTcaResult r = fem::run_reduced_tca(config.tca);
  write_curve(config, "bending_deg", r.pressure_kPa, r.bending_deg);
  std::cout << "mass " << r.mass_kg * 1e3 << " g; " << config.tca.target_bending_deg << "° ";
  if (r.target_pressure_kPa) std::cout << "at " << *r.target_pressure_kPa << " kPa";
  else std::cout << "not reached";
  std::cout << " (rod, " << r.nodes << " nodes, " << r.seconds << " s)\n";
  if (r.spatial) std::cout << "(the loads leave the x–z plane: the spatial rod)\n";
  if (!r.converged) std::cout << "outcome: stopped — " << r.diagnosis << "\n";
  write_json_file(config.output.directory, "summary.json",
                  {{"scene", "tca"}, {"model", model_json(config)}, {"pressure_kPa", r.pressure_kPa},
                   {"bending_deg", r.bending_deg},
                   {"target_pressure_kPa", r.target_pressure_kPa ? nlohmann::json(*r.target_pressure_kPa) : nlohmann::json()},
                   {"rod", r.spatial ? "spatial" : "planar"}, {"outcome", r.converged ? "completed" : "stopped"},
                   {"diagnosis", r.diagnosis}, {"mass_kg", r.mass_kg}, {"seconds", r.seconds}});
  std::cout << "written: " << config.output.directory << "/curve.csv, " << config.output.directory << "/summary.json\n";
  return r.converged ? 0 : 1;
}

}  // namespace softarm::engine

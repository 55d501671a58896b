#include "engine/workspace/workspace_command.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>

#include "engine/options/option_checks.hpp"
#include "engine/report/output_files.hpp"
#include "engine/workspace/cells_cache.hpp"
#include "engine/workspace/reach.hpp"
#include "engine/workspace/workspace_margins.hpp"
#include "engine/workspace/workspace_report.hpp"
#include "fem/core/input_error.hpp"
#include "fem/core/thesis_values.hpp"
#include "fem/core/number_text.hpp"
#include "fem/io/vtu_writer.hpp"
#include "studies/progress_bar.hpp"
#include "studies/workspace.hpp"

namespace softarm::engine {
namespace {

void write_points_csv(const std::string& dir, const studies::WorkspaceResult& w) {
  std::ofstream csv = open_output_file(dir, "points.csv");
  csv << std::setprecision(10);
  for (int k = 1; k <= 9; ++k) csv << "p" << k << "_kPa,";
  csv << "reached,tip_x_mm,tip_y_mm,tip_z_mm,axis_x,axis_y,axis_z,tip_tilt_deg,chamber_stretch_1,chamber_stretch_2,"
         "chamber_stretch_3,peak_stretch,peak_segment,peak_extrapolated,payload_margin_kg,payload_margin_at_least,"
         "pressure_sum_kPa,why\n";
  for (const studies::WorkspacePoint& p : w.points) {
    for (double x : p.pressure_kPa) csv << x << ",";
    csv << (p.ok ? 1 : 0);
    if (p.ok)
      csv << "," << p.tip_mm.x() << "," << p.tip_mm.y() << "," << p.tip_mm.z() << "," << p.tip_axis.x() << ","
          << p.tip_axis.y() << "," << p.tip_axis.z() << "," << p.tip_tilt_deg << "," << p.chamber_stretch[0] << ","
          << p.chamber_stretch[1] << "," << p.chamber_stretch[2] << "," << p.peak.stretch << "," << p.peak.segment
          << "," << (p.peak.extrapolated ? 1 : 0) << ",";
    else
      csv << ",,,,,,,,,,,,,,";
    if (p.payload_margin_kg) csv << *p.payload_margin_kg << "," << (p.payload_margin_at_least ? 1 : 0);
    else csv << ",";
    csv << "," << p.pressure_sum_kPa << "," << csv_text(p.why) << "\n";
  }
}

/// The reached tips, with each chamber's pressure, the pressure sum, the tilt and the axis as fields.
void write_points_vtu(const std::string& dir, const studies::WorkspaceResult& w) {
  std::vector<Eigen::Vector3d> tips;
  std::vector<fem::NamedField> fields;
  for (int k = 1; k <= 9; ++k) fields.push_back({"p" + std::to_string(k) + "_kPa", 1, {}});
  fields.push_back({"pressure_sum_kPa", 1, {}});
  fields.push_back({"tip_tilt_deg", 1, {}});
  fields.push_back({"tip_axis", 3, {}});
  fields.push_back({"peak_stretch", 1, {}});
  for (const studies::WorkspacePoint& p : w.points) {
    if (!p.ok) continue;
    tips.push_back(p.tip_mm);
    for (int k = 0; k < 9; ++k) fields[k].values.push_back(p.pressure_kPa[k]);
    fields[9].values.push_back(p.pressure_sum_kPa);
    fields[10].values.push_back(p.tip_tilt_deg);
    fields[11].values.insert(fields[11].values.end(), {p.tip_axis.x(), p.tip_axis.y(), p.tip_axis.z()});
    fields[12].values.push_back(p.peak.stretch);
  }
  fem::write_point_cloud_vtu(dir + "/workspace.vtu", tips, fields);
}

/// The margins computed: how many, their range and median, and what they cost.
nlohmann::json margins_json(const studies::WorkspaceResult& w, double seconds) {
  std::vector<double> m;
  int at_least = 0;
  for (const studies::WorkspacePoint& p : w.points)
    if (p.payload_margin_kg) m.push_back(*p.payload_margin_kg), at_least += p.payload_margin_at_least ? 1 : 0;
  nlohmann::json j = {{"poses", m.size()}, {"seconds", seconds}, {"bracket_end_held", at_least}};
  if (m.empty()) return j;
  std::sort(m.begin(), m.end());
  j["smallest_kg"] = m.front();
  j["median_kg"] = m[m.size() / 2];
  j["largest_kg"] = m.back();
  return j;
}

/// The chosen poses' centrelines (posed again on the rod's own interval), each with its sample's index.
void write_centrelines_vtu(const std::string& dir, const fem::SplPressureCells& cells, const studies::WorkspaceResult& w,
                           const std::optional<double>& payload_kg) {
  std::vector<std::vector<Eigen::Vector3d>> lines;
  fem::NamedField sample{"sample", 1, {}};
  for (std::size_t i : studies::extent_poses(w)) {
    const fem::SpatialCellRodState s = fem::pose_at_pressures(cells, w.points[i].pressure_kPa, nullptr, payload_kg);
    if (!s.ok) continue;
    lines.push_back(s.position);
    sample.values.push_back(static_cast<double>(i));
  }
  fem::write_polyline_vtu(dir + "/centrelines.vtu", lines, sample);
}

nlohmann::json vector_json(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

/// The poses not reached: beyond the cells' reach (a segment past where a ray's cells stopped), or no
/// equilibrium of the rod.
std::pair<int, int> not_reached(const studies::WorkspaceResult& w) {
  int beyond = 0, other = 0;
  for (const studies::WorkspacePoint& p : w.points)
    if (!p.ok) ++(p.beyond_cells ? beyond : other);
  return {beyond, other};
}

/// The largest peak stretch of the tube over the reached poses, where it is, and how many poses read
/// the lone RRAs' maps beyond their FEM paths.
nlohmann::json peaks_json(const studies::WorkspaceResult& w, const fem::TubePeakMaps& maps,
                          const fem::Material& tube) {
  const studies::WorkspacePoint* top = nullptr;
  int extrapolated = 0;
  for (const studies::WorkspacePoint& p : w.points) {
    if (!p.ok) continue;
    if (!top || p.peak.stretch > top->peak.stretch) top = &p;
    extrapolated += p.peak.extrapolated ? 1 : 0;
  }
  nlohmann::json j = {{"poses_extrapolated", extrapolated}, {"maps_seconds", maps.seconds}};
  // The stretch the tube's law was fitted to (null where its elongation at break is unknown).
  const double trusted = fem::trusted_stretch_limit(tube);
  j["tube_trusted_stretch"] = std::isfinite(trusted) ? nlohmann::json(trusted) : nlohmann::json(nullptr);
  if (top) {
    j["largest"] = top->peak.stretch;
    j["segment"] = top->peak.segment;
    j["pressures_kPa"] = top->pressure_kPa;
  }
  j["rra_paths_kPa"] = nlohmann::json::array();
  for (const fem::RraCalibration& c : maps.segment) j["rra_paths_kPa"].push_back(c.last_pressure_kPa);
  return j;
}

nlohmann::json summary_json(const WorkspaceOptions& o, const fem::SplPressureCells& cells,
                            const studies::WorkspaceResult& w) {
  nlohmann::json j = {{"scene", o.scene},
                      {"max_pressure_kPa", *o.max_pressure_kPa},
                      {"direction_divisions", o.divisions},
                      {"rays", cells.directions.size()},
                      {"cells_seconds", cells.seconds},
                      {"samples", w.points.size()},
                      {"reached", w.reached},
                      {"poses_seconds", w.pose_seconds},
                      {"poses_per_second", w.poses_per_second},
                      {"voxel_mm", o.voxel_mm},
                      {"occupied_volume_mm3", w.occupied_volume_mm3}};
  if (o.payload_kg) j["payload_kg"] = *o.payload_kg;
  if (w.reached > 0) j["extent_mm"] = {{"lower", vector_json(w.lower_mm)}, {"upper", vector_json(w.upper_mm)}};
  if (!cells.failure.empty()) j["failure"] = cells.failure;
  const auto [beyond, other] = not_reached(w);
  j["not_reached"] = {{"beyond_the_cells", beyond}, {"no_equilibrium", other}};
  j["cells_notes"] = nlohmann::json::array();
  for (const fem::SplCells& ray : cells.rays) j["cells_notes"].push_back(ray.notes);
  return j;
}
/// The run's answer on the console: the poses reached and their cost, the extent and volume, the peak
/// stretch, the payload margins where computed, and why poses were not reached.
void print_summary(std::ostream& out, const WorkspaceOptions& o, const fem::SplPressureCells& cells,
                   const studies::WorkspaceResult& w, const nlohmann::json& summary, double margin_seconds) {
  out << std::fixed << std::setprecision(1) << "workspace: " << w.reached << " of " << w.points.size()
      << " poses reached (cells " << cells.seconds << " s; poses " << std::setprecision(2) << w.pose_seconds
      << " s, " << std::setprecision(0) << w.poses_per_second << " per second)\n";
  if (w.reached > 0)
    out << std::setprecision(1) << "  extent x " << w.lower_mm.x() << " to " << w.upper_mm.x() << ", y "
        << w.lower_mm.y() << " to " << w.upper_mm.y() << ", z " << w.lower_mm.z() << " to " << w.upper_mm.z()
        << " mm; occupied volume " << std::setprecision(2) << w.occupied_volume_mm3 * 1e-6 << " L at "
        << o.voxel_mm << " mm cubes\n";
  if (summary.at("peak_stretch").contains("largest"))
    out << std::setprecision(3) << "  the tube's peak stretch: up to "
        << summary.at("peak_stretch").at("largest").get<double>() << " (segment "
        << summary.at("peak_stretch").at("segment").get<int>() << "; the tube's law is fitted up to "
        << (summary.at("peak_stretch").at("tube_trusted_stretch").is_number()
                ? fem::number_text(summary.at("peak_stretch").at("tube_trusted_stretch").get<double>())
                : std::string("an unknown stretch"))
        << ")\n";
  if (summary.contains("payload_margin") && summary.at("payload_margin").contains("median_kg"))
    out << std::setprecision(2) << "  payload margin at " << summary.at("payload_margin").at("poses").get<int>()
        << " poses: " << summary.at("payload_margin").at("smallest_kg").get<double>() << " to "
        << summary.at("payload_margin").at("largest_kg").get<double>() << " kg, median "
        << summary.at("payload_margin").at("median_kg").get<double>() << " kg (" << std::setprecision(0)
        << margin_seconds << " s)\n";
  if (const auto [beyond, other] = not_reached(w); beyond + other > 0) {
    out << "  not reached: " << beyond << " beyond where the cells reached, " << other << " without an equilibrium";
    if (beyond > 0) out << "; the cells' stops: " << cells.rays.front().notes;
    out << "\n";
  }
  out.unsetf(std::ios::floatfield);
}
}  // namespace

CLI::App* add_workspace_command(CLI::App& app, WorkspaceOptions& o) {
  CLI::App* ws = app.add_subcommand(
      "workspace", "where the arm's tip can go: poses over all nine chamber pressures on the arm's cells (an spl scene)");
  ws->add_option("scene", o.scene,
                 "spl scene JSON file (its design, materials, gravity and tip mass), or a requirements file (its arm, "
                 "working pressure and payload)")
      ->required();
  ws->add_option("--design", o.design, "with a requirements file: a design run's summary.json, whose optimum is posed");
  ws->add_option("-o,--output", o.output, "output directory")->capture_default_str();
  ws->add_option("--max-pressure-kPa", o.max_pressure_kPa,
                 "every chamber's bound (default: the requirements' working pressure, else the thesis' 344.7)")
      ->check(finite_in(1, 1000, "kPa"));
  ws->add_option("--samples", o.samples, "pressure vectors posed (the 512 corners of the pressure space first)")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  ws->add_option("--directions", o.divisions,
                 "divisions of each segment's direction grid: (n+1)(n+2)/2 rays of cells (fem/reduced/pressure_space.hpp)")
      ->check(CLI::Range(1, 4))
      ->capture_default_str();
  ws->add_option("--payload-kg", o.payload_kg, "mass at the tip (default: the requirements' payload, else the scene's load.tip_mass_kg)")
      ->check(finite_in(0, 10, "kg"));
  ws->add_option("--voxel-mm", o.voxel_mm, "edge of the cubes the occupied volume counts")
      ->check(finite_in(0.1, 1000, "mm"))
      ->capture_default_str();
  ws->add_option("--colour-by", o.colour_by, "the report's colouring")
      ->check(CLI::IsMember({"pressure_sum", "tip_tilt", "peak_stretch", "payload_margin"}))
      ->capture_default_str();
  ws->add_option("--margin-poses", o.margin_poses,
                 "poses whose payload margin is computed, the first reached of the sequence after the corners (a "
                 "continuation in the tip mass each, about 40 s on the thesis arm; default 24 where coloured by it, else none)")
      ->check(CLI::Range(0, 100000));
  return ws;
}

int run_workspace(const WorkspaceOptions& given) {
  const ArmInput arm = read_arm_input(given.scene, given.design);
  WorkspaceOptions o = given;  // the bound and the payload resolved: the option's, else the file's
  o.max_pressure_kPa = given.max_pressure_kPa.value_or(arm.max_pressure_kPa.value_or(fem::thesis::kWorkingPressure_kPa));
  if (!o.payload_kg) o.payload_kg = arm.payload_kg;
  prepare_output_directory(o.output, "--output");
  const fem::SplPressureCells cells =
      cached_pressure_cells(arm, *o.max_pressure_kPa, o.divisions, o.output + "/cells.json", std::cout);
  if (!cells.failure.empty()) {
    std::cout << "workspace: no cells: " << cells.failure << "\n";
    write_json_file(o.output, "summary.json", summary_json(o, cells, {}));
    return 1;
  }
  studies::WorkspaceSettings settings;
  settings.samples = o.samples;
  settings.payload_kg = o.payload_kg;
  settings.voxel_mm = o.voxel_mm;
  settings.design = arm.spl.design;
  studies::WorkspaceResult w = studies::sweep_workspace(cells, settings, studies::task_progress(std::cout, "poses"));
  const fem::TubePeakMaps maps = studies::judge_workspace_peaks(w, arm.spl, *o.max_pressure_kPa);
  const int margin_count = o.margin_poses > 0 ? o.margin_poses : o.colour_by == "payload_margin" ? kDefaultMarginPoses : 0;
  const double margin_seconds =
      margin_count > 0
          ? margins_at_poses(cells, w, margin_count, o.payload_kg, studies::task_progress(std::cout, "margins"))
          : 0.0;
  write_points_csv(o.output, w);
  write_points_vtu(o.output, w);
  write_centrelines_vtu(o.output, cells, w, o.payload_kg);
  nlohmann::json summary = summary_json(o, cells, w);
  summary["peak_stretch"] = peaks_json(w, maps, arm.spl.tube_material);
  if (margin_count > 0) summary["payload_margin"] = margins_json(w, margin_seconds);
  write_json_file(o.output, "summary.json", summary);
  write_workspace_report(o.output + "/report.html", w, o.colour_by, arm.described);
  print_summary(std::cout, o, cells, w, summary, margin_seconds);
  std::cout << "written: " << o.output << "/points.csv, workspace.vtu, centrelines.vtu, summary.json, report.html, cells.json\n";
  return 0;
}

}  // namespace softarm::engine

#include "fem/scenes/spl_cell_job.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "fem/scenes/solver_work_json.hpp"
#include "fem/scenes/tca_cell.hpp"
#include "fem/scenes/twist_compliance.hpp"

namespace softarm::fem {
namespace {
using nlohmann::json;

double peak_of(const TcaSceneSpec& scene) {
  return *std::max_element(scene.chamber_pressure_kPa.begin(), scene.chamber_pressure_kPa.end());
}

void take_path(const PressurePathResult& path, CellJobResult& out) {
  out.outcome = path.outcome;
  out.reached_pressure_kPa = path.reached_pressure_kPa;
  out.estimated_limit_pressure_kPa = path.estimated_limit_pressure_kPa;
  if (path.outcome != PathOutcome::completed) out.diagnosis = path.diagnosis;
}

// JSON has no NaN: a number that is not finite travels as null (only `torsion` can be NaN).
json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }
double number(const json& j) { return j.is_null() ? std::numeric_limits<double>::quiet_NaN() : j.get<double>(); }

json vectors(const std::vector<Eigen::Vector2d>& v) {
  json a = json::array();
  for (const auto& x : v) a.push_back({x.x(), x.y()});
  return a;
}
std::vector<Eigen::Vector2d> vectors(const json& a) {
  std::vector<Eigen::Vector2d> v;
  for (const auto& x : a) v.emplace_back(x.at(0).get<double>(), x.at(1).get<double>());
  return v;
}
json matrices(const std::vector<Eigen::Matrix2d>& v) {
  json a = json::array();
  for (const auto& m : v) a.push_back({m(0, 0), m(0, 1), m(1, 0), m(1, 1)});
  return a;
}
std::vector<Eigen::Matrix2d> matrices(const json& a) {
  std::vector<Eigen::Matrix2d> v;
  for (const auto& x : a) {
    Eigen::Matrix2d m;
    m << x.at(0).get<double>(), x.at(1).get<double>(), x.at(2).get<double>(), x.at(3).get<double>();
    v.push_back(m);
  }
  return v;
}
}  // namespace

CellJobResult run_cell_job(const TcaSceneSpec& scene, int ring, bool with_torsion) {
  const TcaCellResult cell = run_tca_cell(scene, ring);
  CellJobResult out;
  out.cell = spatial_cell_table(cell, peak_of(scene));
  take_path(cell.path, out);
  out.dofs = cell.dofs;
  out.half_model = cell.model.half;
  out.work.add(cell.path, cell.dofs, cell.seconds);
  if (with_torsion) out.torsion = cell_torsion_stiffness(scene, ring);
  return out;
}

CellJobResult run_end_cell_job(const TcaSceneSpec& scene, TcaEnd end, int rings, EndFaceSupport face,
                               bool with_torsion) {
  const TcaEndCellResult cell = run_tca_end_cell(scene, end, rings, face);
  CellJobResult out;
  out.end = spatial_end_table(cell, peak_of(scene));
  take_path(cell.path, out);
  out.dofs = cell.dofs;
  out.half_model = cell.model.half;
  out.work.add(cell.path, cell.dofs, cell.seconds);
  if (with_torsion && face == EndFaceSupport::bonded) out.torsion = end_cell_twist_compliance(scene, end, rings);
  return out;
}

std::string to_text(const CellJobResult& r) {
  const SpatialCellTable& c = r.cell;
  const SpatialEndTable& e = r.end;
  const json j = {
      {"cell",
       {{"z_mm", c.z_mm},
        {"level", c.level},
        {"stretch", c.stretch},
        {"axial_compliance_per_N", c.axial_compliance_per_N},
        {"curvature_per_mm", vectors(c.curvature_per_mm)},
        {"bending_compliance_per_Nmm2", matrices(c.bending_compliance_per_Nmm2)},
        {"torsion_compliance_per_Nmm2", number(c.torsion_compliance_per_Nmm2)},
        {"mass_per_length_kg_per_mm", c.mass_per_length_kg_per_mm}}},
      {"end",
       {{"at_top", e.at_top},
        {"length_mm", e.length_mm},
        {"level", e.level},
        {"elongation_mm", e.elongation_mm},
        {"rotation_rad", vectors(e.rotation_rad)},
        {"twist_compliance_per_Nmm", number(e.twist_compliance_per_Nmm)}}},
      {"outcome", static_cast<int>(r.outcome)},
      {"reached_pressure_kPa", r.reached_pressure_kPa},
      {"estimated_limit_pressure_kPa", r.estimated_limit_pressure_kPa},
      {"diagnosis", r.diagnosis},
      {"dofs", r.dofs},
      {"half_model", r.half_model},
      {"torsion", number(r.torsion)},
      {"work", solver_work_to_json(r.work)}};
  return j.dump();
}

CellJobResult cell_job_from_text(const std::string& text) {
  const json j = json::parse(text);
  CellJobResult r;
  const json& c = j.at("cell");
  r.cell.z_mm = c.at("z_mm").get<double>();
  r.cell.level = c.at("level").get<std::vector<double>>();
  r.cell.stretch = c.at("stretch").get<std::vector<double>>();
  r.cell.axial_compliance_per_N = c.at("axial_compliance_per_N").get<std::vector<double>>();
  r.cell.curvature_per_mm = vectors(c.at("curvature_per_mm"));
  r.cell.bending_compliance_per_Nmm2 = matrices(c.at("bending_compliance_per_Nmm2"));
  r.cell.torsion_compliance_per_Nmm2 = number(c.at("torsion_compliance_per_Nmm2"));
  r.cell.mass_per_length_kg_per_mm = c.at("mass_per_length_kg_per_mm").get<double>();
  const json& e = j.at("end");
  r.end.at_top = e.at("at_top").get<bool>();
  r.end.length_mm = e.at("length_mm").get<double>();
  r.end.level = e.at("level").get<std::vector<double>>();
  r.end.elongation_mm = e.at("elongation_mm").get<std::vector<double>>();
  r.end.rotation_rad = vectors(e.at("rotation_rad"));
  r.end.twist_compliance_per_Nmm = number(e.at("twist_compliance_per_Nmm"));
  r.outcome = static_cast<PathOutcome>(j.at("outcome").get<int>());
  r.reached_pressure_kPa = j.at("reached_pressure_kPa").get<double>();
  r.estimated_limit_pressure_kPa = j.at("estimated_limit_pressure_kPa").get<double>();
  r.diagnosis = j.at("diagnosis").get<std::string>();
  r.dofs = j.at("dofs").get<int>();
  r.half_model = j.at("half_model").get<bool>();
  r.torsion = number(j.at("torsion"));
  r.work = solver_work_from_json(j.at("work"));
  return r;
}

}  // namespace softarm::fem

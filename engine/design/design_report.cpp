#include "engine/design/design_report.hpp"

#include <cmath>
#include <fstream>

#include "engine/design/design_measures.hpp"
#include "engine/design/design_problem.hpp"
#include "engine/report/html_document.hpp"
#include "engine/report/output_files.hpp"
#include "engine/report/svg_plot.hpp"
#include "fem/io/vtu_writer.hpp"
#include "fem/mesh/tca_mesher.hpp"
#include "fem/scenes/fidelity.hpp"
#include "fem/scenes/solver_work_json.hpp"
#include "objectives/fit_range.hpp"

namespace softarm::engine {

const char* purpose_name(RoundPurpose purpose) {
  switch (purpose) {
    case RoundPurpose::first_search: return "first search";
    case RoundPurpose::correction: return "correction";
    case RoundPurpose::improvement: return "improvement";
  }
  return "?";
}

namespace {
using report::format_number;

report::Series series(std::string label, std::vector<double> x, std::vector<double> y, bool dashed = false) {
  report::Series s;
  s.label = std::move(label);
  s.x = std::move(x);
  s.y = std::move(y);
  s.dashed = dashed;
  return s;
}

nlohmann::json measures_json(const objectives::ArmMeasures& m) {
  nlohmann::json segs = nlohmann::json::array();
  for (const auto& s : m.segments)
    segs.push_back({{"bending_deg_at_working_pressure", s.bending_deg_at_working},
                    {"pressure_for_target_bending_kPa", s.pressure_for_target_kPa >= 0 ? nlohmann::json(s.pressure_for_target_kPa) : nlohmann::json()},
                    {"chamber_axis_stretch", s.chamber_stretch},
                    {"peak_principal_stretch", s.peaks.stretch},
                    {"point_peak_principal_stretch", s.peaks.point_stretch},
                    {"peak_principal_stress_MPa", s.peaks.stress_MPa},
                    {"peak_log_strain", s.peaks.log_strain},
                    {"burst_utilisation", s.burst_utilisation},
                    {"safe_working_pressure_kPa", s.safe_pressure_kPa >= 0 ? nlohmann::json(s.safe_pressure_kPa) : nlohmann::json()},
                    {"burst_governing", s.governing},
                    {"lone_rra_extension_fem_mm", s.rra_fem_extension_mm},
                    {"lone_rra_extension_rod_mm", s.rra_rod_extension_mm},
                    {"rod_diagnosis", s.rod_diagnosis}});
  return {{"mass_kg", m.mass_kg},
          {"mass_by_part_kg", {{"tube", m.masses.tube}, {"rings", m.masses.rings}, {"sheath", m.masses.sheath}, {"connectors", m.masses.connectors}}},
          {"length_mm", m.length_mm},
          {"payload_kg", m.payload_kg},
          {"payload_note", m.payload_note},
          {"min_bending_deg", m.min_bending_deg},
          {"burst_utilisation", m.burst_utilisation},
          {"burst_governing", m.burst_governing},
          {"durability_peak_log_strain", m.durability_log_strain},
          {"segments", segs},
          {"seconds", m.seconds}};
}

nlohmann::json design_json(const DesignConfig& c, const std::vector<double>& x) {
  nlohmann::json j = nlohmann::json::object();
  for (std::size_t i = 0; i < c.variables.size(); ++i) {
    const auto& v = c.variables[i].variable;
    if (v.kind == optimise::VariableKind::categorical) j[v.name] = v.choices.at(static_cast<std::size_t>(std::lround(x[i])));
    else if (v.kind == optimise::VariableKind::integer) j[v.name] = std::lround(x[i]);
    else j[v.name] = x[i];
  }
  return j;
}

/// optimum_payload_pose.vtu: the arm's centreline lifting its payload capacity (in the bend's plane,
/// x and z), with the payload as cell data.
void write_pose_vtu(const std::string& dir, const objectives::ArmMeasures& m) {
  std::vector<Eigen::Vector3d> line;
  for (std::size_t i = 0; i < m.payload_tip_x_mm.size() && i < m.payload_tip_z_mm.size(); ++i)
    line.emplace_back(m.payload_tip_x_mm[i], 0.0, m.payload_tip_z_mm[i]);
  fem::write_polyline_vtu(dir + "/optimum_payload_pose.vtu", {line}, {"payload_kg", 1, {m.payload_kg}});
}

std::vector<std::vector<std::string>> constraint_rows(const DesignConfig& c, const objectives::ArmMeasures& m,
                                                      double ref) {
  const auto g = constraints_of(c, m, ref);
  const std::vector<std::string> value = {format_number(m.mass_kg) + " kg", format_number(m.payload_kg) + " kg",
                                          format_number(m.min_bending_deg) + " deg",
                                          format_number(m.burst_utilisation) + " (" + m.burst_governing + ")",
                                          format_number(m.durability_log_strain) + " (ref " + format_number(ref) + ")"};
  std::vector<std::string> values = value;
  for (const MeasureBound& b : c.extra_constraints)  // the extra bounds follow the five requirements
    values.push_back(format_number(design_measure(b.measure, "constraints").value(m, c.model, ref)));
  std::vector<std::vector<std::string>> rows;
  for (std::size_t i = 0; i < g.names.size() && i < values.size(); ++i) {
    // "!" marks a violated margin (a warning cell). Built by appends: GCC 12 warns falsely
    // (-Wrestrict, GCC bug 105329) on a const char* + std::string chain here.
    std::string margin = g.values[i] > 1e-6 ? "!" : "";
    margin += format_number(-100 * g.values[i]);
    margin += " %";
    rows.push_back({g.names[i], values[i], margin});
  }
  return rows;
}

// A round's verification in brief: the accurate model's measures and each requirement's g.
nlohmann::json verification_summary(const DesignConfig& c, const objectives::CellRodEvaluation& v, double ref_strain) {
  nlohmann::json j = {{"ok", v.ok()}, {"measures", measures_json(v.measures)}, {"g", nlohmann::json::object()}};
  if (v.ok()) {
    const auto g = constraints_of(c, v.measures, ref_strain);
    for (std::size_t i = 0; i < g.names.size(); ++i) j["g"][g.names[i]] = g.values[i];
  }
  j["all_met"] = v.ok() && meets_every_requirement(c, v.measures, ref_strain);
  return j;
}

// The check's fields, and the verdicts and the rod's error derived from them.
nlohmann::json solid_check_json(const objectives::SolidSegmentCheck& sc) {
  nlohmann::json j = objectives::to_json(sc);
  j["meets_bending_3d"] = sc.meets_bending();
  j["holds_working_pressure_3d"] = sc.holds_working_pressure();
  j["rod_bending_error_percent"] = sc.bending_error_percent();
  return j;
}
}  // namespace

nlohmann::json model_errors_json(int rra_mesh_level) {
  nlohmann::json out = nlohmann::json::array();
  const fem::FidelityLadder& tca = fem::fidelity_ladder("tca");
  const fem::ModelLevel& rod = tca.levels.front();
  out.push_back({{"what", "bending of each 3CA segment"}, {"model", rod.name}, {"error_percent", rod.error_percent},
                 {"measured_on", rod.error_measure}, {"against", tca.reference}});
  const fem::FidelityLadder& rra = fem::fidelity_ladder("rra");
  for (const fem::ModelLevel& m : rra.levels)
    if (!m.reduced && m.element_order == 2 && m.mesh_level == rra_mesh_level)
      out.push_back({{"what", "each segment's RRA (local peaks, limit point)"}, {"model", m.name},
                     {"error_percent", m.error_percent}, {"measured_on", m.error_measure}, {"against", rra.reference}});
  return out;
}

const std::optional<objectives::SolidSegmentCheck>& DesignRun::solid_check() const {
  static const std::optional<objectives::SolidSegmentCheck> none;
  return rounds.empty() ? none : rounds.at(answer_round).solid_check;
}

const std::optional<objectives::CellRodEvaluation>& DesignRun::verification() const {
  static const std::optional<objectives::CellRodEvaluation> none;
  return rounds.empty() ? none : rounds.at(answer_round).verification;
}

namespace {
// summary.json's "verification": the final design on the accurate model, every requirement's value
// and margin there, whether all are met, and the search model's error at that design.
nlohmann::json verification_json(const DesignRun& run) {
  const DesignConfig& c = *run.config;
  const objectives::CellRodEvaluation& v = *run.verification();
  nlohmann::json j = {{"model", v.model},
                      {"ok", v.ok()},
                      {"failure", v.failure},
                      {"cells", v.cells},
                      {"end_cells", v.end_cells},
                      {"largest_cell_dofs", v.largest_cell_dofs},
                      {"cell_seconds", v.cell_seconds},
                      {"cell_solver", fem::solver_work_to_json(v.cell_work)},
                      {"pose_seconds", v.pose_seconds},
                      {"poses", v.poses},
                      {"measures", measures_json(v.measures)},
                      {"requirements", nlohmann::json::object()}};
  const auto g = constraints_of(c, v.measures, run.reference_strain);
  bool all = v.ok();
  for (std::size_t i = 0; i < g.names.size(); ++i) {
    const bool met = g.values[i] <= 1e-9;
    all = all && met;
    j["requirements"][g.names[i]] = {{"g", g.values[i]}, {"margin_percent", -100 * g.values[i]}, {"met", met}};
  }
  j["all_met"] = all;
  j["fit_range"] = objectives::to_json(objectives::check_fit_range(v.measures, make_candidate(c, run.optimum_x).tube));
  const objectives::ArmMeasures& s = run.optimum_uncorrected;
  const auto error = [](double search, double accurate) {
    return std::abs(accurate) > 1e-12 ? nlohmann::json(100 * (search - accurate) / std::abs(accurate)) : nlohmann::json();
  };
  j["search_model_error_percent"] = {{"payload_kg", error(s.payload_kg, v.measures.payload_kg)},
                                     {"min_bending_deg", error(s.min_bending_deg, v.measures.min_bending_deg)},
                                     {"burst_utilisation", error(s.burst_utilisation, v.measures.burst_utilisation)},
                                     {"durability_log_strain", error(s.durability_log_strain, v.measures.durability_log_strain)}};
  for (std::size_t n = 0; n < 3; ++n)
    j["search_model_error_percent"]["segment_" + std::to_string(n + 1) + "_bending_deg"] =
        error(s.segments[n].bending_deg_at_working, v.measures.segments[n].bending_deg_at_working);
  return j;
}
}  // namespace

bool verified_all_met(const DesignRun& run) {
  return run.verification() && run.verification()->ok() &&
         meets_every_requirement(*run.config, run.verification()->measures, run.reference_strain);
}

namespace {
/// summary.json: the optimum, its measures and constraints, the thesis design beside it, the
/// optimiser's record, the verification on the cell rod and each check-and-correct round.
nlohmann::json design_summary(const DesignRun& run) {
  const DesignConfig& c = *run.config;
  nlohmann::json summary = {
      {"objective", c.objective},
      {"feasible", run.result.feasible},
      {"optimum", design_json(c, run.optimum_x)},
      {"optimum_measures", measures_json(run.optimum)},
      {"optimum_constraints", nlohmann::json::object()},
      {"optimum_recheck_measures", measures_json(run.check)},
      {"optimum_finer_peaks_measures", run.finer_peaks ? measures_json(*run.finer_peaks) : nlohmann::json(nullptr)},
      {"search_margin", c.search_margin},
      {"thesis", design_json(c, run.thesis_x)},
      {"thesis_measures", measures_json(run.thesis)},
      {"optimiser", {{"algorithm", c.optimiser.algorithm}, {"evaluations", run.result.evaluations},
                     {"cache_hits", run.result.cache_hits}, {"seconds", run.result.seconds},
                     {"stop_reason", run.result.stop_reason}}},
      {"durability_reference_log_strain", run.reference_strain},
      {"model_errors", model_errors_json(c.check.rra_mesh_level)},
      {"seconds", run.seconds}};
  const auto g = constraints_of(c, run.optimum, run.reference_strain);
  for (std::size_t i = 0; i < g.names.size(); ++i) summary["optimum_constraints"][g.names[i]] = g.values[i];
  if (run.solid_check()) summary["optimum_solid_check"] = solid_check_json(*run.solid_check());
  if (run.thesis_verification)
    summary["thesis_verification"] = verification_summary(c, *run.thesis_verification, run.reference_strain);
  if (c.verify_on_cells) {
    summary["verification"] = run.verification() ? verification_json(run) : nlohmann::json();
    summary["feasible"] = verified_all_met(run);  // the accurate model decides (false where it could not run)
    summary["feasible_on_search_model"] = run.result.feasible;
  }
  summary["check_and_correct"] = nlohmann::json::array();
  for (const SearchRound& r : run.rounds)
    summary["check_and_correct"].push_back(
        {{"purpose", purpose_name(r.purpose)},
         {"correction", {{"bending_factor", r.correction.bending_factor},
                         {"burst_utilisation_factor", r.correction.burst_factor},
                         {"from_3d_checks", r.correction.checks}}},
         {"verification", r.verification ? verification_summary(c, *r.verification, run.reference_strain) : nlohmann::json()},
         {"optimum", design_json(c, r.optimum_x)},
         {"feasible_corrected_search_model", r.feasible},
         {"mass_kg", r.optimum.mass_kg},
         {"solid_check", r.solid_check ? solid_check_json(*r.solid_check) : nlohmann::json()}});
  summary["rounds_stop_reason"] = run.rounds_stop_reason;
  return summary;
}

/// optimum_payload_pose.vtu (the rod's pose lifting the payload) and optimum_mesh.vtu, the optimum's
/// 3D geometry.
void write_design_geometry(const DesignRun& run) {
  const DesignConfig& c = *run.config;
  const std::string& dir = c.output_directory;
  write_pose_vtu(dir, run.optimum);
  // The optimum's 3D geometry (Hex8, level 1) with part ids, for ParaView next to the pose.
  fem::SolidMeshOptions mesh_options;
  mesh_options.order = 1;
  const fem::Mesh mesh = fem::mesh_spl(make_candidate(c, run.optimum_x).design, mesh_options);
  fem::write_vtu((std::filesystem::path(dir) / "optimum_mesh.vtu").string(), mesh, mesh.X, {}, {});
}

/// The report's opening verdict: whether the design meets every requirement, on which model.
void add_verdict(report::HtmlDocument& doc, const DesignRun& run) {
  const DesignConfig& c = *run.config;
  const bool verified = c.verify_on_cells;  // asked for: a verification that could not run is no verdict of feasibility
  const bool feasible = verified ? verified_all_met(run) : run.result.feasible;
  doc.paragraph(std::string(feasible ? (verified ? "The design meets every requirement on the accurate model (the cell rod)."
                                                 : "A design meets every requirement of the search model.")
                                     : (verified ? "The design found does NOT meet every requirement on the accurate model "
                                                   "(the cell rod); the closest is shown."
                                                 : "No design within the bounds meets every requirement; the closest is shown.")) +
                " Objective: " + c.objective + ". Optimiser: " + c.optimiser.algorithm + ", " +
                std::to_string(run.result.evaluations) + " evaluations, " + format_number(run.result.seconds) + " s (" +
                run.result.stop_reason + "). Total run " + format_number(run.seconds) + " s.");
}

/// The optimal parameters beside the thesis design's, with their bounds.
void add_parameters(report::HtmlDocument& doc, const DesignRun& run) {
  const DesignConfig& c = *run.config;
  doc.heading(2, "Optimal parameters");
  std::vector<std::vector<std::string>> rows;
  const auto od = design_json(c, run.optimum_x), td = design_json(c, run.thesis_x);
  for (const auto& v : c.variables) {
    const auto show = [](const nlohmann::json& j) { return j.is_number() ? format_number(j.get<double>()) : j.get<std::string>(); };
    rows.push_back({v.variable.name, show(od[v.variable.name]), show(td[v.variable.name]),
                    v.variable.kind == optimise::VariableKind::categorical ? "choices" : format_number(v.variable.lower) + " – " + format_number(v.variable.upper)});
  }
  doc.table({"variable", "optimum", "thesis", "bounds"}, rows);
}

/// The final design on the cell rod (the verdict), segment by segment.
void add_verification(report::HtmlDocument& doc, const DesignRun& run) {
  const DesignConfig& c = *run.config;
  const bool verified = c.verify_on_cells;
  if (verified && run.verification()->ok()) {
    const objectives::CellRodEvaluation& v = *run.verification();
    doc.heading(2, "Verification on the accurate model");
    doc.paragraph("Every requirement of the final design on the cell rod of the whole arm (" + v.model + "; cells " +
                  format_number(v.cell_seconds) + " s: " + fem::solver_work_text(v.cell_work) + "; " +
                  std::to_string(v.poses) + " rod poses " +
                  format_number(v.pose_seconds) + " s). This verdict decides feasibility; the search model only guides.");
    doc.table({"constraint", "accurate model", "margin"}, constraint_rows(c, v.measures, run.reference_strain),
              "final design on the cell rod");
    std::vector<std::vector<std::string>> seg_rows;
    for (std::size_t n = 0; n < 3; ++n)
      seg_rows.push_back({std::to_string(n + 1), format_number(v.measures.segments[n].bending_deg_at_working),
                          format_number(run.optimum_uncorrected.segments[n].bending_deg_at_working),
                          std::string(fem::to_string(v.segment_outcome[n])) + " at " + format_number(v.segment_reached_kPa[n]) + " kPa",
                          format_number(v.measures.segments[n].burst_utilisation)});
    doc.table({"segment", "bending on cells (deg)", "search model (deg)", "cells", "burst utilisation"}, seg_rows,
              "each segment alone at the working pressure, gravity against the bend");
    const auto fit = objectives::check_fit_range(v.measures, make_candidate(c, run.optimum_x).tube);
    doc.paragraph("Material range: " + fit.words + ". The burst criteria (a), (b) and the durability strain read the "
                  "tube's peaks averaged over a ball of " + format_number(c.check.peak_averaging_radius_mm) +
                  " mm radius: the point at the groove lip is a singularity (docs/definitions.md, Peak averaging "
                  "radius).");
  }
}

/// Each constraint's margin for the optimum, the thesis design and the re-check, and their chart.
void add_constraints(report::HtmlDocument& doc, const DesignRun& run) {
  const DesignConfig& c = *run.config;
  const bool verified = c.verify_on_cells;
  const auto g = constraints_of(c, run.optimum, run.reference_strain);
  doc.heading(2, "Constraints and margins");
  const bool corrected = !run.rounds.empty() && run.rounds.back().correction.checks > 0;
  doc.table({"constraint", "optimum", "margin"}, constraint_rows(c, run.optimum, run.reference_strain),
            corrected ? "optimum, search model corrected by the 3D check (" + run.rounds.back().correction.describe() + ")"
                      : std::string(verified ? "optimum, search model uncorrected (it guides the search; the verdict is the "
                                               "cell rod's, above)"
                                             : "optimum, search model"));
  doc.table({"constraint", "thesis design", "margin"}, constraint_rows(c, run.thesis, run.reference_strain),
            corrected ? "thesis design, search model (uncorrected)" : "thesis design, same model");
  doc.table({"constraint", "optimum re-checked", "margin"}, constraint_rows(c, run.check, run.check_reference_strain),
            "optimum at the check fidelity (" + std::to_string(c.check.rod_nodes_per_segment) + " rod nodes per segment, " +
                std::to_string(c.check.pressure_steps) + " pressure steps" + (corrected ? ", corrected" : "") + ")");
  if (run.finer_peaks)
    doc.paragraph("Local peaks one RRA mesh level finer: burst utilisation " + format_number(run.finer_peaks->burst_utilisation) +
                " (" + run.finer_peaks->burst_governing + "), durability strain ratio " +
                format_number(run.finer_peaks->durability_log_strain / run.finer_reference_strain) +
                " (the criteria's peaks are averages over a ball of " + format_number(c.check.peak_averaging_radius_mm) +
                " mm radius, which converge under refinement where the groove lip's point value does not: "
                "docs/definitions.md, Peak averaging radius); the durability measure is a ratio to the thesis RRA at "
                "the same level.");
  report::BarChart bars;
  bars.title = "Constraint margins of the optimum (negative: violated)";
  bars.value_label = "margin, % of the limit";
  for (std::size_t i = 0; i < g.names.size(); ++i) bars.bars.push_back({g.names[i], -100 * g.values[i], ""});
  doc.raw_html(report::render_svg(bars));

}

/// The pressure-bending curves, the payload pose and the search's convergence.
void add_curves(report::HtmlDocument& doc, const DesignRun& run) {
  const DesignConfig& c = *run.config;
  doc.heading(2, "Pressure–bending curves per segment");
  report::LinePlot bend;
  bend.title = "Bending angle vs pressure (segment alone, gravity against the bend)";
  bend.x_label = "pressure (kPa)";
  bend.y_label = "bending angle (deg)";
  bend.horizontal_lines = {{c.requirements.bending_per_segment_deg, "target"}};
  for (int n = 0; n < 3; ++n) {
    bend.series.push_back(series("optimum segment " + std::to_string(n + 1), run.optimum.segments[n].pressure_kPa,
                                 run.optimum.segments[n].bending_deg));
    bend.series.push_back(series("thesis segment " + std::to_string(n + 1), run.thesis.segments[n].pressure_kPa,
                                 run.thesis.segments[n].bending_deg, true));
  }
  doc.raw_html(report::render_svg(bend));

  doc.heading(2, "Payload pose");
  report::LinePlot pose;
  pose.title = "Hanging arm lifting its payload capacity to horizontal (at the lift pressure)";
  pose.x_label = "x (mm)";
  pose.y_label = "z (mm)";
  pose.series.push_back(series("optimum, " + format_number(run.optimum.payload_kg) + " kg", run.optimum.payload_tip_x_mm,
                               run.optimum.payload_tip_z_mm));
  pose.series.push_back(series("thesis, " + format_number(run.thesis.payload_kg) + " kg", run.thesis.payload_tip_x_mm,
                               run.thesis.payload_tip_z_mm, true));
  doc.raw_html(report::render_svg(pose));

  doc.heading(2, "Convergence history");
  report::LinePlot conv;
  conv.title = "Objective per evaluation";
  conv.x_label = "evaluation";
  conv.y_label = c.maximise ? "−" + measure_label(c.objective_measure) + ", maximised" : measure_label(c.objective_measure);
  report::Series feas = series("feasible", {}, {}), infeas = series("infeasible", {}, {});
  feas.style = infeas.style = report::Series::Style::markers;
  infeas.marker = report::Series::Marker::cross;
  for (const auto& h : run.history) {
    auto& s = h.feasible ? feas : infeas;
    s.x.push_back(h.evaluation);
    s.y.push_back(h.objective);
  }
  conv.series = {feas, infeas};
  doc.raw_html(report::render_svg(conv));
}

/// The search model and its measured error; the optimum's 3D check.
void add_model(report::HtmlDocument& doc, const DesignRun& run) {
  const DesignConfig& c = *run.config;
  doc.heading(2, "Model");
  doc.paragraph("Search model: the finite-strain fibre-section rod (fem/reduced) with each segment's RRA in the "
                "axisymmetric FEM (level " + std::to_string(c.model.rra_mesh_level) +
                ") for the local peaks and ballooning. Against the 3D FEM of the thesis 3CA (Hex20 with level 4's "
                "element layers, the fidelity ladder's reference), the rod reaches 90 deg at 297.2 kPa where the 3D "
                "model does at 277.9 kPa, and bends 21 % less at 150 kPa (docs/fidelity-ladder.md, The 3CA).");
  if (run.solid_check()) {
    const auto& sc = *run.solid_check();
    doc.paragraph("3D check of the optimum (check.solid_segment = " + std::to_string(sc.segment) + "): " + sc.element +
                  ", " + std::to_string(sc.dofs) + " dofs, " + format_number(sc.seconds) + " s. At " +
                  format_number(sc.reached_pressure_kPa) + " kPa the segment bends " + format_number(sc.bending_deg) +
                  " deg in 3D and " + format_number(sc.rod_bending_deg) + " deg by the rod: the search model's error on "
                  "this design is " + format_number(sc.bending_error_percent()) + " %. Path: " + sc.outcome +
                  ". 3D verdict: bending " + (sc.meets_bending() ? "met" : "NOT met") + ", working pressure " +
                  sc.working_pressure_verdict() + ".");
  }
}

/// The rounds on the accurate model (or of check and correct), one table row each.
void add_rounds(report::HtmlDocument& doc, const DesignRun& run) {
  const DesignConfig& c = *run.config;
  if (run.rounds.size() > 1 && c.verify_on_cells) {
    doc.heading(2, "Rounds on the accurate model");
    doc.paragraph("Each round searches with the search model corrected by every verified design so far (each "
                  "constraint's discrepancy at the newest, a linear term through the others; "
                  "engine/design/discrepancy_model.hpp) within a trust region about the best verified design, and "
                  "verifies its optimum on the cell rod. A correction round follows a verified design that misses a "
                  "requirement, an improvement round one that meets them all. The answer is round " +
                  std::to_string(run.answer_round) + "'s design, the best verified one. " +
                  (run.rounds_stop_reason.empty() ? std::string() : "No further round: " + run.rounds_stop_reason + "."));
    std::vector<std::vector<std::string>> round_rows;
    for (std::size_t k = 0; k < run.rounds.size(); ++k) {
      const SearchRound& r = run.rounds[k];
      const bool ok = r.verification && r.verification->ok();
      const objectives::ArmMeasures* m = ok ? &r.verification->measures : nullptr;
      round_rows.push_back({std::to_string(k), purpose_name(r.purpose), m ? format_number(m->mass_kg) : "-",
                            m ? format_number(m->payload_kg) : "-", m ? format_number(m->min_bending_deg) : "-",
                            m ? format_number(m->burst_utilisation) : "-",
                            m ? std::string(meets_every_requirement(c, *m, run.reference_strain) ? "yes" : "NO") : "not verified"});
    }
    doc.table({"round", "purpose", "mass (kg)", "payload (kg)", "least bending (deg)", "burst utilisation",
               "every requirement met"},
              round_rows, "rounds, each design verified on the cell rod");
  } else if (run.rounds.size() > 1) {
    doc.heading(2, "Check and correct");
    doc.paragraph("Each round searches with the search model corrected by the 3D checks so far (bending and burst "
                  "utilisation, multiplicative; engine/design/solid_correction.hpp), from the last optimum, and checks "
                  "the new optimum in 3D. The last round's design is the one reported above.");
    std::vector<std::vector<std::string>> round_rows;
    for (std::size_t k = 0; k < run.rounds.size(); ++k) {
      const SearchRound& r = run.rounds[k];
      const auto& sc = r.solid_check;
      round_rows.push_back({std::to_string(k), r.correction.describe(), format_number(r.optimum.mass_kg) + (r.feasible ? "" : " (infeasible)"),
                            sc ? format_number(sc->bending_deg) + " deg at " + format_number(sc->reached_pressure_kPa) + " kPa" : "-",
                            sc ? format_number(sc->bending_error_percent()) : "-",
                            sc ? std::string(sc->meets_bending() ? "met" : "NOT met") : "-",
                            sc ? sc->working_pressure_verdict() : "-"});
    }
    doc.table({"round", "correction", "mass (kg)", "3D bending", "rod error (%)", "3D bending verdict", "3D working pressure"},
              round_rows, "check and correct, round by round");
  }
}
}  // namespace

void write_design_outputs(const DesignRun& run) {
  const std::string& dir = run.config->output_directory;
  write_json_file(dir, "summary.json", design_summary(run));
  write_design_geometry(run);
  report::HtmlDocument doc("softarm design report");
  doc.heading(1, "softarm design report");
  add_verdict(doc, run);
  add_parameters(doc, run);
  add_verification(doc, run);
  add_constraints(doc, run);
  add_curves(doc, run);
  add_model(doc, run);
  add_rounds(doc, run);
  doc.write(std::filesystem::path(dir) / "report.html");
}

}  // namespace softarm::engine

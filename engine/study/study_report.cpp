#include "engine/study/study_report.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>

#include "engine/report/html_document.hpp"
#include "engine/report/output_files.hpp"
#include "engine/report/svg_plot.hpp"
#include "engine/study/shape_svg.hpp"
#include "studies/design_rule.hpp"

namespace softarm::engine {
using nlohmann::json;
using studies::StudyPoint;
using studies::StudySpec;
using studies::value_text;

namespace {

const json* record_of(const std::map<std::string, json>& records, const StudyPoint& p) {
  const auto it = records.find(p.key);
  return it == records.end() ? nullptr : &it->second;
}

double number_or_nan(const json* record, const std::string& key) {
  return record && record->contains(key) && (*record)[key].is_number() ? (*record)[key].get<double>() : std::nan("");
}

/// A value to compare along a parameter: only points solved up to the peak pressure.
double at_peak_or_nan(const json* record, const std::string& key) {
  return record && studies::solved_to_peak(*record) ? number_or_nan(record, key) : std::nan("");
}

std::string cell(const json* record, const std::string& key) {
  const double v = number_or_nan(record, key);
  return std::isfinite(v) ? report::format_number(v, 4) : "—";
}

/// Thesis form: extension normalised by its largest value over the study,
/// bending by 90° (thesis §6.1); other outputs as they are; against the first
/// parameter, one curve per combination of the others, points that stopped
/// before the peak pressure left out; the chosen points marked.
std::string parameter_plot(const StudySpec& spec, const std::vector<StudyPoint>& points,
                           const std::map<std::string, json>& records, const std::vector<studies::CurveChoice>& curves,
                           const std::string& output) {
  double scale = 1;
  std::string y_label = output;
  if (output == "bending_deg") scale = 90, y_label = "bending angle / 90°";
  if (output == "extension_mm") {
    scale = 0;
    for (const auto& p : points) scale = std::max(scale, std::abs(at_peak_or_nan(record_of(records, p), output)));
    if (!(scale > 0)) scale = 1;
    y_label = "extension / largest (" + report::format_number(scale, 4) + " mm)";
  }
  report::LinePlot plot;
  plot.title = output + " vs " + spec.axes.front().label + " (points solved to the peak pressure)";
  plot.x_label = spec.axes.front().label;
  plot.y_label = y_label;
  report::Series chosen{"chosen by the rule", {}, {}, report::Series::Style::markers, "#000", false,
                        report::Series::Marker::square};
  for (const auto& curve : curves) {
    report::Series s;
    s.label = curve.label.empty() ? "softarm" : curve.label;
    s.style = report::Series::Style::line_and_markers;
    for (int i : curve.points) {
      s.x.push_back(points[i].values[0].get<double>());
      s.y.push_back(at_peak_or_nan(record_of(records, points[i]), output) / scale);
    }
    if (curve.chosen >= 0) {
      chosen.x.push_back(points[curve.chosen].values[0].get<double>());
      chosen.y.push_back(at_peak_or_nan(record_of(records, points[curve.chosen]), output) / scale);
    }
    plot.series.push_back(std::move(s));
  }
  if (!chosen.x.empty()) plot.series.push_back(chosen);
  if (spec.thesis.choice.is_number()) {
    double lo = 1e300, hi = -1e300;
    for (const auto& s : plot.series)
      for (double y : s.y)
        if (std::isfinite(y)) lo = std::min(lo, y), hi = std::max(hi, y);
    if (hi >= lo) {
      const double x = spec.thesis.choice.get<double>();
      plot.series.push_back({"thesis choice", {x, x}, {lo, hi}, report::Series::Style::line, "#999", true});
    }
  }
  return report::render_svg(plot);
}

/// One curve per point against normalised pressure (thesis Figs 29, 40, 44).
std::string pressure_plot(const StudySpec& spec, const std::vector<StudyPoint>& points,
                          const std::map<std::string, json>& records) {
  const std::string& y = spec.plot_y;
  double p_max = 0, y_max = 0;
  for (const auto& p : points)
    if (const json* r = record_of(records, p); r && r->contains("curve"))
      for (const auto& v : (*r)["curve"]["pressure_kPa"]) p_max = std::max(p_max, v.get<double>());
  for (const auto& p : points)
    if (const json* r = record_of(records, p); r && r->contains("curve"))
      for (const auto& v : (*r)["curve"][y])
        if (v.is_number()) y_max = std::max(y_max, std::abs(v.get<double>()));
  const double scale = y == "bending_deg" ? 90 : (y_max > 0 ? y_max : 1);
  report::LinePlot plot;
  plot.title = (y == "bending_deg" ? "normalised bending angle" : "normalised extension") + std::string(" vs normalised pressure");
  plot.x_label = "normalised pressure p / " + report::format_number(p_max, 4) + " kPa";
  plot.y_label = y == "bending_deg" ? "bending angle / 90°" : "extension / largest extension";
  for (const auto& p : points) {
    const json* r = record_of(records, p);
    if (!r || !r->contains("curve")) continue;
    report::Series s;
    s.label = spec.axes.front().label + " = " + value_text(p.values[0]) +
              (studies::curve_label(spec, p).empty() ? "" : ", " + studies::curve_label(spec, p));
    s.style = report::Series::Style::line_and_markers;
    const auto& c = (*r)["curve"];
    for (std::size_t i = 0; i < c["pressure_kPa"].size() && i < c[y].size(); ++i) {
      s.x.push_back(c["pressure_kPa"][i].get<double>() / std::max(p_max, 1e-12));
      s.y.push_back(c[y][i].is_number() ? c[y][i].get<double>() / scale : std::nan(""));
    }
    plot.series.push_back(std::move(s));
  }
  return report::render_svg(plot);
}

std::vector<std::string> table_outputs(const StudySpec& spec) {
  std::vector<std::string> out{spec.rule.output};
  const auto add = [&](const std::string& o) {
    if (!o.empty() && std::find(out.begin(), out.end(), o) == out.end()) out.push_back(o);
  };
  add(spec.plot_y);
  add(spec.rule.then_minimise);
  for (const auto& l : spec.rule.limits) add(l.output);
  add("mass_g");
  add(spec.rule.output == "extension_mm" ? "limit_pressure_kPa" : "pressure_for_target_kPa");
  add("reached_pressure_kPa");
  return out;
}

void write_csv(const StudySpec& spec, const std::vector<StudyPoint>& points, const std::map<std::string, json>& records,
               const std::vector<std::string>& outputs, const std::filesystem::path& file) {
  std::ofstream csv(file);
  for (const auto& a : spec.axes) csv << a.parameter << ",";
  csv << "status";
  for (const auto& o : outputs) csv << "," << o;
  csv << ",seconds,diagnosis\n";
  for (const auto& p : points) {
    const json* r = record_of(records, p);
    for (const auto& v : p.values) csv << value_text(v) << ",";
    csv << (r ? r->value("status", std::string("?")) : "not run");
    for (const auto& o : outputs) {
      const double v = number_or_nan(r, o);
      csv << ",";
      if (std::isfinite(v)) csv << v;
    }
    csv << "," << number_or_nan(r, "seconds") << "," << csv_text(r ? r->value("diagnosis", std::string()) : "")
        << "\n";
  }
}

/// The points solved, failed and not run, and the solver time they took.
struct PointTally {
  int ok = 0, failed = 0, missing = 0;
  double seconds = 0;
};
PointTally tally_points(const std::vector<StudyPoint>& points, const std::map<std::string, json>& records) {
  PointTally t;
  for (const auto& p : points) {
    const json* r = record_of(records, p);
    if (!r) ++t.missing;
    else if (r->value("status", "") == "ok") ++t.ok;
    else ++t.failed;
    t.seconds += std::isfinite(number_or_nan(r, "seconds")) ? number_or_nan(r, "seconds") : 0.0;
  }
  return t;
}

/// "Model: …. Points: …": the first record's model and dofs (else the spec's model), and the tally.
std::string model_paragraph(const StudySpec& spec, const std::vector<StudyPoint>& points,
                            const std::map<std::string, json>& records, const PointTally& t) {
  std::string model;
  for (const auto& p : points)
    if (const json* r = record_of(records, p); r && r->contains("model")) {
      model = (*r)["model"].get<std::string>() + ", " + report::format_number(number_or_nan(r, "dofs"), 6) + " dofs";
      break;
    }
  return "Model: " + (model.empty() ? spec.model : model) + ". Points: " + std::to_string(points.size()) + " (" +
         std::to_string(t.ok) + " solved, " + std::to_string(t.failed) + " failed or invalid, " +
         std::to_string(t.missing) + " not run); solver time " + report::format_number(t.seconds, 3) + " s.";
}

/// The rule in words, each curve's reasoning, and the chosen values against the thesis'; returns the
/// choices as the summary lists them.
json rule_section(report::HtmlDocument& doc, const StudySpec& spec, const std::vector<StudyPoint>& points,
                  const std::vector<studies::CurveChoice>& curves) {
  doc.heading(2, "Design rule");
  std::string rule_text = "Rule: " + spec.rule.goal + "imise " + spec.rule.output;
  if (spec.rule.keep_percent < 100 && !spec.rule.then_minimise.empty())
    rule_text += ", then the smallest " + spec.rule.then_minimise + " within " +
                 report::format_number(100 - spec.rule.keep_percent, 3) + " % of the best";
  for (const auto& l : spec.rule.limits)
    rule_text += "; eligible only with " + l.output + (l.max ? " ≤ " + report::format_number(*l.max, 4) : "") +
                 (l.min ? " ≥ " + report::format_number(*l.min, 4) : "");
  doc.paragraph(rule_text + ".");
  for (const auto& c : curves) doc.paragraph((c.label.empty() ? "" : c.label + ": ") + c.words);
  json chosen = json::array();
  std::vector<std::vector<std::string>> choice_rows;
  for (const auto& c : curves) {
    const json value = c.chosen >= 0 ? points[c.chosen].values[0] : json(nullptr);
    chosen.push_back({{"curve", c.label}, {"value", value}, {"trend", c.trend}});
    choice_rows.push_back({c.label.empty() ? "—" : c.label, c.chosen >= 0 ? value_text(value) : "!none",
                           spec.thesis.choice.is_null() ? "—" : value_text(spec.thesis.choice)});
  }
  doc.table({"curve", "softarm's choice (" + spec.axes.front().label + ")", "thesis' choice"}, choice_rows,
            "the chosen values");
  return chosen;
}

/// The plots: the pressure curves where the study plots against pressure; for a numeric axis the rule's
/// output, the thesis' trend output and what the rule weighs or limits; else bars of the rule's output.
void result_plots(report::HtmlDocument& doc, const StudySpec& spec, const std::vector<StudyPoint>& points,
                  const std::map<std::string, json>& records, const std::vector<studies::CurveChoice>& curves) {
  const auto& axis = spec.axes.front();
  if (spec.plot_x == "pressure") doc.raw_html(pressure_plot(spec, points, records));
  if (axis.numeric()) {
    std::vector<std::string> plotted{spec.rule.output};
    const auto add = [&](const std::string& o) {
      if (!o.empty() && std::find(plotted.begin(), plotted.end(), o) == plotted.end()) plotted.push_back(o);
    };
    add(spec.thesis.trend_of);
    add(spec.rule.then_minimise);
    for (const auto& l : spec.rule.limits) add(l.output);
    for (const auto& o : plotted) doc.raw_html(parameter_plot(spec, points, records, curves, o));
    return;
  }
  report::BarChart bars;
  bars.title = spec.rule.output + " by " + axis.label;
  bars.value_label = spec.rule.output;
  for (const auto& p : points)
    bars.bars.push_back({value_text(p.values[0]) + (studies::curve_label(spec, p).empty() ? "" : ", " + studies::curve_label(spec, p)),
                         number_or_nan(record_of(records, p), spec.rule.output), ""});
  doc.raw_html(report::render_svg(bars));
}

/// Every point's values, status, outputs and time (the chosen in bold, the failed muted), then the
/// diagnoses recorded.
void point_tables(report::HtmlDocument& doc, const StudySpec& spec, const std::vector<StudyPoint>& points,
                  const std::map<std::string, json>& records, const std::vector<studies::CurveChoice>& curves,
                  const std::vector<std::string>& outputs) {
  std::vector<std::string> header;
  for (const auto& a : spec.axes) header.push_back(a.label);
  header.push_back("status");
  for (const auto& o : outputs) header.push_back(o);
  header.push_back("time (s)");
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> classes;
  for (const auto& p : points) {
    const json* r = record_of(records, p);
    std::vector<std::string> row;
    for (const auto& v : p.values) row.push_back(value_text(v));
    const std::string status = r ? r->value("status", std::string("?")) : "not run";
    row.push_back(status == "ok" ? "ok" : "!" + status);
    for (const auto& o : outputs) row.push_back(cell(r, o));
    row.push_back(cell(r, "seconds"));
    rows.push_back(row);
    const bool is_chosen = std::any_of(curves.begin(), curves.end(), [&](const auto& c) { return c.chosen == p.index; });
    classes.push_back(is_chosen ? "best" : status == "ok" ? "" : "muted");
  }
  doc.table(header, rows, "every point (bold: chosen by the rule)", classes);
  std::vector<std::vector<std::string>> diagnoses;
  for (const auto& p : points)
    if (const json* r = record_of(records, p); r && r->contains("diagnosis"))
      diagnoses.push_back({p.key, r->value("status", std::string()), (*r)["diagnosis"].get<std::string>()});
  if (!diagnoses.empty()) doc.table({"point", "status", "diagnosis"}, diagnoses, "diagnoses");
}

/// The chosen points' deformed shapes, where recorded.
void chosen_shapes(report::HtmlDocument& doc, const StudySpec& spec, const std::vector<StudyPoint>& points,
                   const std::map<std::string, json>& records, const std::vector<studies::CurveChoice>& curves) {
  doc.heading(2, "Deformed shapes of the chosen points");
  const auto& axis = spec.axes.front();
  std::string shapes;
  for (const auto& c : curves)
    if (c.chosen >= 0)
      if (const json* r = record_of(records, points[c.chosen]); r && r->contains("shape"))
        shapes += render_shape_svg((*r)["shape"], axis.label + " = " + value_text(points[c.chosen].values[0]) +
                                                      (c.label.empty() ? "" : ", " + c.label) + " at " +
                                                      report::format_number(number_or_nan(r, "reached_pressure_kPa"), 4) +
                                                      " kPa");
  doc.raw_html(shapes.empty() ? "<p>No shape recorded.</p>" : "<div>" + shapes + "</div>");
}

}  // namespace

json write_study_report(const StudySpec& spec, const std::vector<StudyPoint>& points,
                        const std::map<std::string, json>& records, const std::filesystem::path& directory) {
  const auto curves = studies::apply_rule(spec, points, records);
  const auto thesis = studies::compare_with_thesis(spec, points, curves);
  const auto outputs = table_outputs(spec);
  const PointTally tally = tally_points(points, records);

  report::HtmlDocument doc(spec.title);
  doc.heading(1, spec.title);
  if (!spec.description.empty()) doc.paragraph(spec.description);
  doc.paragraph(model_paragraph(spec, points, records, tally));
  const json chosen = rule_section(doc, spec, points, curves);
  doc.heading(2, "Comparison with the thesis");
  if (!spec.thesis.figure.empty() || !spec.thesis.finding.empty())
    doc.paragraph("Thesis (" + spec.thesis.figure + "): " + spec.thesis.finding);
  doc.paragraph(thesis.words);
  if (!spec.thesis.discussion.empty()) doc.paragraph("Why: " + spec.thesis.discussion);
  doc.heading(2, "Results");
  result_plots(doc, spec, points, records, curves);
  point_tables(doc, spec, points, records, curves, outputs);
  chosen_shapes(doc, spec, points, records, curves);

  std::filesystem::create_directories(directory);
  doc.write(directory / "report.html");
  write_csv(spec, points, records, outputs, directory / "results.csv");
  json rule_words = json::array();
  for (const auto& c : curves) rule_words.push_back(c.words);
  const json summary = {{"study", spec.name},
                        {"title", spec.title},
                        {"axis", spec.axes.front().label},
                        {"points", points.size()},
                        {"solved", tally.ok},
                        {"failed", tally.failed},
                        {"not_run", tally.missing},
                        {"chosen", chosen},
                        {"thesis_choice", spec.thesis.choice},
                        {"thesis_figure", spec.thesis.figure},
                        {"choice_agrees", thesis.choice_agrees},
                        {"trend_agrees", thesis.trend_agrees},
                        {"comparison", thesis.words},
                        {"rule_words", rule_words}};
  std::ofstream(directory / "summary.json") << summary.dump(2) << "\n";
  return summary;
}

void write_study_index(const std::filesystem::path& root) {
  std::vector<json> summaries;
  if (std::filesystem::is_directory(root))
    for (const auto& entry : std::filesystem::directory_iterator(root))
      if (std::filesystem::exists(entry.path() / "summary.json")) {
        std::ifstream in(entry.path() / "summary.json");
        const json s = json::parse(in, nullptr, false);
        if (!s.is_discarded()) summaries.push_back(s);
      }
  std::sort(summaries.begin(), summaries.end(), [](const json& a, const json& b) { return a["study"] < b["study"]; });
  report::HtmlDocument doc("softarm parameter studies");
  doc.heading(1, "Parameter studies");
  doc.paragraph("Each study's design rule, the value it picks and the thesis' choice (spec §5).");
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> classes;
  std::string links;
  for (const json& s : summaries) {
    std::string picked;
    for (const auto& c : s["chosen"])
      picked += (picked.empty() ? "" : "; ") + (c["value"].is_null() ? "none" : value_text(c["value"])) +
                (c["curve"].get<std::string>().empty() ? "" : " (" + c["curve"].get<std::string>() + ")");
    rows.push_back({s["title"].get<std::string>(), s["axis"].get<std::string>(), picked,
                    s["thesis_choice"].is_null() ? "—" : value_text(s["thesis_choice"]),
                    s["choice_agrees"].get<bool>() ? "yes" : "!no", s["trend_agrees"].get<bool>() ? "yes" : "!no",
                    std::to_string(s["solved"].get<int>()) + "/" + std::to_string(s["points"].get<int>())});
    classes.push_back("");
    const std::string name = s["study"].get<std::string>();
    links += "<li><a href=\"" + report::escape_html(name) + "/report.html\">" +
             report::escape_html(s["title"].get<std::string>()) + "</a></li>";
  }
  doc.table({"study", "parameter", "softarm's choice", "thesis' choice", "same choice", "same trend", "solved"}, rows,
            "studies under " + root.string(), classes);
  doc.raw_html("<ul>" + links + "</ul>");
  doc.write(root / "index.html");
}

}  // namespace softarm::engine

#include "engine/workspace/workspace_report.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "engine/report/html_document.hpp"
#include "engine/report/svg_plot.hpp"

namespace softarm::engine {
namespace {
using report::format_number;

struct Projection {
  const char* title;
  int x, y;  // the coordinates drawn
  const char* x_label;
  const char* y_label;
};
constexpr std::array<Projection, 3> kProjections = {{
    {"Seen from above (x-y)", 0, 1, "x (mm)", "y (mm)"},
    {"Seen from the front (x-z)", 0, 2, "x (mm)", "z (mm, shoulder up)"},
    {"Seen from the side (y-z)", 1, 2, "y (mm)", "z (mm, shoulder up)"},
}};

/// A quantity the points can be coloured by: its name in the legend, its unit, its value.
struct Colouring {
  const char* key;
  const char* name;
  const char* unit;
  double (*value)(const studies::WorkspacePoint&);
};
constexpr std::array<Colouring, 4> kColourings = {{
    {"pressure_sum", "pressure sum ", " kPa", [](const studies::WorkspacePoint& p) { return p.pressure_sum_kPa; }},
    {"tip_tilt", "tip tilt ", "°", [](const studies::WorkspacePoint& p) { return p.tip_tilt_deg; }},
    {"peak_stretch", "tube's peak stretch ", "", [](const studies::WorkspacePoint& p) { return p.peak.stretch; }},
    {"payload_margin", "payload margin ", " kg",
     [](const studies::WorkspacePoint& p) { return p.payload_margin_kg.value_or(std::nan("")); }},
}};

const Colouring& colouring(const std::string& key) {
  for (const Colouring& c : kColourings)
    if (key == c.key) return c;
  return kColourings.front();
}

double quantity(const studies::WorkspacePoint& p, const std::string& colour_by) { return colouring(colour_by).value(p); }

/// The band edges: the quantity's quartiles over the reached points.
std::array<double, 5> band_edges(const studies::WorkspaceResult& w, const std::string& colour_by) {
  std::vector<double> v;
  for (const auto& p : w.points)
    if (p.ok && std::isfinite(quantity(p, colour_by))) v.push_back(quantity(p, colour_by));
  std::sort(v.begin(), v.end());
  std::array<double, 5> edges{};
  for (int k = 0; k <= 4; ++k) edges[k] = v.empty() ? 0.0 : v[std::min(v.size() - 1, k * v.size() / 4)];
  if (!v.empty()) edges[4] = v.back();
  return edges;
}

std::string projection_svg(const studies::WorkspaceResult& w, const Projection& view, const std::string& colour_by,
                           const std::array<double, 5>& edges) {
  static const std::array<const char*, 4> colours = {"#2c7bb6", "#abd9e9", "#fdae61", "#d7191c"};
  const std::string unit = colouring(colour_by).unit, name = colouring(colour_by).name;
  report::LinePlot plot;
  plot.title = view.title;
  plot.x_label = view.x_label;
  plot.y_label = view.y_label;
  plot.width_px = 560;
  plot.height_px = 480;
  // Poses without the quantity (a payload margin computed at some poses only) in grey, beneath.
  report::Series without;
  without.label = "not computed";
  without.style = report::Series::Style::markers;
  without.colour = "#d9d9d9";
  for (const auto& p : w.points)
    if (p.ok && !std::isfinite(quantity(p, colour_by))) without.x.push_back(p.tip_mm[view.x]), without.y.push_back(p.tip_mm[view.y]);
  if (!without.x.empty()) plot.series.push_back(std::move(without));
  for (int band = 0; band < 4; ++band) {
    report::Series s;
    s.label = name + format_number(edges[band], 3) + "–" + format_number(edges[band + 1], 3) + unit;
    s.style = report::Series::Style::markers;
    s.colour = colours[band];
    for (const auto& p : w.points) {
      const double q = quantity(p, colour_by);
      if (!p.ok || !std::isfinite(q)) continue;
      const int in = q >= edges[3] ? 3 : q >= edges[2] ? 2 : q >= edges[1] ? 1 : 0;
      if (in != band) continue;
      s.x.push_back(p.tip_mm[view.x]);
      s.y.push_back(p.tip_mm[view.y]);
    }
    plot.series.push_back(std::move(s));
  }
  return report::render_svg(plot);
}
}  // namespace

void write_workspace_report(const std::string& path, const studies::WorkspaceResult& w, const std::string& colour_by,
                            const std::string& scene) {
  report::HtmlDocument doc("softarm workspace");
  doc.heading(1, "Workspace of " + scene);
  doc.paragraph("Each point is the tip's centre at one of " + std::to_string(w.points.size()) +
                " pressure vectors (the corners of the pressure space, then Roberts' R9 sequence), posed on the arm's "
                "cells; " + std::to_string(w.reached) + " reached an equilibrium within the cells' reach.");
  if (colour_by == "payload_margin") {
    const auto computed = std::count_if(w.points.begin(), w.points.end(), [](const auto& p) { return p.payload_margin_kg.has_value(); });
    doc.paragraph("The payload margin, the extra tip mass with which the arm still holds its tip at that position, "
                  "was computed at " + std::to_string(computed) +
                  " poses (a continuation in the mass each); the others are drawn grey.");
  }
  const auto edges = band_edges(w, colour_by);
  for (const Projection& view : kProjections) doc.raw_html(projection_svg(w, view, colour_by, edges));
  std::vector<std::vector<std::string>> rows = {
      {"poses reached", std::to_string(w.reached) + " of " + std::to_string(w.points.size())},
      {"extent x (mm)", format_number(w.lower_mm.x()) + " to " + format_number(w.upper_mm.x())},
      {"extent y (mm)", format_number(w.lower_mm.y()) + " to " + format_number(w.upper_mm.y())},
      {"extent z (mm)", format_number(w.lower_mm.z()) + " to " + format_number(w.upper_mm.z())},
      {"occupied volume (L)", format_number(w.occupied_volume_mm3 * 1e-6)},
      {"poses per second", format_number(w.poses_per_second)},
  };
  if (w.reached > 0) {
    const auto top = std::max_element(w.points.begin(), w.points.end(), [](const auto& a, const auto& b) {
      return (a.ok ? a.peak.stretch : 0.0) < (b.ok ? b.peak.stretch : 0.0);
    });
    if (top->peak.segment > 0)
      rows.push_back({"largest peak stretch of the tube (segment)",
                      format_number(top->peak.stretch) + " (" + std::to_string(top->peak.segment) + ")"});
  }
  doc.table({"quantity", "value"}, rows, "The workspace's size and cost (summary.json holds the same)");
  doc.write(path);
}

}  // namespace softarm::engine

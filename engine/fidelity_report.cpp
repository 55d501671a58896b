#include "engine/fidelity_report.hpp"

#include <cmath>
#include <iomanip>
#include <iostream>

#include "engine/report/html_document.hpp"
#include "engine/report/svg_plot.hpp"
#include "fem/scenes/fidelity.hpp"

namespace softarm::engine {
namespace {
const char* const kScenes[] = {"rra", "tca", "spl"};
}

void print_fidelity_ladders() {
  for (const std::string scene : kScenes) {
    const fem::FidelityLadder& ladder = fem::fidelity_ladder(scene);
    std::cout << "scene " << scene << " (errors against " << ladder.reference << "):\n";
    for (const auto& m : ladder.levels)
      std::cout << "  " << std::left << std::setw(48) << m.name << std::right << std::setw(9) << m.dofs << " dofs "
                << std::setw(7) << m.seconds << " s  error " << std::setw(5) << m.error_percent << " %  ("
                << m.error_measure << ")\n";
  }
  std::cout << "fidelity: fast = the cheapest model, whatever its error; balanced = within "
            << fem::fidelity_target_percent("balanced") << " %, accurate = within "
            << fem::fidelity_target_percent("accurate") << " %: the cheapest model that meets it\n";
}

void write_fidelity_report(const std::string& file) {
  report::HtmlDocument doc("softarm fidelity ladder");
  doc.heading(1, "Fidelity ladder: measured error against cost");
  doc.paragraph("Each point is a model of the scene; lower left is better. The reference of each scene (error 0) "
                "is not drawn on the logarithmic error axis; it is listed in the table.");
  for (const std::string scene : kScenes) {
    const fem::FidelityLadder& ladder = fem::fidelity_ladder(scene);
    doc.heading(2, "scene " + scene);
    report::LinePlot plot;
    plot.title = scene + ": error vs wall time (Pareto)";
    plot.x_label = "log10 wall time on one core (s)";
    plot.y_label = "measured error (%)";
    plot.log_y = true;
    std::vector<std::vector<std::string>> rows;
    for (const auto& m : ladder.levels) {
      if (m.error_percent > 0 && m.seconds > 0) {
        report::Series point;
        point.label = m.name;
        point.x = {std::log10(m.seconds)};
        point.y = {m.error_percent};
        point.style = report::Series::Style::markers;
        plot.series.push_back(point);
      }
      rows.push_back({m.name, std::to_string(m.dofs), report::format_number(m.seconds, 3),
                      m.error_percent > 0 ? report::format_number(m.error_percent, 3) : "reference", m.error_measure});
    }
    doc.raw_html(report::render_svg(plot));
    doc.table({"model", "dofs", "time (s)", "error (%)", "measured on"}, rows, "against " + ladder.reference);
  }
  doc.write(file);
  std::cout << "wrote " << file << "\n";
}

}  // namespace softarm::engine

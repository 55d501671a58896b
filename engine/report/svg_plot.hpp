#pragma once
// SVG plots for the HTML reports, standard library only: line/marker plots
// (pressure curves, convergence histories) and horizontal bar charts
// (constraint margins). Each render_svg() returns one self-contained <svg>
// element (no ids, no scripts), usable inline in HTML or as an .svg file.
//
// Robustness: non-finite points are skipped (a line breaks there) and never
// printed; with log_y, points with y <= 0 are skipped too; a plot without any
// drawable point renders a "no data" SVG; constant data gets a padded range;
// coordinates are printed with one decimal (compact files); all text is escaped.
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace softarm::report {

struct Series {
    enum class Style { line, markers, line_and_markers };
    enum class Marker { circle, square, triangle, cross };

    std::string label;
    std::vector<double> x, y;  ///< the first min(x.size(), y.size()) points are used
    Style style = Style::line;
    std::string colour;  ///< any SVG colour ("#1f77b4", "red"); empty = next palette colour
    bool dashed = false;
    Marker marker = Marker::circle;  ///< shape for Style::markers / line_and_markers
};

struct LinePlot {
    std::string title, x_label, y_label;
    std::vector<Series> series;
    std::optional<double> x_min, x_max, y_min, y_max;  ///< fixed ranges; unset = from the data
    std::vector<std::pair<double, std::string>> horizontal_lines;  ///< (y, label), e.g. target 90°
    bool log_y = false;
    int width_px = 640, height_px = 400;
};

std::string render_svg(const LinePlot& plot);

struct Bar {
    std::string label;
    double value;
    std::string annotation;  ///< shown to the right of the chart; may be empty
};

/// Horizontal bars around a zero line: negative values red (class "bar negative"),
/// zero and positive green (class "bar positive"); a non-finite value draws no bar
/// and shows "—". The height follows from the bar count.
struct BarChart {
    std::string title, value_label;
    std::vector<Bar> bars;
    int width_px = 640;
};

std::string render_svg(const BarChart& chart);

/// Axis ticks: `values` are "nice" numbers (1, 2 or 5 × 10^k apart on a linear
/// axis), increasing, with values.front() == lo <= data min and
/// values.back() == hi >= data max.
struct Ticks {
    double lo = 0, hi = 1;
    double step = 0;  ///< linear axes: the spacing; log axes: 0
    std::vector<double> values;
};

/// Linear ticks covering [data_min, data_max] (either order) with about
/// `target_count` (>= 2) intervals or fewer. Equal bounds get a padded range
/// (±10 % of the value, or ±1 around zero). Non-finite input throws
/// std::invalid_argument.
Ticks nice_ticks(double data_min, double data_max, int target_count = 6);

/// Logarithmic ticks covering [data_min, data_max] (both > 0, else
/// std::invalid_argument): 1, 2, 5 × 10^k within a decade or two, powers of ten
/// for wider ranges (every n-th decade for very wide ones).
Ticks nice_log_ticks(double data_min, double data_max);

/// Label of tick `value` on a linear axis with spacing `step`: just enough
/// digits to tell neighbours apart ("0.5", "12", "2.5e-6"), "0" for zero.
std::string tick_label(double value, double step);

}  // namespace softarm::report

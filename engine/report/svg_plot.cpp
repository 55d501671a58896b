#include "engine/report/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "engine/report/html_document.hpp"

namespace softarm::report {

namespace {

const char* const palette[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd",
                               "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
constexpr double char_width_px = 6.6;  // rough width of one character at font-size 12

/// A pixel coordinate with one decimal, trailing ".0" dropped, never "-0".
std::string px(double v) {
    if (!std::isfinite(v)) v = 0;  // callers only pass finite values; never print nan/inf
    char buffer[48];
    std::snprintf(buffer, sizeof buffer, "%.1f", v);
    std::string s = buffer;
    if (s.size() > 2 && s.compare(s.size() - 2, 2, ".0") == 0) s.resize(s.size() - 2);
    if (s == "-0") s = "0";
    return s;
}

double pow10i(int e) { return std::pow(10.0, e); }

/// m × 10^e, rounded once (so 3 × 10^-1 is the double nearest 0.3).
double scaled(double m, int e) { return e >= 0 ? m * pow10i(e) : m / pow10i(-e); }

std::size_t code_points(const std::string& s) {
    return static_cast<std::size_t>(
        std::count_if(s.begin(), s.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
}

double text_width(const std::string& s, double font_px = 12) {
    return static_cast<double>(code_points(s)) * char_width_px * font_px / 12.0;
}

/// `s` cut to at most `max_points` code points, with "…" if cut.
std::string truncate(const std::string& s, std::size_t max_points) {
    if (code_points(s) <= max_points) return s;
    if (max_points == 0) return "";
    std::size_t points = 0, i = 0;
    for (; i < s.size(); ++i) {
        if ((static_cast<unsigned char>(s[i]) & 0xC0) != 0x80) {
            if (points == max_points - 1) break;
            ++points;
        }
    }
    return s.substr(0, i) + "\xE2\x80\xA6";
}

std::string svg_open(int width, int height, const std::string& title) {
    std::string out = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(width) + "\" height=\"" +
                      std::to_string(height) + "\" viewBox=\"0 0 " + std::to_string(width) + " " +
                      std::to_string(height) +
                      "\" font-family=\"Helvetica,Arial,sans-serif\" font-size=\"12\" role=\"img\">\n";
    out += "<title>" + escape_html(title) + "</title>\n";
    out += "<rect width=\"" + std::to_string(width) + "\" height=\"" + std::to_string(height) + "\" fill=\"#fff\"/>\n";
    return out;
}

std::string text(double x, double y, const std::string& content, const std::string& attributes = "") {
    return "<text x=\"" + px(x) + "\" y=\"" + px(y) + "\"" + (attributes.empty() ? "" : " " + attributes) + ">" +
           escape_html(content) + "</text>\n";
}

std::string no_data_svg(const std::string& title, int width, int height, const std::string& reason) {
    std::string out = svg_open(width, height, title.empty() ? "no data" : title + " (no data)");
    out += "<rect x=\"4\" y=\"4\" width=\"" + std::to_string(width - 8) + "\" height=\"" + std::to_string(height - 8) +
           "\" fill=\"#fafafa\" stroke=\"#ccc\"/>\n";
    if (!title.empty())
        out += text(width / 2.0, height / 2.0 - 12, title, "text-anchor=\"middle\" font-size=\"14\" font-weight=\"bold\"");
    out += text(width / 2.0, height / 2.0 + (title.empty() ? 4 : 12), "no data: " + reason,
                "text-anchor=\"middle\" fill=\"#888\"");
    out += "</svg>\n";
    return out;
}

struct Axis {
    double lo = 0, hi = 1;  // in plotted units (log10 for a log axis)
    bool log = false;
    std::vector<double> ticks;  // data units
    std::vector<std::string> labels;
    double to_axis(double v) const { return log ? std::log10(v) : v; }
};

/// An axis over the data range [data_lo, data_hi], with fixed ends where given
/// (fixed ends that contradict each other, or are not finite, or not positive
/// on a log axis, are ignored).
Axis make_axis(double data_lo, double data_hi, const std::optional<double>& fixed_lo,
               const std::optional<double>& fixed_hi, bool log) {
    // Plain values rather than optionals (GCC 12 warns spuriously about optionals here).
    auto usable = [&](const std::optional<double>& v) { return v.has_value() && std::isfinite(*v) && (!log || *v > 0); };
    bool has_lo = usable(fixed_lo), has_hi = usable(fixed_hi);
    const double flo = has_lo ? *fixed_lo : 0.0, fhi = has_hi ? *fixed_hi : 0.0;
    if (has_lo && has_hi && !(flo < fhi)) has_lo = has_hi = false;
    double a = has_lo ? flo : data_lo;
    double b = has_hi ? fhi : data_hi;
    if (a > b) {
        if (has_lo)
            b = a;
        else
            a = b;
    }
    const Ticks t = log ? nice_log_ticks(a, b) : nice_ticks(a, b);
    Axis axis;
    axis.log = log;
    axis.lo = axis.to_axis(has_lo ? flo : t.lo);
    axis.hi = axis.to_axis(has_hi ? fhi : t.hi);
    const double tolerance = 1e-9 * (axis.hi - axis.lo);
    for (const double v : t.values) {
        const double u = axis.to_axis(v);
        if (u < axis.lo - tolerance || u > axis.hi + tolerance) continue;
        axis.ticks.push_back(v);
        axis.labels.push_back(log ? format_number(v, v >= 1e-3 && v < 1e5 ? 6 : 3) : tick_label(v, t.step));
    }
    return axis;
}

struct Rect {
    double x0, y0, x1, y1;
};

/// Liang–Barsky: clips the segment (ax, ay)–(bx, by) to `r`; false if nothing is left.
bool clip_segment(double& ax, double& ay, double& bx, double& by, const Rect& r) {
    double t0 = 0, t1 = 1;
    const double dx = bx - ax, dy = by - ay;
    const double p[4] = {-dx, dx, -dy, dy};
    const double q[4] = {ax - r.x0, r.x1 - ax, ay - r.y0, r.y1 - ay};
    for (int i = 0; i < 4; ++i) {
        if (p[i] == 0) {
            if (q[i] < 0) return false;
            continue;
        }
        const double t = q[i] / p[i];
        if (p[i] < 0)
            t0 = std::max(t0, t);
        else
            t1 = std::min(t1, t);
        if (t0 > t1) return false;
    }
    const double nax = ax + t0 * dx, nay = ay + t0 * dy;
    bx = ax + t1 * dx;
    by = ay + t1 * dy;
    ax = nax;
    ay = nay;
    return true;
}

std::string marker_path(Series::Marker marker, double x, double y, double r) {
    switch (marker) {
        case Series::Marker::square:
            return "M" + px(x - r) + " " + px(y - r) + "h" + px(2 * r) + "v" + px(2 * r) + "h" + px(-2 * r) + "z";
        case Series::Marker::triangle:
            return "M" + px(x) + " " + px(y - 1.2 * r) + "l" + px(1.1 * r) + " " + px(2 * r) + "h" + px(-2.2 * r) + "z";
        case Series::Marker::cross:
            return "M" + px(x - r) + " " + px(y - r) + "l" + px(2 * r) + " " + px(2 * r) + "M" + px(x - r) + " " +
                   px(y + r) + "l" + px(2 * r) + " " + px(-2 * r);
        case Series::Marker::circle:
        default:
            return "M" + px(x - r) + " " + px(y) + "a" + px(r) + " " + px(r) + " 0 1 0 " + px(2 * r) + " 0a" + px(r) +
                   " " + px(r) + " 0 1 0 " + px(-2 * r) + " 0";
    }
}

std::string marker_element(Series::Marker marker, const std::string& d, const std::string& colour) {
    if (marker == Series::Marker::cross)
        return "<path d=\"" + d + "\" fill=\"none\" stroke=\"" + colour + "\" stroke-width=\"1.5\"/>\n";
    return "<path d=\"" + d + "\" fill=\"" + colour + "\"/>\n";
}

}  // namespace

Ticks nice_ticks(double data_min, double data_max, int target_count) {
    if (!std::isfinite(data_min) || !std::isfinite(data_max))
        throw std::invalid_argument("nice_ticks: the data range must be finite");
    double lo = std::min(data_min, data_max), hi = std::max(data_min, data_max);
    const int target = std::max(2, target_count);
    const double magnitude = std::max(std::abs(lo), std::abs(hi));
    if (!(hi - lo > 1e-12 * magnitude)) {  // constant (or numerically constant) data
        if (magnitude == 0) {
            lo = -1;
            hi = 1;
        } else {
            lo -= 0.1 * magnitude;
            hi += 0.1 * magnitude;
        }
    }
    if (!std::isfinite(hi - lo)) {  // beyond the double range: halve and retry
        Ticks half = nice_ticks(lo / 2, hi / 2, target_count);
        for (double& v : half.values) v *= 2;
        half.lo *= 2, half.hi *= 2, half.step *= 2;
        return half;
    }
    const double raw = (hi - lo) / target;
    int e = static_cast<int>(std::floor(std::log10(raw)));
    const double f = raw / pow10i(e);
    double m = f <= 1 + 1e-9 ? 1 : f <= 2 + 1e-9 ? 2 : f <= 5 + 1e-9 ? 5 : 10;
    if (m == 10) m = 1, ++e;
    const double step = scaled(m, e);
    auto tick = [&](double k) {
        const double v = scaled(k * m, e);
        return v == 0 ? 0.0 : v;  // no -0
    };
    double kmin = std::floor(lo / step), kmax = std::ceil(hi / step);
    while (tick(kmin) > lo) kmin -= 1;
    while (tick(kmin + 1) <= lo) kmin += 1;
    while (tick(kmax) < hi) kmax += 1;
    while (tick(kmax - 1) >= hi) kmax -= 1;
    Ticks t;
    t.step = step;
    for (double k = kmin; k <= kmax; k += 1) t.values.push_back(tick(k));
    t.lo = t.values.front();
    t.hi = t.values.back();
    return t;
}

Ticks nice_log_ticks(double data_min, double data_max) {
    if (!(std::isfinite(data_min) && std::isfinite(data_max) && data_min > 0 && data_max > 0))
        throw std::invalid_argument("nice_log_ticks: the data range must be finite and positive");
    double lo = std::min(data_min, data_max), hi = std::max(data_min, data_max);
    if (hi / lo < 1 + 1e-9) lo /= 2, hi *= 2;
    int elo = static_cast<int>(std::floor(std::log10(lo)));
    int ehi = static_cast<int>(std::ceil(std::log10(hi)));
    while (scaled(1, elo) > lo) --elo;
    while (scaled(1, ehi) < hi) ++ehi;
    if (ehi == elo) ++ehi;
    Ticks t;
    if (ehi - elo <= 2) {
        std::vector<double> candidates;
        for (int k = elo; k < ehi; ++k)
            for (const double m : {1.0, 2.0, 5.0}) candidates.push_back(scaled(m, k));
        candidates.push_back(scaled(1, ehi));
        std::size_t first = 0, last = candidates.size() - 1;
        while (first + 1 < candidates.size() && candidates[first + 1] <= lo) ++first;
        while (last > first + 1 && candidates[last - 1] >= hi) --last;
        t.values.assign(candidates.begin() + static_cast<std::ptrdiff_t>(first),
                        candidates.begin() + static_cast<std::ptrdiff_t>(last) + 1);
    } else {
        const int stride = std::max(1, static_cast<int>(std::ceil((ehi - elo) / 8.0)));
        const int first = static_cast<int>(std::floor(static_cast<double>(elo) / stride)) * stride;
        const int last = static_cast<int>(std::ceil(static_cast<double>(ehi) / stride)) * stride;
        for (int k = first; k <= last; k += stride) t.values.push_back(scaled(1, k));
    }
    t.lo = t.values.front();
    t.hi = t.values.back();
    t.step = 0;
    return t;
}

std::string tick_label(double value, double step) {
    if (!std::isfinite(value)) return "";
    step = std::abs(step);
    if (value == 0 || (step > 0 && std::abs(value) < 1e-9 * step)) return "0";
    if (!(step > 0) || !std::isfinite(step)) return format_number(value, 4);
    const double step_exponent = std::floor(std::log10(step) + 1e-9);
    if (step >= 1e-4 && std::abs(value) < 1e6) {
        const int decimals = std::max(0, static_cast<int>(-step_exponent));
        char buffer[64];
        std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
        std::string s = buffer;
        if (s.find_first_not_of("-0.") == std::string::npos) return "0";
        return s;
    }
    const int digits =
        static_cast<int>(std::floor(std::log10(std::abs(value)) + 1e-9) - step_exponent) + 1;  // significant digits
    return format_number(value, std::clamp(digits, 1, 15));
}

/// Rows a line plot's legend needs (its labelled series).
std::size_t legend_rows(const LinePlot& plot) {
    return static_cast<std::size_t>(std::count_if(plot.series.begin(), plot.series.end(),
                                                  [](const Series& s) { return !s.label.empty(); }));
}

constexpr double legend_row_px = 16;

/// The legend of `plot` in a box at (x, y), one row per labelled series (a series with nothing to
/// draw says so), no wider than max_width.
std::string legend_svg(const LinePlot& plot, const std::vector<std::string>& colours, double x, double y,
                       double max_width) {
    std::vector<std::size_t> entries;
    for (std::size_t i = 0; i < plot.series.size(); ++i)
        if (!plot.series[i].label.empty()) entries.push_back(i);
    if (entries.empty()) return "";
    const auto legend_text = [&](const Series& s) {
        const std::size_t n = std::min(s.x.size(), s.y.size());
        for (std::size_t i = 0; i < n; ++i)
            if (std::isfinite(s.x[i]) && std::isfinite(s.y[i]) && (!plot.log_y || s.y[i] > 0)) return s.label;
        return s.label + " (no data)";
    };
    const std::size_t max_chars = static_cast<std::size_t>(std::max(4.0, (max_width - 40) / char_width_px));
    double widest = 0;
    for (const std::size_t i : entries) widest = std::max(widest, text_width(truncate(legend_text(plot.series[i]), max_chars)));
    const double box_w = widest + 40, box_h = entries.size() * legend_row_px + 8;
    std::string out = "<g>\n<rect x=\"" + px(x) + "\" y=\"" + px(y) + "\" width=\"" + px(box_w) + "\" height=\"" +
                      px(box_h) + "\" fill=\"#fff\" stroke=\"#ccc\"/>\n";
    for (std::size_t k = 0; k < entries.size(); ++k) {
        const Series& s = plot.series[entries[k]];
        const std::string& colour = colours[entries[k]];
        const double cy = y + 4 + legend_row_px * (k + 0.5);
        if (s.style != Series::Style::markers)
            out += "<path d=\"M" + px(x + 6) + " " + px(cy) + "h22\" stroke=\"" + colour + "\" stroke-width=\"1.8\"" +
                   (s.dashed ? " stroke-dasharray=\"6 4\"" : "") + "/>\n";
        if (s.style != Series::Style::line) out += marker_element(s.marker, marker_path(s.marker, x + 17, cy, 3), colour);
        out += text(x + 34, cy + 4, truncate(legend_text(s), max_chars));
    }
    return out + "</g>\n";
}

namespace {
/// Whether a point of `plot` can be drawn: finite, and positive on a log scale.
bool drawable(const LinePlot& plot, double x, double y) {
    return std::isfinite(x) && std::isfinite(y) && (!plot.log_y || y > 0);
}

/// The box of the drawable points and the reference lines; its count of points.
struct DataBounds {
    double xlo = INFINITY, xhi = -INFINITY, ylo = INFINITY, yhi = -INFINITY;
    std::size_t points = 0;
};
DataBounds data_bounds(const LinePlot& plot) {
    DataBounds b;
    for (const Series& s : plot.series) {
        const std::size_t n = std::min(s.x.size(), s.y.size());
        for (std::size_t i = 0; i < n; ++i) {
            if (!drawable(plot, s.x[i], s.y[i])) continue;
            ++b.points;
            b.xlo = std::min(b.xlo, s.x[i]), b.xhi = std::max(b.xhi, s.x[i]);
            b.ylo = std::min(b.ylo, s.y[i]), b.yhi = std::max(b.yhi, s.y[i]);
        }
    }
    for (const auto& [y, label] : plot.horizontal_lines)
        if (std::isfinite(y) && (!plot.log_y || y > 0)) b.ylo = std::min(b.ylo, y), b.yhi = std::max(b.yhi, y);
    return b;
}

/// The plotting area in the picture: its axes, margins and the maps from data to pixels.
struct PlotFrame {
    Axis xa, ya;
    double left = 0, top = 0, pw = 0, ph = 0;
    Rect area() const { return {left, top, left + pw, top + ph}; }
    double map_x(double x) const { return left + (x - xa.lo) / (xa.hi - xa.lo) * pw; }
    double map_y(double y) const { return top + ph - (ya.to_axis(y) - ya.lo) / (ya.hi - ya.lo) * ph; }
    bool inside(double X, double Y, double slack) const {
        return X >= left - slack && X <= left + pw + slack && Y >= top - slack && Y <= top + ph + slack;
    }
};
PlotFrame plot_frame(const LinePlot& plot, const DataBounds& b, int width, int height) {
    PlotFrame f{make_axis(b.xlo, b.xhi, plot.x_min, plot.x_max, false), make_axis(b.ylo, b.yhi, plot.y_min, plot.y_max, plot.log_y)};
    double widest_y_label = 0;
    for (const auto& l : f.ya.labels) widest_y_label = std::max(widest_y_label, text_width(l, 11));
    f.top = plot.title.empty() ? 14 : 34;
    const double bottom = 26 + (plot.x_label.empty() ? 0 : 18);
    f.left = widest_y_label + 12 + (plot.y_label.empty() ? 0 : 20);
    const double right = 18;
    f.pw = std::max(40.0, width - f.left - right), f.ph = std::max(40.0, height - f.top - bottom);
    return f;
}

/// Grid, frame, ticks, their labels and the axes' labels.
std::string axes_svg(const LinePlot& plot, const PlotFrame& f, int height) {
    std::string grid;
    for (const double t : f.xa.ticks) grid += "M" + px(f.map_x(t)) + " " + px(f.top) + "V" + px(f.top + f.ph + 4);
    for (const double t : f.ya.ticks) grid += "M" + px(f.left - 4) + " " + px(f.map_y(t)) + "H" + px(f.left + f.pw);
    std::string out = "<path d=\"" + grid + "\" stroke=\"#e3e3e3\" fill=\"none\"/>\n";
    out += "<rect x=\"" + px(f.left) + "\" y=\"" + px(f.top) + "\" width=\"" + px(f.pw) + "\" height=\"" + px(f.ph) +
           "\" fill=\"none\" stroke=\"#777\"/>\n";
    out += "<g font-size=\"11\" fill=\"#333\">\n";
    for (std::size_t i = 0; i < f.xa.ticks.size(); ++i)
        out += text(f.map_x(f.xa.ticks[i]), f.top + f.ph + 16, f.xa.labels[i], "text-anchor=\"middle\"");
    for (std::size_t i = 0; i < f.ya.ticks.size(); ++i)
        out += text(f.left - 6, f.map_y(f.ya.ticks[i]) + 4, f.ya.labels[i], "text-anchor=\"end\"");
    out += "</g>\n";
    if (!plot.x_label.empty()) out += text(f.left + f.pw / 2, height - 8, plot.x_label, "text-anchor=\"middle\"");
    if (!plot.y_label.empty())
        out += "<text transform=\"rotate(-90)\" x=\"" + px(-(f.top + f.ph / 2)) + "\" y=\"15\" text-anchor=\"middle\">" +
               escape_html(plot.y_label) + "</text>\n";
    return out;
}

/// The horizontal reference lines inside the area, dashed, each with its label at the right.
std::string reference_lines_svg(const LinePlot& plot, const PlotFrame& f) {
    std::string out;
    for (const auto& [y, label] : plot.horizontal_lines) {
        if (!std::isfinite(y) || (plot.log_y && y <= 0)) continue;
        const double v = f.map_y(y);
        if (v < f.top - 0.5 || v > f.top + f.ph + 0.5) continue;
        out += "<path d=\"M" + px(f.left) + " " + px(v) + "H" + px(f.left + f.pw) +
               "\" stroke=\"#555\" stroke-dasharray=\"3 3\" fill=\"none\"/>\n";
        if (!label.empty())
            out += text(f.left + f.pw - 4, v - 4, label, "text-anchor=\"end\" font-size=\"11\" fill=\"#555\"");
    }
    return out;
}

/// One series: its line clipped to the area and broken at points not drawable, a dot for an isolated
/// point of a line, its markers inside the area.
std::string series_svg(const LinePlot& plot, const Series& s, const std::string& colour, const PlotFrame& f) {
    const std::size_t n = std::min(s.x.size(), s.y.size());
    const bool lines = s.style != Series::Style::markers;
    const bool markers = s.style != Series::Style::line;
    const Rect area = f.area();
    std::string d, dots, marks;
    bool have_previous = false, pen_valid = false;
    double previous_x = 0, previous_y = 0, pen_x = 0, pen_y = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (!drawable(plot, s.x[i], s.y[i])) {  // skipped: the line breaks here
            have_previous = false;
            continue;
        }
        const double X = f.map_x(s.x[i]), Y = f.map_y(s.y[i]);
        if (!std::isfinite(X) || !std::isfinite(Y)) {
            have_previous = false;
            continue;
        }
        if (markers && f.inside(X, Y, 0.5)) marks += marker_path(s.marker, X, Y, 3);
        if (lines) {
            if (have_previous) {
                double ax = previous_x, ay = previous_y, bx = X, by = Y;
                if (clip_segment(ax, ay, bx, by, area)) {
                    if (!pen_valid || ax != pen_x || ay != pen_y) d += "M" + px(ax) + " " + px(ay);
                    d += "L" + px(bx) + " " + px(by);
                    pen_x = bx, pen_y = by, pen_valid = true;
                }
            } else {
                // An isolated point (no finite neighbour on either side) still shows, as a dot.
                const bool next_ok = i + 1 < n && drawable(plot, s.x[i + 1], s.y[i + 1]);
                if (!next_ok && !markers && f.inside(X, Y, 0)) dots += marker_path(Series::Marker::circle, X, Y, 1.8);
            }
        }
        previous_x = X, previous_y = Y, have_previous = true;
    }
    std::string out;
    if (!d.empty())
        out += "<path d=\"" + d + "\" fill=\"none\" stroke=\"" + colour +
               "\" stroke-width=\"1.8\" stroke-linejoin=\"round\"" + (s.dashed ? " stroke-dasharray=\"6 4\"" : "") +
               "/>\n";
    if (!dots.empty()) out += "<path d=\"" + dots + "\" fill=\"" + colour + "\"/>\n";
    if (!marks.empty()) out += marker_element(s.marker, marks, colour);
    return out;
}
}  // namespace

std::string render_svg(const LinePlot& plot) {
    const int width = std::max(plot.width_px, 200), height = std::max(plot.height_px, 150);
    if (plot.series.empty()) return no_data_svg(plot.title, width, height, "no series to plot");
    const DataBounds bounds = data_bounds(plot);
    if (bounds.points == 0)
        return no_data_svg(plot.title, width, height,
                           plot.log_y ? "no finite positive points (log scale)" : "no finite points");
    const PlotFrame frame = plot_frame(plot, bounds, width, height);
    const std::size_t rows = legend_rows(plot);
    const int legend_height = rows ? static_cast<int>(std::ceil(rows * legend_row_px + 14)) : 0;
    std::string out = svg_open(width, height + legend_height, plot.title.empty() ? "plot" : plot.title);
    if (!plot.title.empty())
        out += text(width / 2.0, 21, plot.title, "text-anchor=\"middle\" font-size=\"14\" font-weight=\"bold\"");
    out += axes_svg(plot, frame, height);
    out += reference_lines_svg(plot, frame);
    std::size_t palette_index = 0;
    std::vector<std::string> colours;
    for (const Series& s : plot.series) {
        colours.push_back(escape_html(s.colour.empty() ? palette[palette_index++ % std::size(palette)] : s.colour));
        out += series_svg(plot, s, colours.back(), frame);
    }
    // Legend: below the axes, where it hides no point and needs no truncation.
    out += legend_svg(plot, colours, frame.left, height + 2.0, width - frame.left - 8);
    out += "</svg>\n";
    return out;
}

std::string render_svg(const BarChart& chart) {
    const int width = std::max(chart.width_px, 240);
    if (chart.bars.empty()) return no_data_svg(chart.title, width, 120, "no bars");

    double vmin = 0, vmax = 0;
    bool any_finite = false;
    for (const Bar& b : chart.bars) {
        if (!std::isfinite(b.value)) continue;
        any_finite = true;
        vmin = std::min(vmin, b.value), vmax = std::max(vmax, b.value);
    }
    if (!any_finite) return no_data_svg(chart.title, width, 120, "no finite values");
    const Ticks t = nice_ticks(vmin, vmax, 6);

    const double row = 26, bar_h = 18;
    const double top = chart.title.empty() ? 10 : 34;
    const double bottom = 24 + (chart.value_label.empty() ? 0 : 18) + 6;
    const int height = static_cast<int>(std::ceil(top + row * chart.bars.size() + bottom));

    const std::size_t label_chars = static_cast<std::size_t>(width * 0.35 / char_width_px);
    const std::size_t annotation_chars = static_cast<std::size_t>(width * 0.25 / char_width_px);
    double label_w = 0, annotation_w = 0;
    for (const Bar& b : chart.bars) {
        label_w = std::max(label_w, text_width(truncate(b.label, label_chars)));
        annotation_w = std::max(annotation_w, text_width(truncate(b.annotation, annotation_chars)));
    }
    const double left = label_w + 14;
    const double right = (annotation_w > 0 ? annotation_w + 12 : 0) + 14;
    const double pw = std::max(60.0, width - left - right);
    auto map = [&](double v) { return left + (v - t.lo) / (t.hi - t.lo) * pw; };
    const double x0 = map(0);
    const double plot_bottom = top + row * chart.bars.size();

    std::string out = svg_open(width, height, chart.title.empty() ? "bar chart" : chart.title);
    if (!chart.title.empty())
        out += text(width / 2.0, 21, chart.title, "text-anchor=\"middle\" font-size=\"14\" font-weight=\"bold\"");
    std::string grid;
    for (const double v : t.values) {  // appended piecewise: GCC 12 warns spuriously (-Wrestrict) on "M" + …
        grid += 'M';
        grid += px(map(v));
        grid += ' ';
        grid += px(top);
        grid += 'V';
        grid += px(plot_bottom + 4);
    }
    out += "<path d=\"" + grid + "\" stroke=\"#e3e3e3\" fill=\"none\"/>\n";
    out += "<g font-size=\"11\" fill=\"#333\">\n";
    for (const double v : t.values) out += text(map(v), plot_bottom + 16, tick_label(v, t.step), "text-anchor=\"middle\"");
    out += "</g>\n";
    if (!chart.value_label.empty())
        out += text(left + pw / 2, height - 10, chart.value_label, "text-anchor=\"middle\"");

    for (std::size_t i = 0; i < chart.bars.size(); ++i) {
        const Bar& b = chart.bars[i];
        const double y = top + row * i + (row - bar_h) / 2, cy = top + row * (i + 0.5) + 4;
        out += text(left - 8, cy, truncate(b.label, label_chars), "text-anchor=\"end\"");
        if (std::isfinite(b.value)) {
            const bool negative = b.value < 0;
            const double xv = map(b.value);
            const double w = std::max(1.0, std::abs(xv - x0));
            const double x = std::min(x0, xv);
            out += "<rect class=\"bar " + std::string(negative ? "negative" : "positive") + "\" x=\"" + px(x) +
                   "\" y=\"" + px(y) + "\" width=\"" + px(w) + "\" height=\"" + px(bar_h) + "\" fill=\"" +
                   (negative ? "#d62728" : "#2ca02c") + "\"><title>" + escape_html(b.label) + ": " +
                   format_number(b.value, 4) + "</title></rect>\n";
        } else {
            out += text(x0 + 4, cy, "\xE2\x80\x94 (not finite)", "fill=\"#888\" font-size=\"11\"");
        }
        if (!b.annotation.empty())
            out += text(left + pw + 12, cy, truncate(b.annotation, annotation_chars), "fill=\"#333\"");
    }
    out += "<path d=\"M" + px(x0) + " " + px(top - 2) + "V" + px(plot_bottom + 2) + "\" stroke=\"#222\" stroke-width=\"1.2\"/>\n";
    out += "</svg>\n";
    return out;
}

}  // namespace softarm::report

// engine/report: HTML document builder and SVG plots for the design reports.
// Escaping, "nice" axis ticks, robustness against non-finite and empty data,
// bar colouring by sign, well-formedness of the emitted markup, and write()
// failing with the path in the message.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/report/html_document.hpp"
#include "engine/report/svg_plot.hpp"

using namespace softarm::report;

namespace {

const double nan_value = std::numeric_limits<double>::quiet_NaN();
const double inf_value = std::numeric_limits<double>::infinity();

std::size_t count(const std::string& text, const std::string& needle) {
    std::size_t n = 0;
    for (auto pos = text.find(needle); pos != std::string::npos; pos = text.find(needle, pos + needle.size())) ++n;
    return n;
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

/// Empty if every tag is closed in order (void elements, self-closing tags and
/// <!DOCTYPE> aside), else a description of the first problem.
std::string tag_balance_problem(const std::string& markup) {
    static const std::regex tag(R"(<(/?)([A-Za-z][A-Za-z0-9]*)[^<>]*?(/?)>)");
    std::vector<std::string> stack;
    for (auto it = std::sregex_iterator(markup.begin(), markup.end(), tag); it != std::sregex_iterator(); ++it) {
        const std::string name = lower((*it)[2]);
        if ((*it)[3] == "/" || name == "meta" || name == "br") continue;
        if ((*it)[1] == "/") {
            if (stack.empty()) return "</" + name + "> without an opening tag";
            if (stack.back() != name) return "</" + name + "> closes <" + stack.back() + ">";
            stack.pop_back();
        } else {
            stack.push_back(name);
        }
    }
    if (!stack.empty()) return "<" + stack.back() + "> never closed";
    // Stray angle brackets outside tags would mean unescaped text.
    const std::string without_tags = std::regex_replace(markup, tag, "");
    const std::string rest = std::regex_replace(without_tags, std::regex("<!DOCTYPE html>"), "");
    if (rest.find('<') != std::string::npos || rest.find('>') != std::string::npos) return "stray < or > in text";
    return "";
}

/// The absolute coordinates of the first <path> whose stroke is `colour` (M/L commands only).
std::vector<std::pair<double, double>> line_points(const std::string& svg, const std::string& colour,
                                                   std::size_t* moves = nullptr) {
    const std::regex path("<path d=\"([^\"]*)\" fill=\"none\" stroke=\"" + colour + "\"");
    std::smatch m;
    std::vector<std::pair<double, double>> points;
    if (!std::regex_search(svg, m, path)) return points;
    const std::string d = m[1];
    if (moves) *moves = count(d, "M");
    static const std::regex command(R"([ML](-?[0-9.]+) (-?[0-9.]+))");
    for (auto it = std::sregex_iterator(d.begin(), d.end(), command); it != std::sregex_iterator(); ++it)
        points.emplace_back(std::stod((*it)[1]), std::stod((*it)[2]));
    return points;
}

bool is_nice_step(double step) {
    const double e = std::floor(std::log10(step));
    const double m = step / std::pow(10.0, e);
    return std::abs(m - 1) < 1e-9 || std::abs(m - 2) < 1e-9 || std::abs(m - 5) < 1e-9 || std::abs(m - 10) < 1e-9;
}

LinePlot simple_plot() {
    LinePlot plot;
    plot.title = "Bending angle";
    plot.x_label = "pressure (kPa)";
    plot.y_label = "angle (deg)";
    Series s;
    s.label = "optimum";
    s.x = {0, 50, 100, 150, 200};
    s.y = {0, 20, 45, 70, 95};
    s.colour = "#123456";
    plot.series.push_back(s);
    return plot;
}

}  // namespace

TEST_CASE("escape_html escapes markup characters and control characters", "[report]") {
    CHECK(escape_html("<a href=\"x\">Tom & Jerry's</a>") == "&lt;a href=&quot;x&quot;&gt;Tom &amp; Jerry&#39;s&lt;/a&gt;");
    CHECK(escape_html("plain text 90\xC2\xB0") == "plain text 90\xC2\xB0");  // UTF-8 kept
    CHECK(escape_html(std::string("a\x01" "b")) == "a\xEF\xBF\xBD" "b");
    CHECK(escape_html("tab\tnew\nline") == "tab\tnew\nline");
    CHECK(escape_html("") == "");
}

TEST_CASE("format_number uses limited precision and a dash for non-finite values", "[report]") {
    CHECK(format_number(3.14159265) == "3.142");
    CHECK(format_number(3.14159265, 2) == "3.1");
    CHECK(format_number(1.5e-6) == "1.5e-6");
    CHECK(format_number(2e6) == "2e6");
    CHECK(format_number(12345678) == "1.235e7");
    CHECK(format_number(-0.0) == "0");
    CHECK(format_number(-42.5) == "-42.5");
    CHECK(format_number(nan_value) == "\xE2\x80\x94");
    CHECK(format_number(inf_value) == "\xE2\x80\x94");
    CHECK(format_number(-inf_value) == "\xE2\x80\x94");
}

TEST_CASE("nice ticks are 1-2-5 numbers that cover the data range", "[report]") {
    const std::vector<std::pair<double, double>> ranges = {
        {0, 1}, {-3.7, 12.2}, {1e-6, 5e-6}, {42, 42}, {0, 0}, {-8.3, -0.2}, {-250, -250},
        {1000, 1000.5}, {-1e9, 3e9}, {0.1 + 0.2, 0.7}, {12.2, -3.7}};
    for (const auto& [a, b] : ranges) {
        INFO("range " << a << " .. " << b);
        const Ticks t = nice_ticks(a, b);
        const double lo = std::min(a, b), hi = std::max(a, b);
        REQUIRE(t.values.size() >= 3);
        CHECK(t.values.size() <= 12);
        CHECK(t.values.front() <= lo);
        CHECK(t.values.back() >= hi);
        CHECK(t.lo == t.values.front());
        CHECK(t.hi == t.values.back());
        CHECK(t.hi > t.lo);
        CHECK(is_nice_step(t.step));
        // Not wastefully wide: at most one step beyond the data on either side.
        if (hi > lo) CHECK(t.hi - t.lo <= (hi - lo) + 2 * t.step * (1 + 1e-9));
        for (std::size_t i = 0; i < t.values.size(); ++i) {
            const double k = t.values[i] / t.step;
            CHECK(std::abs(k - std::round(k)) < 1e-6);  // a multiple of the step
            if (i > 0) CHECK(std::abs(t.values[i] - t.values[i - 1] - t.step) < 1e-9 * t.step);
        }
    }
    CHECK(nice_ticks(0, 1).values == std::vector<double>{0, 0.2, 0.4, 0.6, 0.8, 1.0});
    CHECK(nice_ticks(-3.7, 12.2).values == std::vector<double>{-5, 0, 5, 10, 15});
    CHECK(nice_ticks(1e-6, 5e-6).values == std::vector<double>{1e-6, 2e-6, 3e-6, 4e-6, 5e-6});
    const Ticks constant = nice_ticks(42, 42);
    CHECK(constant.lo < 42);
    CHECK(constant.hi > 42);
    CHECK(constant.hi - constant.lo < 42);  // padded around the value, not from zero
    CHECK_THROWS_AS(nice_ticks(0, nan_value), std::invalid_argument);
}

TEST_CASE("log ticks cover the range with decades or 1-2-5 values", "[report]") {
    const Ticks narrow = nice_log_ticks(1e-6, 5e-6);
    CHECK(narrow.values == std::vector<double>{1e-6, 2e-6, 5e-6});
    const Ticks wide = nice_log_ticks(0.03, 2000);
    CHECK(wide.values == std::vector<double>{0.01, 0.1, 1, 10, 100, 1000, 1e4});
    const Ticks very_wide = nice_log_ticks(1e-12, 1e12);
    CHECK(very_wide.values.front() <= 1e-12);
    CHECK(very_wide.values.back() >= 1e12);
    CHECK(very_wide.values.size() <= 13);
    const Ticks constant = nice_log_ticks(3, 3);
    CHECK(constant.lo < 3);
    CHECK(constant.hi > 3);
    CHECK_THROWS_AS(nice_log_ticks(0, 1), std::invalid_argument);
    CHECK_THROWS_AS(nice_log_ticks(-1, 1), std::invalid_argument);
}

TEST_CASE("tick labels carry just enough digits and no float noise", "[report]") {
    CHECK(tick_label(0.1 + 0.2, 0.1) == "0.3");
    CHECK(tick_label(0.5, 0.5) == "0.5");
    CHECK(tick_label(100, 20) == "100");
    CHECK(tick_label(-5, 5) == "-5");
    CHECK(tick_label(-0.0, 1) == "0");
    CHECK(tick_label(1e-17, 0.1) == "0");
    CHECK(tick_label(2e-6, 1e-6) == "2e-6");
    CHECK(tick_label(2.5e-6, 5e-7) == "2.5e-6");
    CHECK(tick_label(3e9, 1e9) == "3e9");
}

TEST_CASE("line plot text is escaped and the SVG is well formed", "[report]") {
    LinePlot plot = simple_plot();
    plot.title = "Angle <deg> & \"pressure\" 'kPa'";
    plot.x_label = "p < 200 & > 0";
    plot.series[0].label = "<optimum>";
    plot.horizontal_lines = {{90, "target 90\xC2\xB0 <goal>"}};
    const std::string svg = render_svg(plot);
    CHECK(svg.find("Angle &lt;deg&gt; &amp; &quot;pressure&quot; &#39;kPa&#39;") != std::string::npos);
    CHECK(svg.find("p &lt; 200 &amp; &gt; 0") != std::string::npos);
    CHECK(svg.find("&lt;optimum&gt;") != std::string::npos);
    CHECK(svg.find("target 90\xC2\xB0 &lt;goal&gt;") != std::string::npos);
    CHECK(svg.find("<deg>") == std::string::npos);
    CHECK(svg.find("<optimum>") == std::string::npos);
    CHECK(count(svg, "<svg") == 1);
    CHECK(count(svg, "</svg>") == 1);
    CHECK(tag_balance_problem(svg) == "");
    // Axis labels are nice numbers: 0..200 kPa in steps of 50, 0..100 deg in steps of 20.
    CHECK(svg.find(">150</text>") != std::string::npos);
    CHECK(svg.find(">80</text>") != std::string::npos);
    const auto points = line_points(svg, "#123456");
    CHECK(points.size() == 5);
}

TEST_CASE("non-finite points are skipped, break the line and never print as nan or inf", "[report]") {
    LinePlot plot = simple_plot();
    plot.series[0].x = {0, 50, 100, 150, 200, 250};
    plot.series[0].y = {0, 20, nan_value, 70, 95, inf_value};
    Series bad_x;
    bad_x.label = "second";
    bad_x.x = {nan_value, 1, -inf_value, 3};
    bad_x.y = {1, 2, 3, 4};
    bad_x.style = Series::Style::line_and_markers;
    plot.series.push_back(bad_x);
    plot.horizontal_lines = {{nan_value, "bad line"}, {90, "target"}};
    plot.x_min = nan_value;  // a non-finite fixed range is ignored
    const std::string svg = render_svg(plot);
    CHECK(lower(svg).find("nan") == std::string::npos);
    CHECK(lower(svg).find("inf") == std::string::npos);
    CHECK(svg.find("bad line") == std::string::npos);
    CHECK(tag_balance_problem(svg) == "");
    std::size_t moves = 0;
    const auto points = line_points(svg, "#123456", &moves);
    CHECK(points.size() == 4);  // (0,0)-(50,20), then (150,70)-(200,95)
    CHECK(moves == 2);          // the NaN breaks the line into two pieces

    LinePlot log_plot = simple_plot();
    log_plot.log_y = true;
    log_plot.series[0].y = {-1, 0, 10, 100, 1000};
    const std::string log_svg = render_svg(log_plot);
    CHECK(lower(log_svg).find("nan") == std::string::npos);
    CHECK(lower(log_svg).find("inf") == std::string::npos);
    CHECK(log_svg.find("no data") == std::string::npos);
    CHECK(line_points(log_svg, "#123456").size() == 3);  // y <= 0 skipped on a log axis
    CHECK(log_svg.find(">1000</text>") != std::string::npos);
}

TEST_CASE("plots without drawable data render a no data SVG", "[report]") {
    LinePlot none;
    none.title = "Convergence";
    LinePlot empty_series = none;
    empty_series.series.push_back(Series{});
    LinePlot all_nan = simple_plot();
    all_nan.series[0].y.assign(5, nan_value);
    LinePlot log_negative = simple_plot();
    log_negative.log_y = true;
    log_negative.series[0].y = {-1, -2, 0, -3, -4};
    for (const LinePlot* p : {&none, &empty_series, &all_nan, &log_negative}) {
        const std::string svg = render_svg(*p);
        CHECK(svg.find("no data") != std::string::npos);
        CHECK(count(svg, "<svg") == 1);
        CHECK(count(svg, "</svg>") == 1);
        CHECK(tag_balance_problem(svg) == "");
        CHECK(lower(svg).find("nan") == std::string::npos);
    }
    CHECK(render_svg(simple_plot()).find("no data") == std::string::npos);
    BarChart no_bars;
    no_bars.title = "Margins";
    CHECK(render_svg(no_bars).find("no data") != std::string::npos);
    BarChart nan_bars = no_bars;
    nan_bars.bars = {{"a", nan_value, ""}};
    CHECK(render_svg(nan_bars).find("no data") != std::string::npos);
}

TEST_CASE("constant data and fixed ranges give a sensible plot", "[report]") {
    LinePlot constant = simple_plot();
    constant.series[0].y.assign(5, 5.0);
    const std::string svg = render_svg(constant);
    CHECK(svg.find("no data") == std::string::npos);
    CHECK(lower(svg).find("nan") == std::string::npos);
    CHECK(svg.find(">5.0</text>") != std::string::npos);  // the value is a tick inside the range
    CHECK(svg.find(">4.4</text>") != std::string::npos);  // padded by 10 %, rounded out to a tick
    const auto flat = line_points(svg, "#123456");
    REQUIRE(flat.size() == 5);
    for (const auto& p : flat) CHECK(p.second == flat.front().second);

    // Points outside a fixed range are clipped to the plot area.
    LinePlot fixed = simple_plot();
    fixed.series[0].y = {0, 20, 1e6, 70, -1e6};
    fixed.y_min = 0;
    fixed.y_max = 100;
    const std::string clipped = render_svg(fixed);
    CHECK(clipped.find(">100</text>") != std::string::npos);
    const auto points = line_points(clipped, "#123456");
    REQUIRE(points.size() >= 4);
    for (const auto& [x, y] : points) {
        CHECK(x >= 0);
        CHECK(x <= fixed.width_px);
        CHECK(y >= 0);
        CHECK(y <= fixed.height_px);
    }
}

TEST_CASE("bar chart draws one rect per bar coloured by sign", "[report]") {
    BarChart chart;
    chart.title = "Constraint margins";
    chart.value_label = "margin (normalised)";
    chart.bars = {{"stress <= limit & \"ok\"", 0.35, "35 %"},
                  {"stretch", -0.12, "violated"},
                  {"angle", 0.0, "active"},
                  {"mass", 1.7, ""},
                  {"volume", nan_value, "failed"},
                  {"pressure", -2.4, "violated"}};
    const std::string svg = render_svg(chart);
    CHECK(count(svg, "<rect class=\"bar ") == 5);  // the non-finite one draws no bar
    CHECK(count(svg, "class=\"bar negative\"") == 2);
    CHECK(count(svg, "class=\"bar positive\"") == 3);
    CHECK(count(svg, "fill=\"#d62728\"") == 2);  // red
    CHECK(count(svg, "fill=\"#2ca02c\"") == 3);  // green
    const std::regex negative_bar(R"re(<rect class="bar negative"[^>]*fill="([^"]*)")re");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), negative_bar); it != std::sregex_iterator(); ++it)
        CHECK((*it)[1] == "#d62728");
    CHECK(svg.find("stress &lt;= limit &amp; &quot;ok&quot;") != std::string::npos);
    CHECK(svg.find("violated") != std::string::npos);
    CHECK(lower(svg).find("nan") == std::string::npos);
    CHECK(tag_balance_problem(svg) == "");
    // The height grows with the number of bars.
    BarChart two = chart;
    two.bars.resize(2);
    const std::regex height(R"re(<svg[^>]* height="([0-9]+)")re");
    std::smatch m6, m2;
    REQUIRE(std::regex_search(svg, m6, height));
    const std::string svg2 = render_svg(two);
    REQUIRE(std::regex_search(svg2, m2, height));
    CHECK(std::stoi(m6[1]) > std::stoi(m2[1]));
}

TEST_CASE("HTML document contains its parts escaped and with balanced tags", "[report]") {
    HtmlDocument doc("Design <report> & 'results'");
    doc.heading(1, "Optimal design");
    doc.heading(2, "Constraints & <margins>");
    doc.heading(9, "clamped level");
    doc.paragraph("Objective < 1 & \"feasible\"\nsecond line <script>alert(1)</script>");
    doc.raw_html(render_svg(simple_plot()));
    BarChart chart;
    chart.bars = {{"a", 1, ""}, {"b", -1, ""}};
    doc.raw_html(render_svg(chart));
    doc.table({"parameter", "value <unit>"}, {{"wall", "!too thin"}, {"rings & caps", "\\!literal"}, {"short"}},
              "Table <1>");
    doc.table({"run", "objective"}, {{"1", "0.5"}, {"2", "0.4"}}, "", {"", "best"});
    doc.preformatted("x < y\n  && z");
    const std::string html = doc.str();

    CHECK(html.rfind("<!DOCTYPE html>", 0) == 0);
    CHECK(html.find("<title>Design &lt;report&gt; &amp; &#39;results&#39;</title>") != std::string::npos);
    CHECK(html.find("<h1>Optimal design</h1>") != std::string::npos);
    CHECK(html.find("<h2>Constraints &amp; &lt;margins&gt;</h2>") != std::string::npos);
    CHECK(html.find("<h6>clamped level</h6>") != std::string::npos);
    CHECK(html.find("Objective &lt; 1 &amp; &quot;feasible&quot;<br>second line &lt;script&gt;") !=
          std::string::npos);
    CHECK(html.find("<script") == std::string::npos);
    CHECK(html.find("<link") == std::string::npos);
    CHECK(html.find("src=") == std::string::npos);
    CHECK(html.find("<th>value &lt;unit&gt;</th>") != std::string::npos);
    CHECK(html.find("<td class=\"warn\">too thin</td>") != std::string::npos);
    CHECK(html.find("<td>!literal</td>") != std::string::npos);
    CHECK(html.find("<td>rings &amp; caps</td>") != std::string::npos);
    CHECK(html.find("<caption>Table &lt;1&gt;</caption>") != std::string::npos);
    CHECK(html.find("<tr class=\"best\"><td>2</td>") != std::string::npos);
    CHECK(html.find("<pre>x &lt; y\n  &amp;&amp; z</pre>") != std::string::npos);
    CHECK(count(html, "<svg") == 2);
    CHECK(count(html, "</svg>") == 2);
    CHECK(count(html, "<table") == 2);
    CHECK(count(html, "</table>") == 2);
    CHECK(count(html, "<tr") == count(html, "</tr>"));
    CHECK(count(html, "<td") == count(html, "</td>"));
    CHECK(count(html, "<td") == 3 * 2 + 2 * 2);  // the short row is padded
    CHECK(count(html, "<html") == 1);
    CHECK(count(html, "</html>") == 1);
    CHECK(tag_balance_problem(html) == "");
    CHECK(tag_balance_problem("<p><b>x</p></b>") != "");  // the checker itself can fail
}

TEST_CASE("HTML document write round-trips and names the path when it fails", "[report]") {
    HtmlDocument doc("write test");
    doc.heading(1, "Result");
    const auto dir = std::filesystem::temp_directory_path() / "softarm_test_report";
    std::filesystem::create_directories(dir);
    const auto file = dir / "report.html";
    doc.write(file);
    std::ifstream in(file, std::ios::binary);
    std::stringstream content;
    content << in.rdbuf();
    CHECK(content.str() == doc.str());
    std::filesystem::remove_all(dir);

    const std::filesystem::path missing = "/nonexistent_softarm_dir/sub/report.html";
    try {
        doc.write(missing);
        FAIL("write() to " << missing << " did not throw");
    } catch (const std::runtime_error& e) {
        CHECK(std::string(e.what()).find(missing.string()) != std::string::npos);
    }
    // A directory is not a writable file either (also as root).
    const auto as_directory = std::filesystem::temp_directory_path();
    CHECK_THROWS_WITH(doc.write(as_directory), Catch::Contains(as_directory.string()));
}

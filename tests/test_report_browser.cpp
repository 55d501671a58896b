// engine/report in a real browser (headless Chromium, tests/support/browser_render.hpp):
// a report built with HtmlDocument, LinePlot and BarChart lays out with every plot at a
// sensible size, drawn, inked and under its heading, also in a narrow window; and the
// check itself catches a zero-size plot, marks drawn off-canvas, a blank plot, script
// errors, a missing resource, a document without a doctype and one that swallows the
// measurement. Without Chromium these tests fail, naming scripts/setup.sh.
#include <catch2/catch.hpp>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "engine/report/html_document.hpp"
#include "engine/report/svg_plot.hpp"
#include "engine/workspace/workspace_report.hpp"
#include "support/browser_render.hpp"
#include "support/external_tool.hpp"

using namespace softarm::report;
using softarm::test::BrowserRender;
using softarm::test::render_in_chromium;

namespace {

namespace fs = std::filesystem;

struct TempDir {  // one per test case and process: ctest runs them in parallel
    inline static int count = 0;
    fs::path path = fs::temp_directory_path() /
                    ("softarm_test_browser_" + std::to_string(::getpid()) + "_" + std::to_string(count++));
    TempDir() { fs::create_directories(path); }
    ~TempDir() { fs::remove_all(path); }
};

BrowserRender render_or_fail(const fs::path& html, int window_width = 1280) {
    BrowserRender r = render_in_chromium(html, window_width);
    INFO(r.error);
    REQUIRE(r.ok);
    return r;
}

fs::path write(const fs::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

HtmlDocument sample_report() {
    HtmlDocument doc("Browser check <report>");
    doc.heading(1, "Design report");
    doc.paragraph("Pressure sweep of the optimum & its margins.");
    doc.heading(2, "Pressure\xE2\x80\x93" "bending curves");
    LinePlot plot;
    plot.title = "Bending angle vs pressure";
    plot.x_label = "pressure (kPa)";
    plot.y_label = "angle (deg)";
    Series a, b;
    a.label = "segment 1";
    a.x = b.x = {0, 50, 100, 150, 200};
    a.y = {0, 20, 45, 70, 95};
    b.label = "segment 2";
    b.y = {0, 15, 35, 60, 80};
    b.style = Series::Style::line_and_markers;
    b.dashed = true;
    plot.series = {a, b};
    plot.horizontal_lines = {{90, "target 90\xC2\xB0"}};
    doc.raw_html(render_svg(plot));
    doc.heading(2, "Constraint margins");
    BarChart chart;
    chart.title = "Margins of the optimum";
    chart.value_label = "margin (normalised)";
    chart.bars = {{"stress", 0.35, "35 %"}, {"stretch", -0.12, "violated"}, {"mass", 1.7, ""}, {"length", 0.0, "active"}};
    doc.raw_html(render_svg(chart));
    doc.table({"parameter", "value"}, {{"wall (mm)", "2.1"}, {"chambers", "6"}}, "Optimum");
    return doc;
}

}  // namespace

TEST_CASE("a report's plots are laid out, drawn and under their headings in Chromium", "[report][browser]") {
    if (softarm::test::skip_without(!softarm::test::find_chromium().empty(), "headless Chromium",
                                    "Debian package chromium; scripts/setup.sh installs it"))
        return;
    TempDir dir;
    const fs::path file = dir.path / "report.html";
    sample_report().write(file);

    // 500 px: Chromium's narrowest window; the body's padding leaves the plots 468 px.
    for (const int window_width : {1280, 500}) {
        INFO("window " << window_width << " px wide");
        const BrowserRender r = render_or_fail(file, window_width);
        CHECK(r.title == "Browser check <report>");
        CHECK_FALSE(r.quirks_mode);
        CHECK(r.js_errors.empty());
        CHECK(r.viewport_width == window_width);
        CHECK(r.page_width <= window_width);  // nothing overflows sideways
        REQUIRE(r.svgs.size() == 2);
        for (const auto& svg : r.svgs) {
            INFO(svg.describe());
            CHECK(svg.width > 100);
            CHECK(svg.width <= std::min(640, window_width));  // max-width: 100 % scales it down
            CHECK(svg.height > 100);
            CHECK(svg.marks_outside == 0);
            CHECK(svg.inked > 0.02);
            CHECK(svg.inked < 0.6);
        }
        const auto& line = r.svgs[0];
        CHECK(line.svg_title == "Bending angle vs pressure");
        CHECK(line.heading == "Pressure\xE2\x80\x93" "bending curves");  // non-ASCII survives the round trip
        CHECK(line.caption.empty());
        // Scaled, not clipped: 640 x 400 px and the two-row legend below the axes (2 x 16 + 14 px).
        CHECK(line.width / line.height == Approx(640.0 / (400.0 + 2 * 16 + 14)).epsilon(0.01));
        CHECK(line.marks > 25);
        CHECK(line.marks_by_element.count("path"));
        CHECK(line.marks_by_element.at("text") >= 10);  // ticks, axis labels, legend, title
        const auto& bars = r.svgs[1];
        CHECK(bars.svg_title == "Margins of the optimum");
        CHECK(bars.heading == "Constraint margins");
        CHECK(bars.marks_by_element.at("rect") >= 4);  // one per bar
        CHECK(bars.marks > 12);
    }
}

TEST_CASE("the browser check catches broken plots and pages", "[report][browser]") {
    if (softarm::test::skip_without(!softarm::test::find_chromium().empty(), "headless Chromium",
                                    "Debian package chromium; scripts/setup.sh installs it"))
        return;
    TempDir dir;
    SECTION("zero-size, off-canvas and blank plots, script errors, a missing image, no doctype") {
        const std::string broken = R"(<html><head><title>broken</title></head><body>
<h2>Empty</h2><svg xmlns="http://www.w3.org/2000/svg" width="0" height="0"><path d="M0 0 L50 50" stroke="black"/></svg>
<figure><svg xmlns="http://www.w3.org/2000/svg" width="300" height="200"><rect x="400" y="10" width="50" height="50" fill="red"/>
<rect x="10" y="10" width="50" height="50" fill="white"/></svg><figcaption>Off canvas</figcaption></figure>
<img src="missing.png" alt="">
<script>undefined_function();</script>
</body></html>)";
        const BrowserRender r = render_or_fail(write(dir.path / "broken.html", broken));
        CHECK(r.title == "broken");
        CHECK(r.quirks_mode);
        REQUIRE(r.svgs.size() == 2);
        INFO(r.svgs[0].describe() << "\n" << r.svgs[1].describe());
        CHECK(r.svgs[0].heading == "Empty");
        CHECK(r.svgs[0].width == 0);
        CHECK(r.svgs[0].marks == 0);
        CHECK(r.svgs[0].marks_outside == 1);
        CHECK(r.svgs[0].inked == 0);
        CHECK(r.svgs[1].heading == "Empty");
        CHECK(r.svgs[1].caption == "Off canvas");
        CHECK(r.svgs[1].width == 300);
        CHECK(r.svgs[1].marks == 1);
        CHECK(r.svgs[1].marks_outside == 1);
        CHECK(r.svgs[1].inked == 0);  // the only visible mark is white
        INFO(r.js_errors.size() << " errors: " << (r.js_errors.empty() ? "" : r.js_errors[0]));
        REQUIRE(r.js_errors.size() == 2);  // the script's first; the image fails later
        const auto error_naming = [&](const std::string& what) {
            return std::count_if(r.js_errors.begin(), r.js_errors.end(),
                                 [&](const std::string& e) { return e.find(what) != std::string::npos; });
        };
        CHECK(error_naming("missing.png") == 1);
        CHECK(error_naming("undefined_function") == 1);
    }
    SECTION("a document that swallows the measurement is an error, not an empty pass") {
        const fs::path file = write(dir.path / "comment.html", "<!DOCTYPE html><title>x</title><body><!-- unclosed");
        const BrowserRender r = render_in_chromium(file);
        CHECK_FALSE(r.ok);
        CHECK_THAT(r.error, Catch::Contains("did not report"));
    }
    SECTION("a missing Chromium or file is reported, naming scripts/setup.sh") {
        const fs::path file = write(dir.path / "ok.html", "<!DOCTYPE html><title>x</title>");
        const char* previous = std::getenv("SOFTARM_CHROMIUM");
        const std::string saved = previous ? previous : "";
        ::setenv("SOFTARM_CHROMIUM", "/nonexistent/chromium", 1);
        const BrowserRender r = render_in_chromium(file);
        if (previous)
            ::setenv("SOFTARM_CHROMIUM", saved.c_str(), 1);
        else
            ::unsetenv("SOFTARM_CHROMIUM");
        CHECK_FALSE(r.ok);
        CHECK_THAT(r.error, Catch::Contains("scripts/setup.sh"));
        const BrowserRender missing = render_in_chromium(dir.path / "nonexistent.html");
        CHECK_FALSE(missing.ok);
        CHECK_THAT(missing.error, Catch::Contains("nonexistent.html"));
    }
}

TEST_CASE("the workspace report draws the tips in three projections in Chromium", "[report][browser][workspace]") {
    if (softarm::test::skip_without(!softarm::test::find_chromium().empty(), "headless Chromium",
                                    "Debian package chromium; scripts/setup.sh installs it"))
        return;
    TempDir dir;
    // Tips on a bowl under the shoulder, as a hanging arm's: enough to see the drawing, no cells needed.
    softarm::studies::WorkspaceResult w;
    for (int i = 0; i < 400; ++i) {
        softarm::studies::WorkspacePoint p;
        p.ok = i % 50 != 7;  // a few not reached: left out of the plots
        const double a = 0.1 * i, r = 150.0 * (i % 20) / 20;
        p.tip_mm = {r * std::cos(a), r * std::sin(a), -20 + r * r / 300};
        p.pressure_sum_kPa = 10.0 * i;
        p.tip_tilt_deg = r / 3;
        w.points.push_back(p);
        if (!p.ok) continue;
        ++w.reached;
        w.lower_mm = w.lower_mm.cwiseMin(p.tip_mm);
        w.upper_mm = w.upper_mm.cwiseMax(p.tip_mm);
    }
    const fs::path file = dir.path / "report.html";
    softarm::engine::write_workspace_report(file.string(), w, "pressure_sum", "configs/spl_thesis_pose.json");
    const BrowserRender r = render_or_fail(file);
    CHECK(r.js_errors.empty());
    REQUIRE(r.svgs.size() == 3);
    for (const auto& svg : r.svgs) {
        INFO(svg.describe());
        CHECK(svg.width > 100);
        CHECK(svg.marks > 20);  // the four bands' markers (a path each), axes, ticks and legend
        CHECK(svg.marks_outside == 0);
        CHECK(svg.inked > 0.02);
    }
    CHECK(r.svgs[0].svg_title == "Seen from above (x-y)");
    // Coloured by a payload margin computed at every third pose only: the others in grey beneath, the
    // bands over the margins.
    for (std::size_t i = 0; i < w.points.size(); i += 3) w.points[i].payload_margin_kg = 0.01 * static_cast<double>(i);
    const fs::path margins = dir.path / "margins.html";
    softarm::engine::write_workspace_report(margins.string(), w, "payload_margin", "configs/spl_thesis_pose.json");
    const BrowserRender m = render_or_fail(margins);
    CHECK(m.js_errors.empty());
    REQUIRE(m.svgs.size() == 3);
    for (const auto& svg : m.svgs) {
        INFO(svg.describe());
        CHECK(svg.marks > 20);
        CHECK(svg.marks_outside == 0);
    }
    std::ifstream text(margins);
    const std::string html((std::istreambuf_iterator<char>(text)), std::istreambuf_iterator<char>());
    CHECK_THAT(html, Catch::Contains("not computed"));
    CHECK_THAT(html, Catch::Contains("payload margin"));
}

#pragma once
// Renders an HTML file in headless Chromium (Debian package `chromium`, installed by
// scripts/setup.sh) and reports what the browser actually laid out, so that a test can
// check a report "looks right in a real browser", not only that its markup is well formed.
//
//     const auto r = softarm::test::render_in_chromium(dir / "report.html");
//     REQUIRE(r.ok);                 // else r.error says why (no chromium: run scripts/setup.sh)
//     CHECK(r.js_errors.empty());
//     for (const auto& svg : r.svgs) {
//         INFO(svg.describe());
//         CHECK(svg.width > 100);
//         CHECK(svg.marks > 10);
//         CHECK(svg.inked > 0.01);
//     }
//
// How: the file is copied into a fresh temporary directory (relative links then no longer
// resolve, and show up in js_errors: reports must be self-contained, as HtmlDocument's
// are) with two scripts injected: one at the start of <head> that records
// errors (uncaught exceptions, unhandled rejections, console.error, resources that fail to
// load), one at the end of <body> that, on the load event, measures every outermost <svg>
// and writes a JSON blob into <pre id="softarm-render-check">. Chromium runs with
// --headless --no-sandbox (needed as root) --dump-dom --virtual-time-budget under
// `timeout`; the JSON is parsed back from the dumped DOM. Chromium's stderr (dbus noise)
// is ignored unless it fails. One render takes about 1-2.5 s. The temporary directory is
// removed afterwards unless SOFTARM_KEEP_RENDER is set (then the instrumented copy, the
// dumped DOM and Chromium's log stay there for a look).
//
// The executable is $SOFTARM_CHROMIUM if set (it must then be executable), else the first
// of chromium, chromium-browser, google-chrome, google-chrome-stable found on PATH.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace softarm::test {

/// One outermost <svg> element as laid out by the browser, in document order.
struct RenderedSvg {
    double width = 0, height = 0;  ///< getBoundingClientRect() in CSS px (after CSS scaling)
    /// Drawn marks: path, polyline, polygon, line, rect, circle, ellipse and text elements
    /// in it that are not display:none / visibility:hidden and whose rendered bounding box
    /// is not empty (width or height > 0: a horizontal line counts) and overlaps the svg's
    /// box (so an svg of zero size has none).
    int marks = 0;
    std::map<std::string, int> marks_by_element;  ///< e.g. {"path", 14}, {"text", 19}
    /// Visible, non-empty marks entirely outside the svg's box (drawn off-canvas).
    int marks_outside = 0;
    /// Fraction (0..1) of the svg's pixels that are not white when the browser rasterises
    /// it on its own (serialised, drawn on a white canvas at its rendered size; page CSS
    /// does not apply there); -1 if that failed. 0 means the plot is blank.
    double inked = -1;
    std::string heading;    ///< text of the nearest h1-h6 before it in the document, or ""
    std::string caption;    ///< <figcaption> of the enclosing <figure>, or ""
    std::string svg_title;  ///< its own <title> child (the plot title of svg_plot.hpp), or ""

    /// "svg 2 'Bending angle' under 'Pressure curves': 640x400 px, 36 marks, 8.8 % inked"
    /// for INFO() messages.
    std::string describe() const;
};

struct BrowserRender {
    bool ok = false;     ///< chromium ran and the measurement came back
    std::string error;   ///< why not, when !ok (missing chromium, timeout, no measurement, …)
    std::string title;   ///< document.title
    bool quirks_mode = false;  ///< document.compatMode == "BackCompat" (no <!DOCTYPE html>)
    /// window.innerWidth: the window_width asked for, but at least 500 (Chromium's
    /// smallest window, headless too).
    double viewport_width = 0;
    double page_width = 0, page_height = 0;  ///< document.documentElement scroll size, CSS px
    std::vector<RenderedSvg> svgs;
    /// Uncaught exceptions, unhandled promise rejections, console.error() calls and
    /// resources (img, link, script) that failed to load, in the order they happened.
    std::vector<std::string> js_errors;
};

/// The Chromium executable (see above), or "" if none is installed.
std::filesystem::path find_chromium();

/// Renders `html` in a `window_width` x 900 px headless window (500 px wide at least). Never throws for a
/// rendering problem: ok = false and `error` tell. Without Chromium, `error` says to run
/// scripts/setup.sh.
BrowserRender render_in_chromium(const std::filesystem::path& html, int window_width = 1280,
                                 int timeout_s = 60);

}  // namespace softarm::test

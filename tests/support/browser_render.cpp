#include "browser_render.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>
#include <system_error>

#include <nlohmann/json.hpp>

namespace softarm::test {

namespace {

namespace fs = std::filesystem;

const char* const check_id = "softarm-render-check";

// Injected first thing in <head>: records errors before the page's own scripts run.
// The capture-phase listener also sees resources that fail to load (those events do
// not bubble to window).
const char* const error_recorder = R"js(<script>
window.__softarmErrors = [];
window.addEventListener('error', function (e) {
  var t = e.target;
  if (t && t !== window && t.tagName)
    window.__softarmErrors.push('failed to load <' + t.tagName.toLowerCase() + '> ' + (t.src || t.href || ''));
  else
    window.__softarmErrors.push((e.message || 'error') + (e.filename ? ' at ' + e.filename + ':' + e.lineno : ''));
}, true);
window.addEventListener('unhandledrejection', function (e) { window.__softarmErrors.push('unhandled rejection: ' + e.reason); });
(function () {
  var original = console.error;
  console.error = function () {
    window.__softarmErrors.push('console.error: ' + Array.prototype.join.call(arguments, ' '));
    return original.apply(console, arguments);
  };
})();
</script>
)js";

// Injected at the end of <body>: after the load event, measures every outermost <svg>,
// rasterises each on its own to count inked pixels, and writes the JSON into the <pre>.
// Characters that the DOM serialiser would escape (< > & and non-ASCII, e.g. U+00A0 as
// &nbsp;) are written as \uXXXX, so the dumped text is the JSON verbatim.
const char* const measurement = R"js(<script>
(function () {
  'use strict';
  var out = document.getElementById('softarm-render-check');
  function text(e) { return e ? (e.textContent || '').replace(/\s+/g, ' ').trim() : ''; }
  function heading_before(svg) {
    var all = document.querySelectorAll('h1,h2,h3,h4,h5,h6'), best = null;
    for (var i = 0; i < all.length; ++i)
      if (all[i].compareDocumentPosition(svg) & Node.DOCUMENT_POSITION_FOLLOWING) best = all[i];
    return text(best);
  }
  function caption_of(svg) {
    var figure = svg.closest('figure');
    return figure ? text(figure.querySelector('figcaption')) : '';
  }
  function inked_fraction(svg, done) {
    var r = svg.getBoundingClientRect(), w = Math.round(r.width), h = Math.round(r.height);
    if (w < 1 || h < 1) { done(0); return; }
    var copy = svg.cloneNode(true);
    copy.setAttribute('width', w);
    copy.setAttribute('height', h);
    copy.setAttribute('xmlns', 'http://www.w3.org/2000/svg');
    var img = new Image();
    img.onload = function () {
      try {
        var canvas = document.createElement('canvas');
        canvas.width = w;
        canvas.height = h;
        var g = canvas.getContext('2d');
        g.fillStyle = '#fff';
        g.fillRect(0, 0, w, h);
        g.drawImage(img, 0, 0, w, h);
        var d = g.getImageData(0, 0, w, h).data, n = 0;
        for (var i = 0; i < d.length; i += 4) if (d[i] < 250 || d[i + 1] < 250 || d[i + 2] < 250) ++n;
        done(n / (w * h));
      } catch (e) { done(-1); }
    };
    img.onerror = function () { done(-1); };
    img.src = 'data:image/svg+xml;charset=utf-8,' + encodeURIComponent(new XMLSerializer().serializeToString(copy));
  }
  function measure() {
    var svgs = Array.prototype.filter.call(document.querySelectorAll('svg'),
                                           function (s) { return !(s.parentElement && s.parentElement.closest('svg')); });
    var root = document.documentElement;
    var result = { title: document.title, quirks_mode: document.compatMode === 'BackCompat',
                   viewport_width: window.innerWidth, page_width: root.scrollWidth, page_height: root.scrollHeight,
                   js_errors: window.__softarmErrors || [], svgs: [] };
    function finish() {
      out.textContent = JSON.stringify(result).replace(/[<>&\u007f-\uffff]/g, function (c) {
        return '\\u' + ('0000' + c.charCodeAt(0).toString(16)).slice(-4);
      });
    }
    svgs.forEach(function (svg, k) {
      var r = svg.getBoundingClientRect(), marks = {}, total = 0, outside = 0;
      svg.querySelectorAll('path,polyline,polygon,line,rect,circle,ellipse,text').forEach(function (e) {
        var b = e.getBoundingClientRect(), style = getComputedStyle(e);
        if (!(b.width > 0 || b.height > 0) || style.display === 'none' || style.visibility === 'hidden') return;
        // The part of its box inside the svg's: a horizontal or vertical line has one
        // side 0; nothing is inside an svg of zero size.
        var w = Math.min(b.right, r.right) - Math.max(b.left, r.left);
        var h = Math.min(b.bottom, r.bottom) - Math.max(b.top, r.top);
        if (!(w >= 0 && h >= 0 && w + h > 0)) { ++outside; return; }
        var tag = e.tagName.toLowerCase();
        marks[tag] = (marks[tag] || 0) + 1;
        ++total;
      });
      var title = svg.querySelector(':scope > title');
      result.svgs[k] = { width: r.width, height: r.height, marks: total, marks_by_element: marks,
                         marks_outside: outside, inked: -1, heading: heading_before(svg),
                         caption: caption_of(svg), svg_title: text(title) };
    });
    var pending = svgs.length;
    if (!pending) { finish(); return; }
    svgs.forEach(function (svg, k) {
      inked_fraction(svg, function (f) { result.svgs[k].inked = f; if (--pending === 0) finish(); });
    });
  }
  if (document.readyState === 'complete') measure(); else window.addEventListener('load', measure);
})();
</script>
)js";

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

/// Position just after the '>' of the first tag `<name` (case-insensitive), or npos.
std::size_t after_open_tag(const std::string& html_lower, const std::string& name) {
    for (auto pos = html_lower.find("<" + name); pos != std::string::npos; pos = html_lower.find("<" + name, pos + 1)) {
        const char next = pos + 1 + name.size() < html_lower.size() ? html_lower[pos + 1 + name.size()] : '>';
        if (next != '>' && !std::isspace(static_cast<unsigned char>(next))) continue;  // <header>, <html5…>
        const auto end = html_lower.find('>', pos);
        return end == std::string::npos ? std::string::npos : end + 1;
    }
    return std::string::npos;
}

/// `html` with the error recorder at the start of <head> (after <html> or <!DOCTYPE>
/// without one; never before the doctype, which would switch to quirks mode) and the
/// measurement before the last </body> (at the end without one).
std::string instrument(std::string html) {
    const std::string low = lower(html);
    const std::string tail = std::string("<pre id=\"") + check_id + "\"></pre>\n" + measurement;
    const auto body_end = low.rfind("</body");
    if (body_end == std::string::npos)
        html += tail;
    else
        html.insert(body_end, tail);
    std::size_t head = after_open_tag(low, "head");
    if (head == std::string::npos) head = after_open_tag(low, "html");
    if (head == std::string::npos) head = after_open_tag(low, "!doctype");
    html.insert(head == std::string::npos ? 0 : head, error_recorder);
    return html;
}

std::string shell_quote(const std::string& s) {
    std::string q = "'";
    for (const char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

std::string read_file(const fs::path& path, bool* ok = nullptr) {
    std::ifstream in(path, std::ios::binary);
    if (ok) *ok = static_cast<bool>(in);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

/// The last lines of Chromium's stderr that are not its usual noise (dbus, the
/// launcher script's shell warning), for error messages.
std::string stderr_summary(const fs::path& path) {
    std::istringstream in(read_file(path));
    std::vector<std::string> kept;
    for (std::string line; std::getline(in, line);) {
        if (line.empty() || line.find("dbus") != std::string::npos || line.find("unexpected operator") != std::string::npos)
            continue;
        kept.push_back(line);
    }
    std::string out;
    for (std::size_t i = kept.size() > 8 ? kept.size() - 8 : 0; i < kept.size(); ++i) out += "\n  " + kept[i];
    return out.empty() ? "" : "; chromium's stderr:" + out;
}

fs::path fresh_directory() {
    static std::atomic<unsigned> counter{0};
    std::random_device random;
    const fs::path dir = fs::temp_directory_path() / ("softarm_render_" + std::to_string(::getpid()) + "_" +
                                                      std::to_string(counter++) + "_" + std::to_string(random()));
    fs::create_directories(dir);
    return dir;
}

void parse_measurement(const std::string& json_text, BrowserRender& r) {
    const auto j = nlohmann::json::parse(json_text);
    r.title = j.at("title").get<std::string>();
    r.quirks_mode = j.at("quirks_mode").get<bool>();
    r.viewport_width = j.at("viewport_width").get<double>();
    r.page_width = j.at("page_width").get<double>();
    r.page_height = j.at("page_height").get<double>();
    for (const auto& e : j.at("js_errors")) r.js_errors.push_back(e.get<std::string>());
    for (const auto& s : j.at("svgs")) {
        RenderedSvg svg;
        svg.width = s.at("width").get<double>();
        svg.height = s.at("height").get<double>();
        svg.marks = s.at("marks").get<int>();
        for (const auto& [tag, n] : s.at("marks_by_element").items()) svg.marks_by_element[tag] = n.get<int>();
        svg.marks_outside = s.at("marks_outside").get<int>();
        svg.inked = s.at("inked").get<double>();
        svg.heading = s.at("heading").get<std::string>();
        svg.caption = s.at("caption").get<std::string>();
        svg.svg_title = s.at("svg_title").get<std::string>();
        r.svgs.push_back(std::move(svg));
    }
}

}  // namespace

std::string RenderedSvg::describe() const {
    char numbers[160];
    std::snprintf(numbers, sizeof numbers, "%.0fx%.0f px, %d marks (%d outside), %.1f %% inked", width, height, marks,
                  marks_outside, inked * 100);
    std::string out = "svg '" + svg_title + "'";
    if (!heading.empty()) out += " under '" + heading + "'";
    if (!caption.empty()) out += " captioned '" + caption + "'";
    return out + ": " + numbers;
}

fs::path find_chromium() {
    if (const char* forced = std::getenv("SOFTARM_CHROMIUM"); forced && *forced)
        return ::access(forced, X_OK) == 0 ? fs::path(forced) : fs::path();
    const char* path = std::getenv("PATH");
    std::vector<fs::path> dirs;
    std::istringstream in(path ? path : "/usr/bin:/bin");
    for (std::string dir; std::getline(in, dir, ':');)
        if (!dir.empty()) dirs.emplace_back(dir);
    for (const char* name : {"chromium", "chromium-browser", "google-chrome", "google-chrome-stable"})
        for (const auto& dir : dirs)
            if (::access((dir / name).c_str(), X_OK) == 0) return dir / name;
    return {};
}

BrowserRender render_in_chromium(const fs::path& html, int window_width, int timeout_s) {
    BrowserRender r;
    const fs::path chromium = find_chromium();
    if (chromium.empty()) {
        const char* forced = std::getenv("SOFTARM_CHROMIUM");
        r.error = std::string("headless Chromium is not installed (") +
                  (forced && *forced ? "SOFTARM_CHROMIUM='" + std::string(forced) + "' is not executable"
                                     : std::string("no chromium on PATH")) +
                  "): run scripts/setup.sh (Debian package `chromium`)";
        return r;
    }
    bool readable = false;
    const std::string source = read_file(html, &readable);
    if (!readable) {
        r.error = "cannot read '" + html.string() + "'";
        return r;
    }
    fs::path dir;
    try {
        dir = fresh_directory();
    } catch (const fs::filesystem_error& e) {
        r.error = std::string("cannot create a temporary directory: ") + e.what();
        return r;
    }
    const fs::path copy = dir / html.filename();
    if (!(std::ofstream(copy, std::ios::binary) << instrument(source))) {
        r.error = "cannot write '" + copy.string() + "'";
        return r;
    }
    const fs::path out = dir / "dom.html", err = dir / "chromium.log";
    // --user-data-dir: a profile per call, so concurrent renders (ctest -j) do not meet;
    // --disable-dev-shm-usage: containers often have a tiny /dev/shm; the virtual time
    // budget lets the load event and the image decoding finish before the DOM is dumped.
    const std::string command =
        "timeout -k 5 " + std::to_string(timeout_s) + " " + shell_quote(chromium.string()) +
        " --headless --no-sandbox --disable-gpu --disable-dev-shm-usage --no-first-run --disable-extensions"
        " --hide-scrollbars --mute-audio --user-data-dir=" + shell_quote((dir / "profile").string()) +
        " --window-size=" + std::to_string(window_width) + ",900 --virtual-time-budget=5000 --dump-dom " +
        shell_quote(fs::absolute(copy).string()) + " >" + shell_quote(out.string()) + " 2>" +
        shell_quote(err.string()) + " </dev/null";
    const int status = std::system(command.c_str());
    const int code = status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    const std::string dom = read_file(out);
    const std::string open = std::string("<pre id=\"") + check_id + "\">";
    const auto begin = dom.find(open);
    const auto end = begin == std::string::npos ? std::string::npos : dom.find("</pre>", begin);
    const std::string json_text =
        end == std::string::npos ? std::string() : dom.substr(begin + open.size(), end - begin - open.size());

    if (code == 124 || code == 137)
        r.error = "chromium did not finish within " + std::to_string(timeout_s) + " s";
    else if (code != 0)
        r.error = "chromium failed (exit status " + std::to_string(code) + ")";
    else if (json_text.empty())
        r.error = "the measurement script did not report (document malformed, e.g. an unclosed comment or "
                  "<script>, or the page replaced its body?)";
    if (r.error.empty()) {
        try {
            parse_measurement(json_text, r);
            r.ok = true;
        } catch (const std::exception& e) {
            r.error = std::string("cannot parse the measurement: ") + e.what();
        }
    }
    const char* keep = std::getenv("SOFTARM_KEEP_RENDER");
    if (!r.ok)
        r.error += stderr_summary(err) + (keep ? " (files kept in " + dir.string() + ")"
                                               : std::string(" (SOFTARM_KEEP_RENDER=1 keeps the files)"));
    if (!keep) {
        std::error_code ignored;
        fs::remove_all(dir, ignored);
    }
    return r;
}

}  // namespace softarm::test

#pragma once
// A single self-contained HTML file (inline CSS, no scripts, no external
// resources) for the reports of `softarm design` and friends. Text given to
// heading(), paragraph(), table() and preformatted() is escaped; raw_html()
// inserts markup verbatim (an SVG from svg_plot.hpp, for instance).
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace softarm::report {

/// Escapes & < > " ' (as &amp; &lt; &gt; &quot; &#39;, valid in both HTML and
/// XML/SVG) and replaces control characters other than tab, newline and
/// carriage return (not allowed in XML) by U+FFFD.
std::string escape_html(std::string_view text);

/// `value` with `significant_digits` significant digits (clamped to 1..17),
/// as printf's %g but with a compact exponent ("1.5e-6", "2e6") and never
/// "-0"; "—" (U+2014) for NaN and ±infinity.
std::string format_number(double value, int significant_digits = 4);

class HtmlDocument {
public:
    explicit HtmlDocument(std::string title);

    /// <h1>…<h6>; `level` is clamped to 1..6.
    void heading(int level, const std::string& text);
    /// <p>; escaped, newlines become <br>.
    void paragraph(const std::string& text);
    /// Inserted verbatim into the body.
    void raw_html(const std::string& html);
    /// <table> with an optional <caption>. Cells are escaped. A cell whose text
    /// starts with '!' is a warning: the '!' is dropped and the cell gets
    /// class "warn" (red). Start a cell with "\!" to show a literal leading '!'.
    /// Rows shorter than the header are padded with empty cells.
    void table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows,
               const std::string& caption = "");
    /// As above, with a class per row: "" (none), or e.g. "warn" (red), "ok"
    /// (green), "muted" (grey), "best" (bold); any other class name is kept
    /// (escaped) for custom CSS added by raw_html(). Missing entries mean "".
    void table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows,
               const std::string& caption, const std::vector<std::string>& row_classes);
    /// <pre>; escaped.
    void preformatted(const std::string& text);

    /// The complete document: <!DOCTYPE html> … </html>.
    std::string str() const;
    /// Writes str() to `path` (replacing it); throws std::runtime_error naming
    /// the path if it cannot be opened or written.
    void write(const std::filesystem::path& path) const;

private:
    std::string title_;
    std::string body_;
};

}  // namespace softarm::report

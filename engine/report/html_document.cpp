#include "engine/report/html_document.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace softarm::report {

std::string escape_html(std::string_view text) {
    std::string out;
    out.reserve(text.size() + text.size() / 8);
    for (const char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&#39;"; break;
            default:
                if ((static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7f)
                    out += "\xEF\xBF\xBD";  // U+FFFD: control characters are not allowed in XML
                else
                    out += c;
        }
    }
    return out;
}

std::string format_number(double value, int significant_digits) {
    if (!std::isfinite(value)) return "\xE2\x80\x94";  // em dash
    if (value == 0.0) return "0";                       // also -0
    const int digits = std::clamp(significant_digits, 1, 17);
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
    std::string text = buffer;
    // Compact exponent: "1.5e-06" -> "1.5e-6", "2e+06" -> "2e6".
    if (const auto e = text.find('e'); e != std::string::npos) {
        std::string mantissa = text.substr(0, e);
        std::string exponent = text.substr(e + 1);
        bool negative = false;
        if (!exponent.empty() && (exponent[0] == '+' || exponent[0] == '-')) {
            negative = exponent[0] == '-';
            exponent.erase(0, 1);
        }
        const auto nonzero = exponent.find_first_not_of('0');
        exponent = nonzero == std::string::npos ? "0" : exponent.substr(nonzero);
        text = mantissa + "e" + (negative ? "-" : "") + exponent;
    }
    if (text == "-0") text = "0";
    return text;
}

namespace {

const char* const css = R"(body{font-family:-apple-system,"Segoe UI",Helvetica,Arial,sans-serif;color:#222;max-width:980px;margin:1.5em auto;padding:0 1em;line-height:1.45}
h1,h2,h3,h4,h5,h6{line-height:1.2;margin:1.2em 0 .5em}
h1{font-size:1.7em;border-bottom:2px solid #ddd;padding-bottom:.2em}
h2{font-size:1.35em;border-bottom:1px solid #eee;padding-bottom:.15em}
table{border-collapse:collapse;margin:.8em 0;font-size:.92em}
caption{caption-side:top;text-align:left;font-weight:600;padding:.2em 0}
th,td{border:1px solid #ccc;padding:.25em .6em;text-align:left;vertical-align:top}
th{background:#f2f2f2}
tr:nth-child(even) td{background:#fafafa}
td.warn,tr.warn td{background:#fde2e0;color:#a40000}
tr.ok td{background:#e6f4e6}
tr.muted td{color:#888}
tr.best td{font-weight:700}
pre{background:#f6f6f6;border:1px solid #e2e2e2;padding:.6em;overflow-x:auto;font-size:.88em}
svg{display:block;max-width:100%;height:auto;margin:.6em 0})";

}  // namespace

HtmlDocument::HtmlDocument(std::string title) : title_(std::move(title)) {}

void HtmlDocument::heading(int level, const std::string& text) {
    const std::string l = std::to_string(std::clamp(level, 1, 6));
    body_ += "<h" + l + ">" + escape_html(text) + "</h" + l + ">\n";
}

void HtmlDocument::paragraph(const std::string& text) {
    std::string escaped = escape_html(text);
    std::string out;
    out.reserve(escaped.size());
    for (const char c : escaped) {
        if (c == '\n')
            out += "<br>";
        else
            out += c;
    }
    body_ += "<p>" + out + "</p>\n";
}

void HtmlDocument::raw_html(const std::string& html) {
    body_ += html;
    if (html.empty() || html.back() != '\n') body_ += '\n';
}

void HtmlDocument::table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows,
                         const std::string& caption) {
    table(header, rows, caption, {});
}

void HtmlDocument::table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows,
                         const std::string& caption, const std::vector<std::string>& row_classes) {
    std::string out = "<table>\n";
    if (!caption.empty()) out += "<caption>" + escape_html(caption) + "</caption>\n";
    if (!header.empty()) {
        out += "<thead><tr>";
        for (const auto& h : header) out += "<th>" + escape_html(h) + "</th>";
        out += "</tr></thead>\n";
    }
    out += "<tbody>\n";
    for (std::size_t r = 0; r < rows.size(); ++r) {
        const std::string row_class = r < row_classes.size() ? row_classes[r] : std::string();
        out += row_class.empty() ? "<tr>" : "<tr class=\"" + escape_html(row_class) + "\">";
        const std::size_t columns = std::max(rows[r].size(), header.size());
        for (std::size_t c = 0; c < columns; ++c) {
            std::string_view cell = c < rows[r].size() ? std::string_view(rows[r][c]) : std::string_view();
            if (!cell.empty() && cell[0] == '!') {
                out += "<td class=\"warn\">" + escape_html(cell.substr(1)) + "</td>";
            } else {
                if (cell.size() >= 2 && cell[0] == '\\' && cell[1] == '!') cell.remove_prefix(1);
                out += "<td>" + escape_html(cell) + "</td>";
            }
        }
        out += "</tr>\n";
    }
    out += "</tbody>\n</table>\n";
    body_ += out;
}

void HtmlDocument::preformatted(const std::string& text) { body_ += "<pre>" + escape_html(text) + "</pre>\n"; }

std::string HtmlDocument::str() const {
    std::string out;
    out.reserve(body_.size() + 2048);
    out += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
    out += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
    out += "<title>" + escape_html(title_) + "</title>\n";
    out += "<style>\n";
    out += css;
    out += "\n</style>\n</head>\n<body>\n";
    out += body_;
    out += "</body>\n</html>\n";
    return out;
}

void HtmlDocument::write(const std::filesystem::path& path) const {
    const std::string text = str();
    std::ofstream file(path, std::ios::binary | std::ios::trunc);
    if (!file) {
        const int error = errno;
        throw std::runtime_error("cannot open HTML report '" + path.string() + "' for writing" +
                                 (error != 0 ? std::string(": ") + std::strerror(error) : std::string()));
    }
    file.write(text.data(), static_cast<std::streamsize>(text.size()));
    file.close();
    if (!file) throw std::runtime_error("cannot write HTML report '" + path.string() + "'");
}

}  // namespace softarm::report

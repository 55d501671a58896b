#include "engine/study/shape_svg.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "engine/report/html_document.hpp"

namespace softarm::engine {
using nlohmann::json;

namespace {

struct Segment {
  double x0, y0, x1, y1;
  std::string colour;
  double width;
};

std::string draw(const std::vector<Segment>& segments, const std::string& caption, int height_px) {
  double xmin = std::numeric_limits<double>::max(), xmax = -xmin, ymin = xmin, ymax = -xmin;
  for (const Segment& s : segments) {
    xmin = std::min({xmin, s.x0, s.x1});
    xmax = std::max({xmax, s.x0, s.x1});
    ymin = std::min({ymin, s.y0, s.y1});
    ymax = std::max({ymax, s.y0, s.y1});
  }
  if (segments.empty() || !(xmax > xmin) || !(ymax > ymin)) return "";
  constexpr double kMargin = 12, kCaption = 22;
  const double scale = (height_px - 2 * kMargin - kCaption) / (ymax - ymin);
  const int width_px = static_cast<int>(std::ceil((xmax - xmin) * scale + 2 * kMargin));
  const auto X = [&](double x) { return kMargin + (x - xmin) * scale; };
  const auto Y = [&](double y) { return kMargin + (ymax - y) * scale; };  // up is up
  std::ostringstream svg;
  svg.setf(std::ios::fixed);
  svg.precision(1);
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << std::max(width_px, 160) << "\" height=\"" << height_px
      << "\" viewBox=\"0 0 " << std::max(width_px, 160) << " " << height_px << "\" class=\"shape\">";
  svg << "<rect x=\"0\" y=\"0\" width=\"100%\" height=\"100%\" fill=\"#fff\" stroke=\"#ccc\"/>";
  for (const Segment& s : segments)
    svg << "<line x1=\"" << X(s.x0) << "\" y1=\"" << Y(s.y0) << "\" x2=\"" << X(s.x1) << "\" y2=\"" << Y(s.y1)
        << "\" stroke=\"" << s.colour << "\" stroke-width=\"" << s.width << "\"/>";
  svg << "<text x=\"" << kMargin << "\" y=\"" << height_px - 7 << "\" font-size=\"12\" font-family=\"sans-serif\">"
      << report::escape_html(caption) << "</text></svg>";
  return svg.str();
}

std::vector<Segment> axisymmetric(const json& shape) {
  std::vector<Segment> out;
  for (const auto& [part, edges] : shape.at("parts").items()) {
    const std::string colour = part == "rings" ? "#d62728" : "#1f77b4";
    for (const auto& e : edges)
      for (double mirror : {1.0, -1.0})  // the section through the axis shows both sides
        out.push_back({mirror * e[0].get<double>(), e[1].get<double>(), mirror * e[2].get<double>(),
                       e[3].get<double>(), colour, 1.0});
  }
  return out;
}

std::vector<Segment> rod(const json& shape) {
  const auto x = shape.at("x_mm").get<std::vector<double>>(), z = shape.at("z_mm").get<std::vector<double>>();
  const auto w = shape.at("half_width_mm").get<std::vector<double>>();
  std::vector<Segment> out;
  const std::size_t n = std::min({x.size(), z.size(), w.size()});
  std::vector<double> lx, lz, rx, rz;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t a = i ? i - 1 : i, b = i + 1 < n ? i + 1 : i;
    const double tx = x[b] - x[a], tz = z[b] - z[a], len = std::hypot(tx, tz);
    const double nx = len > 0 ? -tz / len : 1, nz = len > 0 ? tx / len : 0;  // normal to the centreline
    lx.push_back(x[i] + w[i] * nx), lz.push_back(z[i] + w[i] * nz);
    rx.push_back(x[i] - w[i] * nx), rz.push_back(z[i] - w[i] * nz);
  }
  for (std::size_t i = 1; i < n; ++i) {
    out.push_back({x[i - 1], z[i - 1], x[i], z[i], "#888", 1.0});
    out.push_back({lx[i - 1], lz[i - 1], lx[i], lz[i], "#1f77b4", 1.5});
    out.push_back({rx[i - 1], rz[i - 1], rx[i], rz[i], "#1f77b4", 1.5});
  }
  if (n > 1) {  // the end faces
    out.push_back({lx[0], lz[0], rx[0], rz[0], "#333", 2.0});
    out.push_back({lx[n - 1], lz[n - 1], rx[n - 1], rz[n - 1], "#333", 2.0});
  }
  return out;
}

}  // namespace

std::string render_shape_svg(const json& shape, const std::string& caption, int height_px) {
  const std::string kind = shape.value("kind", std::string());
  if (kind == "axisymmetric_outline") return draw(axisymmetric(shape), caption, height_px);
  if (kind == "rod_centreline") return draw(rod(shape), caption, height_px);
  return "";
}

}  // namespace softarm::engine

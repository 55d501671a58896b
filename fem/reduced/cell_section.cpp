#include "fem/reduced/cell_section.hpp"

#include <algorithm>
#include <cmath>

#include "fem/reduced/rod_section.hpp"
#include "fem/reduced/section_geometry.hpp"
#include "fem/core/angles.hpp"

namespace softarm::fem {
using namespace section_geometry;
namespace {
}  // namespace

CellSection tca_cell_section(const TcaDesign& design, double z, int cells, int subrows) {
  const RraDesign& a = design.actuator;
  const double r_o = a.outer_radius(z), r_f = chamber_force_radius(a, z);
  const double r_c = in_end_cap(a, z) ? 0.0 : a.chamber_radius(z);
  const double rho = r_o + design.sheath_thickness_mm, r_hole = design.centre_hole_diameter_mm / 2;
  // tca_axes gives the scene's (x, y); the section's ξ = (x, −y) (header).
  std::array<Point, 3> axes = tca_axes(design, z, 0.0);
  for (auto& c : axes) c[1] = -c[1];
  CellSection s;
  for (const auto& c : axes) {
    s.chamber_xi.emplace_back(c[0], c[1]);
    s.chamber_force_area.push_back(kPi * r_f * r_f);
  }
  const std::array<Point, 3> envelope = counter_clockwise(axes);
  // A square grid centred on the 3CA axis, so that the cells are as symmetric as the section
  // (about ξ2 = 0 with chamber 1 on +ξ1): a grid that is not would bend the rod out of plane.
  double hi = 0;
  for (const auto& c : axes) hi = std::max({hi, std::abs(c[0]) + rho, std::abs(c[1]) + rho});
  const double lo = -hi;
  const double h = (hi - lo) / cells, dr = h / subrows;
  const double gauss[3][2] = {{-0.7745966692414834, 5.0 / 18}, {0.0, 8.0 / 18}, {0.7745966692414834, 5.0 / 18}};
  std::vector<FibreCell> row(cells);
  for (int j = 0; j < cells; ++j) {
    const double y0 = lo + j * h;
    for (int i = 0; i < cells; ++i) row[i] = {{lo + (i + 0.5) * h, y0 + 0.5 * h}, 0.0, 0.0};
    for (int r = 0; r < subrows; ++r)
      for (const auto& g : gauss) {
        const double y = y0 + (r + 0.5 + 0.5 * g[0]) * dr, w = g[1] * dr;
        const Interval env = envelope_chord(envelope, rho, y), hole = disc_chord(0, 0, r_hole, y);
        for (int i = 0; i < cells; ++i) {
          const double x0 = lo + i * h, x1 = x0 + h;
          double outer = hole.overlap(x0, x1), tube = 0;
          for (const auto& c : axes) {
            const double disc = disc_chord(c[0], c[1], r_o, y).overlap(x0, x1);
            tube += disc - disc_chord(c[0], c[1], r_c, y).overlap(x0, x1);
            outer += disc;
          }
          row[i].tube_area += w * tube;
          row[i].sheath_area += w * std::max(0.0, env.overlap(x0, x1) - outer);
        }
      }
    for (const FibreCell& c : row) {
      if (c.tube_area + c.sheath_area <= 1e-12 * h * h) continue;
      s.cells.push_back(c);
      s.tube_area += c.tube_area;
      s.sheath_area += c.sheath_area;
    }
  }
  return s;
}

}  // namespace softarm::fem

#include "fem/reduced/rod_section.hpp"

#include <algorithm>
#include <cmath>

#include "fem/reduced/confined_wall.hpp"
#include "fem/reduced/section_geometry.hpp"
#include "fem/core/angles.hpp"

namespace softarm::fem {
using namespace section_geometry;
namespace {
}  // namespace

bool in_end_cap(const RraDesign& d, double z) {
  return z < d.end_cap_thickness_mm || z > d.length_mm - d.end_cap_thickness_mm;
}

double chamber_force_radius(const RraDesign& d, double z) {
  const double zc = std::clamp(z, d.end_cap_thickness_mm, d.length_mm - d.end_cap_thickness_mm);
  return d.chamber_radius(zc);
}

double confinement_radius(const RraDesign& d, double z) {
  if (d.ring_count == 0 || in_end_cap(d, z)) return 0.0;
  const double depth = d.square_rings() ? 0.5 * d.ring_square_side_mm() : d.ring_section_radius();
  return d.outer_radius(z) - depth;
}

RodSection tca_section(const TcaDesign& design, double z, double bend_direction_rad, int strips, int subrows,
                       const HyperelasticLaw* confined_tube_law) {
  const RraDesign& a = design.actuator;
  const double r_o = a.outer_radius(z);
  const double r_c = in_end_cap(a, z) ? 0.0 : a.chamber_radius(z);
  // A validated design's grooves stop short of the chamber (rra_design.cpp), so R_i > r_c; an
  // unvalidated one whose groove reaches it is left free rather than given a negative area.
  const double held_radius = confined_tube_law ? confinement_radius(a, z) : 0.0;
  const double r_i = held_radius > r_c ? held_radius : 0.0;
  const double r_f = r_i > 0 ? r_i : chamber_force_radius(a, z);
  const double rho = r_o + design.sheath_thickness_mm;
  const double r_hole = design.centre_hole_diameter_mm / 2;
  // Section frame: y along the bending direction, x across it.
  RodSection s;
  const std::array<Point, 3> chambers = tca_axes(design, z, bend_direction_rad - kPi / 2);
  for (const auto& c : chambers) {
    s.chamber_y.push_back(c[1]);
    s.chamber_force_area.push_back(kPi * r_f * r_f);
  }
  const std::array<Point, 3> axes = counter_clockwise(chambers);
  double y_lo = 1e300, y_hi = -1e300;
  for (const auto& c : axes) y_lo = std::min(y_lo, c[1] - rho), y_hi = std::max(y_hi, c[1] + rho);
  // The envelope's chord is C1 inside (arcs meet the straight sides tangentially): 3-point
  // Gauss–Legendre per sub-row; the discs (tubes, chambers, centre hole) are exact.
  const double dy = (y_hi - y_lo) / strips, dr = dy / subrows;
  const double gauss[3][2] = {{-0.7745966692414834, 5.0 / 18}, {0.0, 8.0 / 18}, {0.7745966692414834, 5.0 / 18}};
  for (int j = 0; j < strips; ++j) {
    FibreStrip f;
    const double a = y_lo + j * dy, b = a + dy;
    f.y = 0.5 * (a + b);
    double envelope = 0, outer = disc_strip_area(0, r_hole, a, b);
    for (int r = 0; r < subrows; ++r)
      for (const auto& g : gauss)
        envelope += g[1] * dr * envelope_chord(axes, rho, a + (r + 0.5 + 0.5 * g[0]) * dr).length();
    for (const auto& c : axes) {
      const double disc = disc_strip_area(c[1], r_o, a, b);
      const double held = r_i > 0 ? disc_strip_area(c[1], r_i, a, b) - disc_strip_area(c[1], r_c, a, b) : 0.0;
      f.tube_area += disc - disc_strip_area(c[1], r_c, a, b) - held;
      f.confined_area += held;
      outer += disc;
    }
    f.sheath_area = std::max(0.0, envelope - outer);
    s.tube_area += f.tube_area;
    s.sheath_area += f.sheath_area;
    s.confined_area += f.confined_area;
    s.strips.push_back(f);
  }
  if (r_i > 0) s.confined_law = std::make_shared<const FibreLaw>(confined_wall_law(*confined_tube_law, r_c, r_i));
  return s;
}

RodSection rra_section(const RraDesign& design, double z, int strips) {
  const double r_o = design.outer_radius(z), r_f = chamber_force_radius(design, z);
  const double r_c = in_end_cap(design, z) ? 0.0 : design.chamber_radius(z);
  RodSection s;
  s.chamber_y = {0.0};
  s.chamber_force_area = {kPi * r_f * r_f};
  const double dy = 2 * r_o / strips;
  for (int j = 0; j < strips; ++j) {
    FibreStrip f;
    const double a = -r_o + j * dy, b = a + dy;
    f.y = 0.5 * (a + b);
    f.tube_area = disc_strip_area(0, r_o, a, b) - disc_strip_area(0, r_c, a, b);
    s.tube_area += f.tube_area;
    s.strips.push_back(f);
  }
  return s;
}

}  // namespace softarm::fem

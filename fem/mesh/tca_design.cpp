#include "fem/mesh/tca_design.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include "fem/core/angles.hpp"

namespace softarm::fem {
namespace {
std::string show(double x) {
  std::ostringstream s;
  s.precision(6);
  s << x;
  return s.str();
}

void validate_design(const TcaDesign& d, const std::string& field_prefix) {
  validate(d.actuator);
  const double a = d.actuator.ring_count > 0 ? square_ring_side_mm(d.actuator) : 0.0;
  if (!(d.actuator_spacing_mm > a))
    throw InputError(field_prefix + "actuator_spacing_mm",
                     "spacing " + show(d.actuator_spacing_mm) + " mm: neighbouring RRAs' rings (square side a = " +
                         show(a) + " mm, protruding a/2 from each tube) would touch; it must be > " + show(a) + " mm");
  if (!(d.sheath_thickness_mm > a / 2))
    throw InputError(field_prefix + "sheath_thickness_mm",
                     "sheath thickness " + show(d.sheath_thickness_mm) +
                         " mm does not cover the rings: it must be > a/2 = " + show(a / 2) + " mm");
  // The hole must leave core between it and the ring bands at both ends.
  const double r_hole = d.centre_hole_diameter_mm / 2;
  double clearance = 1e300;
  for (double z : {0.0, d.actuator.length_mm})
    clearance = std::min(clearance, d.axis_distance(z) - d.actuator.outer_radius(z) - a / 2);
  if (d.centre_hole_diameter_mm < 0 || !(r_hole < 0.8 * clearance))
    throw InputError(field_prefix + "centre_hole_diameter_mm",
                     "centre hole diameter " + show(d.centre_hole_diameter_mm) +
                         " mm: it must be >= 0 and leave core around the rings, i.e. < " + show(1.6 * clearance) + " mm");
}
}  // namespace

double square_ring_side_mm(const RraDesign& design) { return design.ring_diameter_mm * std::sqrt(kPi) / 2; }

TcaParameters read_tca_parameters(JsonReader& g, bool radii_and_end) {
  TcaParameters p;
  p.actuator_spacing_mm = g.number("actuator_spacing_mm", 3, Range::positive(),
                                   "3CA: gap between the outer surfaces of neighbouring RRAs (mm)");
  p.sheath_thickness_mm = g.number("sheath_thickness_mm", 2, Range::positive(),
                                   "3CA: offset of the outer surface from the RRAs' convex envelope (mm)");
  p.centre_hole_diameter_mm = g.number("centre_hole_diameter_mm", 0, Range::non_negative(),
                                       "3CA: diameter of the bore along the 3CA axis (mm; 0: none)");
  p.actuator = read_rra_parameters(g, radii_and_end);
  return p;
}

TcaDesign build_tca_design(const TcaParameters& p) {
  TcaDesign d;
  d.actuator_spacing_mm = p.actuator_spacing_mm;
  d.sheath_thickness_mm = p.sheath_thickness_mm;
  d.centre_hole_diameter_mm = p.centre_hole_diameter_mm;
  d.actuator = build_rra_design(p.actuator);
  validate_design(d, p.actuator.path.empty() ? "" : p.actuator.path + ".");
  return d;
}

TcaDesign read_tca_design(JsonReader& g) {
  const TcaParameters p = read_tca_parameters(g);
  g.finish();
  return build_tca_design(p);
}

void validate(const TcaDesign& design) { validate_design(design, "geometry."); }

nlohmann::json to_json(const TcaDesign& d) {
  return {{"actuator", to_json(d.actuator)},
          {"actuator_spacing_mm", d.actuator_spacing_mm},
          {"sheath_thickness_mm", d.sheath_thickness_mm},
          {"centre_hole_diameter_mm", d.centre_hole_diameter_mm},
          {"ring_square_side_mm", d.actuator.ring_count > 0 ? square_ring_side_mm(d.actuator) : 0.0}};
}

}  // namespace softarm::fem

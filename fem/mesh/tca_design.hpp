#pragma once
// Design parameters of the three-chambered actuator (3CA), spec §1 "our
// definition" column: three identical tapered RRAs whose axes stand on an
// equilateral triangle, bonded by an elastomeric core and enclosed by a sheath
// (core and sheath are one material). Lengths in mm; z = 0 is the bottom
// (distal, free) face, z = l the top (fixed) face.
//
//   Actuator spacing s: the gap between the outer surfaces of neighbouring RRAs,
//     the same at every height, so the axes stand at a_c(z) = (2 r_o(z) + s)/√3
//     from the 3CA axis and lean inwards with the taper.
//   Sheath thickness t_s: offset of the outer surface from the convex envelope of
//     the three RRAs (arcs of radius r_o + t_s joined by straight segments).
//   Centre hole: a bore of the given diameter along the 3CA axis (0: none).
//   Rings in 3D: the 3D meshes extrude a cross-section in layers, so each ring is
//     a square of the same area as the thesis' circular section (side
//     a = d_r·√π/2), centred on the tube's outer surface and embedded half in the
//     tube, half in the core (square_ring_side_mm).
#include <nlohmann/json.hpp>

#include "fem/core/json_reader.hpp"
#include "fem/mesh/rra_design.hpp"

namespace softarm::fem {

struct TcaDesign {
  RraDesign actuator;                  // each of the three RRAs (spec Table 7 values by default)
  double actuator_spacing_mm = 3;      // s; the thesis' "3·s mm" with s = 1 mm (Table 11, s arbitrary)
  double sheath_thickness_mm = 2;      // thesis §6.1
  double centre_hole_diameter_mm = 0;  // not given in the thesis

  /// Distance of each RRA axis from the 3CA axis at height z.
  double axis_distance(double z) const { return (2 * actuator.outer_radius(z) + actuator_spacing_mm) / 1.7320508075688772; }
};

/// Side of the square ring section with the area of the circular one, a = d_r·√π/2.
double square_ring_side_mm(const RraDesign& design);

/// The 3CA's "geometry" keys as given (rra_design.hpp's RraParameters for its RRAs).
struct TcaParameters {
  RraParameters actuator;
  double actuator_spacing_mm = 0, sheath_thickness_mm = 0, centre_hole_diameter_mm = 0;
};
/// Parses the 3CA keys without finishing the reader (`radii_and_end`: read_rra_parameters).
TcaParameters read_tca_parameters(JsonReader& geometry, bool radii_and_end = true);
/// The design the parameters describe, validated (errors name the keys as given).
TcaDesign build_tca_design(const TcaParameters& parameters);

/// Reads the "geometry" object of a 3CA scene: actuator_spacing_mm,
/// sheath_thickness_mm, centre_hole_diameter_mm and every RRA key
/// (read_rra_design). Validated; errors name the field.
TcaDesign read_tca_design(JsonReader& geometry);

/// Throws InputError naming the field when the 3CA cannot be built: rings of
/// neighbouring RRAs touching (s must exceed the ring's protrusion a), rings
/// poking through the sheath (t_s > a/2), a centre hole reaching the rings.
void validate(const TcaDesign& design);

/// {"actuator": to_json(RRA), "actuator_spacing_mm", "sheath_thickness_mm", "centre_hole_diameter_mm"}.
nlohmann::json to_json(const TcaDesign& design);

}  // namespace softarm::fem

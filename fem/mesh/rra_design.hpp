#pragma once
// Design parameters of the ring-reinforced actuator (RRA), spec §1 "our
// definition" column. One place owns the geometry: the mesher, the reports and
// the studies all read it from here. Lengths in mm.
//
//   z = 0 is the bottom (distal) end, z = l the top (proximal) end.
//   Outer radius r_o(z): linear taper from r_b (z = 0) to r_t (z = l).
//   Chamber radius r_c(z) = r_o(z) − t_w, for t_c ≤ z ≤ l − t_c; the end caps
//   (axial thickness t_c) are solid from the axis to the outer surface.
//   n_r rings of circular section (diameter d_r) centred on the outer surface at
//   z_k = (k − ½)·l/n_r, k = 1..n_r, seated half-depth in semicircular grooves.
//   Or (ring_section = square) rings of the same section area: squares of side
//   a = d_r·√π/2 occupying r_o(z) − a/2 ≤ r ≤ r_o(z) + a/2, |z − z_k| ≤ a/2 (the
//   faces follow the taper), half sunk into grooves of depth a/2.
#include <algorithm>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "fem/core/json_reader.hpp"

namespace softarm::fem {

/// Defaults: the thesis RRA (Table 7).
struct RraDesign {
  double length_mm = 160, bottom_radius_mm = 9, top_radius_mm = 12;  // outer radii, linear taper
  double wall_thickness_mm = 0.466 * 9, end_cap_thickness_mm = 0.25 * 9;
  int ring_count = 30;                          // n_r (0 = plain tube)
  double ring_diameter_mm = 0.4 * 160.0 / 30;   // d_r, circular ring section
  double ring_reference_diameter_mm = 2;        // d_ref of eq 8; only used to report r̂
  enum class FixedEnd { top, bottom } fixed_end = FixedEnd::top;
  /// Ring cross-section: circle of diameter d_r, or the square of equal area.
  enum class RingSection { circle, square } ring_section = RingSection::circle;

  /// Outer radius of the plain tapered tube (grooves ignored).
  double outer_radius(double z) const { return bottom_radius_mm + (top_radius_mm - bottom_radius_mm) * z / length_mm; }
  /// Radius of the chamber wall (meaningful for t_c ≤ z ≤ l − t_c).
  double chamber_radius(double z) const { return outer_radius(z) - wall_thickness_mm; }
  /// Axial distance between neighbouring ring centres, l / n_r (0 without rings).
  double pitch() const { return ring_count > 0 ? length_mm / ring_count : 0.0; }
  /// Axial position of ring k = 1..n_r.
  double ring_centre_z(int k) const { return (k - 0.5) * pitch(); }
  /// Radius ρ = d_r / 2 of the ring section (and of its groove).
  double ring_section_radius() const { return 0.5 * ring_diameter_mm; }
  /// Side a = d_r·√π/2 of the square ring section of the same area as the circle.
  double ring_square_side_mm() const { return ring_diameter_mm * 0.88622692545275801365; }  // √π/2
  bool square_rings() const { return ring_section == RingSection::square && ring_count > 0; }
  /// Smaller of the two end radii: the wall must be thinner than this.
  double smallest_outer_radius() const { return std::min(bottom_radius_mm, top_radius_mm); }
};

/// A size as the user gave it: in mm, or normalised (× r_b for walls and caps, × the ring pitch for
/// a ring's diameter; a ring count normalised as r̂ with n_r = round(l·r̂ / d_ref), eq 8).
struct GivenSize {
  double value = 0;
  bool normalised = false;
};

/// The RRA's "geometry" keys as given, before the normalised sizes are resolved: the typed form in
/// which a design travels from a config or an optimiser's variables to the mesher. Parsed (keys,
/// types, ranges) by read_rra_parameters; resolved and validated once by build_rra_design. `path` is
/// the object the keys came from, so that errors name the key as the user wrote it.
struct RraParameters {
  double length_mm = 0, bottom_radius_mm = 0, top_radius_mm = 0;
  GivenSize wall, end_cap, ring_count;
  std::optional<GivenSize> ring_size;  // absent only without rings
  double ring_reference_diameter_mm = 0;
  RraDesign::FixedEnd fixed_end = RraDesign::FixedEnd::top;
  RraDesign::RingSection ring_section = RraDesign::RingSection::circle;
  std::string path = "geometry";
};

/// Parses the RRA keys of a "geometry" object (read_rra_design lists them) without finishing the
/// reader. `radii_and_end` false leaves out bottom_radius_mm, top_radius_mm and fixed_end (an SPL's
/// segments take their radii from the taper and hang from the top).
RraParameters read_rra_parameters(JsonReader& geometry, bool radii_and_end = true);
/// The design the parameters describe: normalised sizes resolved, validated (errors name the keys
/// as given, under parameters.path).
RraDesign build_rra_design(const RraParameters& parameters);

/// Reads the "geometry" object (and rejects unknown keys in it, so read any
/// extra keys of that object before calling this). Each sized parameter may be
/// given physically or normalised (exactly one of each pair):
///   wall_thickness_mm     | wall_thickness_normalised     (= t_w / r_b)
///   end_cap_thickness_mm  | end_cap_thickness_normalised  (= t_c / r_b)
///   ring_count            | ring_count_normalised         (n_r = round(l·r̂ / ring_reference_diameter_mm), eq 8)
///   ring_diameter_mm      | ring_thickness_normalised     (= d_r / (l / n_r); 1 = neighbouring rings touch)
/// plus length_mm, bottom_radius_mm, top_radius_mm (defaults 160, 9, 12),
/// ring_reference_diameter_mm (default 2), fixed_end ("top" | "bottom",
/// default "top") and ring_section ("circle" | "square", default "circle"; a
/// square has the circle's area, side d_r·√π/2). With n_r = 0 the ring size may be omitted. The result is
/// validated; errors name the key the user actually wrote.
RraDesign read_rra_design(JsonReader& geometry);

/// Throws InputError naming the offending field (as "geometry.<physical key>")
/// when the design cannot be built: non-positive sizes, a wall that leaves no
/// chamber, caps that leave no chamber, rings that touch or overlap (d_r ≥ l/n_r)
/// or grooves as deep as the wall (d_r/2 ≥ t_w·cos θ, measured normal to a taper of
/// angle θ). Square rings instead: rings that touch (a ≥ l/n_r) or grooves as
/// deep as the wall (a/2 ≥ t_w). Any positive taper, including
/// a reverse one (r_t < r_b), is valid.
void validate(const RraDesign& design);

/// Exact volume of the silicone tube (caps included, grooves and chamber
/// removed), mm³: frusta between grooves through both lips of ring k at R_k,
/// a cylinder of radius R_k over each groove, minus the half-disc grooves
/// (Pappus: area πρ²/2 times 2π times the centroid radius R_k − 4ρ/3π), minus
/// the chamber frustum. Square rings: the tapered frustum minus the grooves
/// Σ π a² (R_k − a/4) and the chamber. The mass reports use this, not the mesh.
double tube_volume_mm3(const RraDesign& design);
/// Exact volume of all rings, Σ 2π² R_k ρ² (tori; square rings Σ 2π a² R_k, the
/// same), mm³.
double ring_volume_mm3(const RraDesign& design);

/// {"physical": {...}, "normalised": {...}, "derived": {...}}. "physical" alone is
/// a valid "geometry" input (it round-trips through read_rra_design).
nlohmann::json to_json(const RraDesign& design);

}  // namespace softarm::fem

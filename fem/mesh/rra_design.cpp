#include "fem/mesh/rra_design.hpp"

#include <cmath>
#include <sstream>
#include "fem/core/angles.hpp"

namespace softarm::fem {
namespace {

// The JSON field each parameter came from, so that a validation error names the
// key the user actually wrote (physical or normalised).
struct FieldNames {
  std::string length = "geometry.length_mm";
  std::string bottom_radius = "geometry.bottom_radius_mm";
  std::string top_radius = "geometry.top_radius_mm";
  std::string wall = "geometry.wall_thickness_mm";
  std::string cap = "geometry.end_cap_thickness_mm";
  std::string ring_count = "geometry.ring_count";
  std::string ring_size = "geometry.ring_diameter_mm";
  std::string ring_section = "geometry.ring_section";
};

std::string show(double x) {
  std::ostringstream s;
  s.precision(6);
  s << x;
  return s.str();
}

std::string with_normalised(double mm, double normalised) {
  return show(mm) + " mm (normalised " + show(normalised) + ")";
}

void require_positive(double x, const std::string& field, const std::string& what) {
  if (!(x > 0) || !std::isfinite(x)) throw InputError(field, what + " is " + show(x) + " mm; it must be > 0");
}

void validate_design(const RraDesign& d, const FieldNames& f) {
  require_positive(d.length_mm, f.length, "length");
  require_positive(d.bottom_radius_mm, f.bottom_radius, "bottom radius");
  require_positive(d.top_radius_mm, f.top_radius, "top radius");
  require_positive(d.wall_thickness_mm, f.wall, "wall thickness");
  require_positive(d.end_cap_thickness_mm, f.cap, "end-cap thickness");
  const double r_b = d.bottom_radius_mm;

  // Chamber radius r_c = r_o − t_w (spec §1) must stay positive along the whole taper.
  const double r_min = d.smallest_outer_radius();
  if (d.wall_thickness_mm >= r_min)
    throw InputError(f.wall, "wall thickness " + with_normalised(d.wall_thickness_mm, d.wall_thickness_mm / r_b) +
                                 " leaves no chamber: it must be less than the smaller outer radius " + show(r_min) +
                                 " mm (normalised " + show(r_min / r_b) + ")");
  if (2 * d.end_cap_thickness_mm >= d.length_mm)
    throw InputError(f.cap, "two end caps of " + with_normalised(d.end_cap_thickness_mm, d.end_cap_thickness_mm / r_b) +
                                " leave no chamber in a " + show(d.length_mm) + " mm tube: need t_c < l/2 = " +
                                show(d.length_mm / 2) + " mm");

  if (d.ring_count < 0) throw InputError(f.ring_count, "ring count " + std::to_string(d.ring_count) + " must be >= 0");
  if (d.ring_count == 0) return;
  const double pitch = d.pitch(), d_r = d.ring_diameter_mm;
  if (!(d_r > 0) || !std::isfinite(d_r))
    throw InputError(f.ring_size, "ring diameter is " + show(d_r) + " mm; it must be > 0 when there are rings");
  if (d.ring_section == RraDesign::RingSection::square) {
    // Square section of the circle's area, side a = d_r·√π/2, half sunk in a
    // rectangular groove whose bottom r_o(z) − a/2 runs parallel to the chamber wall.
    const double a = d.ring_square_side_mm();
    if (a >= pitch)
      throw InputError(f.ring_size, "ring diameter " + with_normalised(d_r, d_r / pitch) + " gives a square ring (" +
                                        f.ring_section + " = \"square\") of side a = d_r·√π/2 = " + show(a) +
                                        " mm that does not fit: a must be less than the ring pitch l/n_r = " +
                                        show(pitch) + " mm (at a = l/n_r neighbouring rings touch)");
    if (a / 2 >= d.wall_thickness_mm)
      throw InputError(f.ring_size, "ring diameter " + with_normalised(d_r, d_r / pitch) + " gives a square ring (" +
                                        f.ring_section + " = \"square\") whose groove depth a/2 = " + show(a / 2) +
                                        " mm must be less than the wall thickness " + show(d.wall_thickness_mm) +
                                        " mm, or the groove cuts into the chamber");
    return;
  }
  // d_r = pitch means touching rings: no tube surface would be left between the
  // grooves (a cusp of zero thickness), which no mesh can represent.
  if (d_r >= pitch)
    throw InputError(f.ring_size, "ring diameter " + with_normalised(d_r, d_r / pitch) +
                                      " does not fit: it must be less than the ring pitch l/n_r = " + show(pitch) +
                                      " mm (normalised < 1; at 1 neighbouring rings touch)");
  // The groove is centred on the tapered surface; the chamber wall runs parallel
  // to it at the perpendicular distance t_w·cos θ (tan θ = taper slope).
  const double slope = (d.top_radius_mm - d.bottom_radius_mm) / d.length_mm;
  const double wall_normal = d.wall_thickness_mm / std::sqrt(1 + slope * slope);
  if (d.ring_section_radius() >= wall_normal)
    throw InputError(f.ring_size, "ring diameter " + with_normalised(d_r, d_r / pitch) + ": its groove depth d_r/2 = " +
                                      show(d.ring_section_radius()) + " mm must be less than the wall thickness " +
                                      show(wall_normal) + " mm (normal to the taper), or the groove cuts into the chamber");
}

/// Reads one parameter given either physically (mm) or normalised; exactly one of the two keys must
/// be present.
GivenSize physical_or_normalised(JsonReader& g, const std::string& physical_key, const std::string& normalised_key,
                                 const std::string& what, const std::string& normalised_as) {
  const auto physical = g.optional_number(physical_key, Range::positive(), what + " (mm)");
  const auto normalised = g.optional_number(normalised_key, Range::positive(), what + ", normalised " + normalised_as);
  g.exactly_one_of({physical_key, normalised_key});
  return physical ? GivenSize{*physical, false} : GivenSize{*normalised, true};
}

// A resource bound, not a physical one: every ring's groove is resolved by the mesh, so the element
// count grows with the rings; 500 rings of the thesis' 160 mm RRA are 0.32 mm apart, far past any
// printable ring, and mesh in seconds. (10⁶ rings were accepted and grew to gigabytes without output.)
constexpr int kMaxRingCount = 500;

std::string key(const std::string& path, const std::string& name) { return path.empty() ? name : path + "." + name; }

/// n_r from the count as given (eq 8 when normalised), within the resource bound.
int ring_count_of(const RraParameters& p) {
  if (!p.ring_count.normalised) return static_cast<int>(p.ring_count.value);
  const double n = std::round(p.length_mm * p.ring_count.value / p.ring_reference_diameter_mm);
  if (n > kMaxRingCount)
    throw InputError(key(p.path, "ring_count_normalised"),
                     "value " + show(p.ring_count.value) + " gives " + show(n) + " rings; valid: at most " +
                         std::to_string(kMaxRingCount) + " rings (normalised <= " +
                         show(kMaxRingCount * p.ring_reference_diameter_mm / p.length_mm) +
                         " here: every groove is meshed)");
  return static_cast<int>(n);
}

}  // namespace

RraParameters read_rra_parameters(JsonReader& g, bool radii_and_end) {
  RraParameters p;
  p.path = g.path();
  p.length_mm = g.number("length_mm", 160, Range::positive(), "axial length of the tube, caps included (mm)");
  if (radii_and_end) {
    p.bottom_radius_mm =
        g.number("bottom_radius_mm", 9, Range::positive(), "outer radius at the bottom (distal) end, z = 0 (mm)");
    p.top_radius_mm = g.number("top_radius_mm", 12, Range::positive(), "outer radius at the top (proximal) end, z = l (mm)");
  }
  p.wall = physical_or_normalised(g, "wall_thickness_mm", "wall_thickness_normalised", "radial wall thickness t_w",
                                  "t_w / r_b");
  p.end_cap = physical_or_normalised(g, "end_cap_thickness_mm", "end_cap_thickness_normalised",
                                     "axial end-cap thickness t_c", "t_c / r_b");
  p.ring_reference_diameter_mm =
      g.number("ring_reference_diameter_mm", 2, Range::positive(), "reference ring diameter d_ref of eq 8 (mm)");
  const auto count = g.optional_integer("ring_count", Range::closed(0, kMaxRingCount),
                                        "number of rings n_r (0 = plain tube; at most 500: every groove is meshed)");
  const auto count_normalised = g.optional_number("ring_count_normalised", Range::non_negative(),
                                                  "ring count, normalised: n_r = round(l·r̂ / ring_reference_diameter_mm), eq 8");
  g.exactly_one_of({"ring_count", "ring_count_normalised"});
  p.ring_count = count ? GivenSize{static_cast<double>(*count), false} : GivenSize{*count_normalised, true};
  const auto diameter = g.optional_number("ring_diameter_mm", Range::positive(), "ring section diameter d_r (mm)");
  const auto size_normalised = g.optional_number("ring_thickness_normalised", Range::positive(),
                                                 "ring section diameter, normalised d_r / (l / n_r) (1 = rings touch)");
  if (ring_count_of(p) > 0 || diameter || size_normalised) {  // a plain tube needs no ring size
    g.exactly_one_of({"ring_diameter_mm", "ring_thickness_normalised"});
    p.ring_size = diameter ? GivenSize{*diameter, false} : GivenSize{*size_normalised, true};
  }
  if (radii_and_end)
    p.fixed_end = g.choice("fixed_end", "top", {"top", "bottom"}, "which end is clamped") == "top"
                      ? RraDesign::FixedEnd::top
                      : RraDesign::FixedEnd::bottom;
  p.ring_section = g.choice("ring_section", "circle", {"circle", "square"},
                            "ring cross-section: \"circle\" (diameter d_r, semicircular groove) or \"square\" "
                            "(the same area, side d_r·√π/2, centred on the outer surface, half sunk in a rectangular groove)") ==
                           "square"
                       ? RraDesign::RingSection::square
                       : RraDesign::RingSection::circle;
  return p;
}

RraDesign build_rra_design(const RraParameters& p) {
  RraDesign d;
  FieldNames f;
  f.length = key(p.path, "length_mm");
  f.bottom_radius = key(p.path, "bottom_radius_mm");
  f.top_radius = key(p.path, "top_radius_mm");
  f.wall = key(p.path, p.wall.normalised ? "wall_thickness_normalised" : "wall_thickness_mm");
  f.cap = key(p.path, p.end_cap.normalised ? "end_cap_thickness_normalised" : "end_cap_thickness_mm");
  f.ring_count = key(p.path, p.ring_count.normalised ? "ring_count_normalised" : "ring_count");
  f.ring_size = key(p.path, p.ring_size && p.ring_size->normalised ? "ring_thickness_normalised" : "ring_diameter_mm");
  f.ring_section = key(p.path, "ring_section");
  d.length_mm = p.length_mm;
  d.bottom_radius_mm = p.bottom_radius_mm;
  d.top_radius_mm = p.top_radius_mm;
  const double r_b = d.bottom_radius_mm;
  d.wall_thickness_mm = p.wall.normalised ? p.wall.value * r_b : p.wall.value;
  d.end_cap_thickness_mm = p.end_cap.normalised ? p.end_cap.value * r_b : p.end_cap.value;
  d.ring_reference_diameter_mm = p.ring_reference_diameter_mm;
  d.ring_count = ring_count_of(p);
  if (!p.ring_size) d.ring_diameter_mm = 0.0;
  else if (!p.ring_size->normalised) d.ring_diameter_mm = p.ring_size->value;
  else d.ring_diameter_mm = d.ring_count > 0 ? p.ring_size->value * d.length_mm / d.ring_count : 0.0;
  d.fixed_end = p.fixed_end;
  d.ring_section = p.ring_section;
  validate_design(d, f);
  return d;
}

RraDesign read_rra_design(JsonReader& g) {
  const RraParameters p = read_rra_parameters(g);
  g.finish();
  return build_rra_design(p);
}

void validate(const RraDesign& design) { validate_design(design, FieldNames{}); }

nlohmann::json to_json(const RraDesign& d) {
  const double r_b = d.bottom_radius_mm, l = d.length_mm, t_c = d.end_cap_thickness_mm;
  nlohmann::json physical = {
      {"length_mm", l},
      {"bottom_radius_mm", r_b},
      {"top_radius_mm", d.top_radius_mm},
      {"wall_thickness_mm", d.wall_thickness_mm},
      {"end_cap_thickness_mm", t_c},
      {"ring_count", d.ring_count},
      {"ring_reference_diameter_mm", d.ring_reference_diameter_mm},
      {"fixed_end", d.fixed_end == RraDesign::FixedEnd::top ? "top" : "bottom"},
      {"ring_section", d.ring_section == RraDesign::RingSection::square ? "square" : "circle"},
  };
  if (d.ring_count > 0) physical["ring_diameter_mm"] = d.ring_diameter_mm;
  nlohmann::json normalised = {
      {"wall_thickness_normalised", d.wall_thickness_mm / r_b},
      {"end_cap_thickness_normalised", t_c / r_b},
      {"ring_count_normalised", d.ring_count * d.ring_reference_diameter_mm / l},
      {"ring_thickness_normalised", d.ring_count > 0 ? d.ring_diameter_mm / d.pitch() : 0.0},
  };
  nlohmann::json derived = {
      {"pitch_mm", d.pitch()},
      {"ring_section_radius_mm", d.ring_section_radius()},
      {"chamber_length_mm", l - 2 * t_c},
      {"chamber_radius_at_bottom_cap_mm", d.chamber_radius(t_c)},
      {"chamber_radius_at_top_cap_mm", d.chamber_radius(l - t_c)},
  };
  if (d.ring_section == RraDesign::RingSection::square) derived["ring_square_side_mm"] = d.ring_square_side_mm();
  return {{"physical", physical}, {"normalised", normalised}, {"derived", derived}};
}

namespace {
double frustum(double height, double r1, double r2) { return kPi * height * (r1 * r1 + r1 * r2 + r2 * r2) / 3; }
}  // namespace

double tube_volume_mm3(const RraDesign& d) {
  const double t_c = d.end_cap_thickness_mm;
  const double chamber = frustum(d.length_mm - 2 * t_c, d.chamber_radius(t_c), d.chamber_radius(d.length_mm - t_c));
  if (d.square_rings()) {
    // The outer surface is the straight taper; groove k is the band
    // r_o(z) − a/2 ≤ r ≤ r_o(z), |z − z_k| ≤ a/2: ∫ π (a r_o − a²/4) dz = π a² (R_k − a/4).
    const double a = d.ring_square_side_mm();
    double v = frustum(d.length_mm, d.bottom_radius_mm, d.top_radius_mm) - chamber;
    for (int k = 1; k <= d.ring_count; ++k) v -= kPi * a * a * (d.outer_radius(d.ring_centre_z(k)) - a / 4);
    return v;
  }
  const double rho = d.ring_section_radius();
  double v = 0, z = 0, r = d.bottom_radius_mm;
  for (int k = 1; k <= d.ring_count; ++k) {
    const double z_k = d.ring_centre_z(k), R = d.outer_radius(z_k);
    v += frustum(z_k - rho - z, r, R) + kPi * R * R * 2 * rho - 2 * kPi * (R - 4 * rho / (3 * kPi)) * (kPi * rho * rho / 2);
    z = z_k + rho;
    r = R;
  }
  v += frustum(d.length_mm - z, r, d.top_radius_mm);
  return v - chamber;
}

double ring_volume_mm3(const RraDesign& d) {
  const double rho = d.ring_section_radius();
  double v = 0.0;
  if (d.square_rings()) {  // ∫ π ((r_o + a/2)² − (r_o − a/2)²) dz over |z − z_k| ≤ a/2 = 2π a² R_k
    const double a = d.ring_square_side_mm();
    for (int k = 1; k <= d.ring_count; ++k) v += 2 * kPi * a * a * d.outer_radius(d.ring_centre_z(k));
    return v;
  }
  for (int k = 1; k <= d.ring_count; ++k) v += 2 * kPi * kPi * d.outer_radius(d.ring_centre_z(k)) * rho * rho;
  return v;
}

}  // namespace softarm::fem

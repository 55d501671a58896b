#pragma once
// Design of the Soft Poly-Limb (SPL), spec §1: three 3CA segments in series,
// segment 1 proximal (at the shoulder) … 3 distal, joined by rigid ABS
// connectors. Radii from the taper ratio (thesis eqs 5–7), with (r_b)_3 the
// distal bottom radius:
//     (r_t)_1 = (r_b)_3 / t_r,
//     (r_t)_n = (r_b)_3 + (4 − n)/3 · ((r_t)_1 − (r_b)_3),   (r_b)_n = (r_t)_(n+1).
// Every segment's RRAs take the normalised sizes of the thesis RRA (Table 7)
// relative to their own bottom radius (wall, cap), the same ring count and ring
// thickness (eq 8 depends on l only). Connectors (our definition; the thesis
// gives none): solid ABS blocks with the cross-section of the joint they fill, one
// at the shoulder and one between each pair of segments, each of thickness
// (600 − 3·160)/3 = 40 mm by default so that the arm is 0.60 m long (Table 1);
// their mass may be set, which sets their density. Lengths in mm; z = 0 is the
// distal tip, z = L the shoulder (fixed).
#include <array>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "fem/core/json_reader.hpp"
#include "fem/mesh/tca_design.hpp"

namespace softarm::fem {

struct SplDesign {
  std::array<TcaDesign, 3> segments;        // segment 1 (proximal) … 3 (distal)
  double taper_ratio = 0.5;                 // t_r = (r_b)_3 / (r_t)_1
  double distal_bottom_radius_mm = 9;       // (r_b)_3
  double connector_thickness_mm = 40;
  std::optional<double> connector_mass_g;   // each connector; default from the ABS density

  /// Axial extent [z0, z1] of segment n = 1..3 and of connector c = 0 (shoulder), 1 (1–2), 2 (2–3).
  std::array<double, 2> segment_extent(int n) const;
  std::array<double, 2> connector_extent(int c) const;
  double total_length_mm() const;
};

/// Top and bottom outer radius of segment n = 1..3 from eqs 5–7.
std::array<double, 2> spl_segment_radii(double taper_ratio, double distal_bottom_radius_mm, int n);

/// The SPL's "geometry" keys as given: the arm's own and the 3CA keys every segment shares (their
/// RRAs' radii come from the taper, eqs 5–7; normalised sizes are relative to each segment's bottom
/// radius). The typed form in which a design travels: a search sets its variables here (set) and
/// build_spl_design resolves and validates it once per candidate.
struct SplParameters {
  double taper_ratio = 0, distal_bottom_radius_mm = 0, connector_thickness_mm = 0;
  std::optional<double> connector_mass_g;
  TcaParameters segment;

  /// Sets a geometry key to `value`, in that key's unit, replacing its twin in the other unit:
  /// taper_ratio, actuator_spacing_mm, wall_thickness_mm | _normalised, end_cap_thickness_mm |
  /// _normalised, ring_count (rounded) | ring_count_normalised, ring_diameter_mm |
  /// ring_thickness_normalised, length_mm. Throws std::invalid_argument for another key.
  void set(const std::string& key, double value);
};

/// Parses the SPL keys (read_spl_design lists them) without finishing the reader.
SplParameters read_spl_parameters(JsonReader& geometry);
/// The arm the parameters describe, every segment validated (errors name the keys as given).
SplDesign build_spl_design(const SplParameters& parameters);

/// Reads the "geometry" object of an SPL scene: taper_ratio, distal_bottom_radius_mm,
/// connector_thickness_mm, connector_mass_g (optional), the 3CA keys actuator_spacing_mm,
/// sheath_thickness_mm, centre_hole_diameter_mm, and the RRA keys except the radii
/// (normalised sizes are relative to each segment's bottom radius). Validated; errors
/// name the field.
SplDesign read_spl_design(JsonReader& geometry);
nlohmann::json to_json(const SplDesign& design);

}  // namespace softarm::fem

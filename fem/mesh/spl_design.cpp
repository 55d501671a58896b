#include "fem/mesh/spl_design.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace softarm::fem {

std::array<double, 2> spl_segment_radii(double taper_ratio, double distal_bottom_radius_mm, int n) {
  const double rb3 = distal_bottom_radius_mm, rt1 = rb3 / taper_ratio;
  const auto top = [&](int k) { return rb3 + (4.0 - k) / 3.0 * (rt1 - rb3); };  // eq 7
  return {top(n), n == 3 ? rb3 : top(n + 1)};                                    // (r_b)_n = (r_t)_(n+1)
}

std::array<double, 2> SplDesign::segment_extent(int n) const {
  // From the tip: segment 3, connector 2–3, segment 2, connector 1–2, segment 1, shoulder connector.
  double z = 0;
  for (int k = 3; k > n; --k) z += segments[k - 1].actuator.length_mm + connector_thickness_mm;
  return {z, z + segments[n - 1].actuator.length_mm};
}

std::array<double, 2> SplDesign::connector_extent(int c) const {
  const double z0 = segment_extent(c == 0 ? 1 : c + 1)[1];  // connector c sits on segment c + 1 (c = 0: on segment 1)
  return {z0, z0 + connector_thickness_mm};
}

double SplDesign::total_length_mm() const { return connector_extent(0)[1]; }

SplParameters read_spl_parameters(JsonReader& g) {
  SplParameters p;
  p.taper_ratio = g.number("taper_ratio", 0.5, Range{0, 1, true, false},  // 1: no taper, every radius (r_b)_3
                           "t_r = (r_b)_3 / (r_t)_1, bottom radius of segment 3 over top radius of segment 1 (eq 6)");
  p.distal_bottom_radius_mm = g.number("distal_bottom_radius_mm", 9, Range::positive(),
                                       "(r_b)_3, bottom radius of the distal segment's RRAs (mm)");
  p.connector_thickness_mm = g.number("connector_thickness_mm", 40, Range::positive(),
                                      "axial thickness of each of the three ABS connectors (mm)");
  p.connector_mass_g = g.optional_number("connector_mass_g", Range::positive(),
                                         "mass of each connector (g); absent: from the ABS density");
  // The 3CA and RRA keys, read once for every segment; each segment's radii come from the taper.
  p.segment = read_tca_parameters(g, false);
  return p;
}

SplDesign build_spl_design(const SplParameters& p) {
  SplDesign d;
  d.taper_ratio = p.taper_ratio;
  d.distal_bottom_radius_mm = p.distal_bottom_radius_mm;
  d.connector_thickness_mm = p.connector_thickness_mm;
  d.connector_mass_g = p.connector_mass_g;
  for (int n = 1; n <= 3; ++n) {
    const auto radii = spl_segment_radii(d.taper_ratio, d.distal_bottom_radius_mm, n);
    TcaParameters segment = p.segment;
    segment.actuator.top_radius_mm = radii[0];
    segment.actuator.bottom_radius_mm = radii[1];
    d.segments[n - 1] = build_tca_design(segment);
  }
  return d;
}

SplDesign read_spl_design(JsonReader& g) { return build_spl_design(read_spl_parameters(g)); }

void SplParameters::set(const std::string& key, double value) {
  RraParameters& a = segment.actuator;
  if (key == "taper_ratio") taper_ratio = value;
  else if (key == "actuator_spacing_mm") segment.actuator_spacing_mm = value;
  else if (key == "length_mm") a.length_mm = value;
  else if (key == "wall_thickness_mm" || key == "wall_thickness_normalised")
    a.wall = {value, key == "wall_thickness_normalised"};
  else if (key == "end_cap_thickness_mm" || key == "end_cap_thickness_normalised")
    a.end_cap = {value, key == "end_cap_thickness_normalised"};
  else if (key == "ring_count") a.ring_count = {std::round(value), false};
  else if (key == "ring_count_normalised") a.ring_count = {value, true};
  else if (key == "ring_diameter_mm" || key == "ring_thickness_normalised")
    a.ring_size = GivenSize{value, key == "ring_thickness_normalised"};
  else throw std::invalid_argument("SplParameters::set: no geometry key '" + key + "'");
}

nlohmann::json to_json(const SplDesign& d) {
  nlohmann::json segments = nlohmann::json::array();
  for (const auto& s : d.segments) segments.push_back(to_json(s));
  nlohmann::json out = {{"taper_ratio", d.taper_ratio},
                        {"distal_bottom_radius_mm", d.distal_bottom_radius_mm},
                        {"connector_thickness_mm", d.connector_thickness_mm},
                        {"total_length_mm", d.total_length_mm()},
                        {"segments", segments}};
  if (d.connector_mass_g) out["connector_mass_g"] = *d.connector_mass_g;
  return out;
}

}  // namespace softarm::fem

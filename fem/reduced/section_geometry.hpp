#pragma once
// Plane geometry of the rod sections (rod_section.hpp, cell_section.hpp): the
// chords that the 3CA's shapes cut on a line y = const. The shapes are discs
// (tubes, chambers, centre hole) and the sheath's envelope, the Minkowski sum
// of the triangle of the RRA axes and a disc of radius r_o + t_s (convex, so
// every chord is one interval).
#include <array>
#include <vector>

#include "fem/mesh/tca_design.hpp"

namespace softarm::fem::section_geometry {

struct Interval {
  double lo = 1, hi = 0;  // empty when lo > hi
  double length() const { return hi > lo ? hi - lo : 0.0; }
  /// Length of the overlap with [a, b].
  double overlap(double a, double b) const;
};

using Point = std::array<double, 2>;

/// Chord of the disc (centre (cx, cy), radius r) on the line y = const.
Interval disc_chord(double cx, double cy, double r, double y);
/// Chord of a convex polygon (counter-clockwise vertices) on the line y = const.
Interval polygon_chord(const std::vector<Point>& polygon, double y);
/// Exact area of the disc (centre height cy, radius r) between the lines y = a and y = b > a.
double disc_strip_area(double cy, double r, double a, double b);
/// Chord of the envelope (triangle `v`, counter-clockwise, grown by rho) on the line y = const.
Interval envelope_chord(const std::array<Point, 3>& v, double rho, double y);

/// The three RRA axes of a 3CA at height z in a section frame whose first
/// axis is at angle `frame_angle_rad` from chamber 1's axis (chamber k at
/// (k − 1)·120°, counter-clockwise): axis k − 1 at a_c(z)·(cos φ, sin φ),
/// φ = (k − 1)·120° − frame_angle_rad.
std::array<Point, 3> tca_axes(const TcaDesign& design, double z, double frame_angle_rad);
/// The same three points in counter-clockwise order (for the envelope's outward normals).
std::array<Point, 3> counter_clockwise(std::array<Point, 3> v);

}  // namespace softarm::fem::section_geometry

#pragma once
// The quadrilateral cross-section (x, y) of a lone RRA or of a three-chambered
// actuator (3CA), as 9-node quadrilaterals whose topology is fixed for a mesh
// level and whose node positions are a smooth function of the section's size,
// so a tapered body is meshed by evaluating the same section at every height
// (layered_extrusion.hpp).
//
// Each actuator is an O-grid about its axis C: a bilinear "kite" in the
// middle of the chamber (used only where the chamber is capped), then rays
// from C through the chamber circle r_c, the tube wall, the ring band
// [r_o − a/2, r_o + a/2] (a: side of the equal-area square ring, tca_design.hpp)
// with a station on the tube's outer surface r_o, and, in a 3CA, the core out
// to the boundary of the actuator's 120° sector. Circles are exact at every node
// (mid-edge nodes included); the sector boundary is the sheath's outer surface
// (an arc of radius r_o + t_s about C joined tangentially to the straight
// segments of the convex envelope, spec §1 "sheath thickness") and the two lines
// from the 3CA axis O to the envelope that separate neighbouring sectors. Rays
// end at points distributed along that boundary, so the corners of a sector
// (O, or the centre hole, and the envelope's points on the separating lines)
// are nodes and neighbouring sectors share their boundary nodes exactly.
//
// The section is mirror-symmetric about the line from O through each actuator's
// axis, and that line is made of element edges: a half model cuts no element.
#include <Eigen/Core>
#include <array>
#include <vector>

namespace softarm::fem {

enum class SectionRegion { chamber, tube, ring_inner, ring_outer, core };

/// The sizes that set the section at one height z (mm, radians).
struct SectionGeometry {
  double outer_radius = 9;         // r_o(z) of each RRA
  double wall_thickness = 4;       // t_w: chamber radius r_c = r_o − t_w
  double ring_side = 1.9;          // a: the ring band spans r_o ± a/2
  double spacing = 3;              // 3CA: gap between neighbouring RRAs' outer surfaces
  double sheath_thickness = 2;     // 3CA: envelope offset
  double hole_radius = 0;          // 3CA: centre hole (0: none)
  double first_axis_angle = 0;     // angle of actuator 0's axis about O (3CA)
};

class ActuatorSection {
 public:
  /// actuators = 1: a lone RRA centred on O, sections out to r_o + a/2;
  /// actuators = 3: a 3CA. `level` ≥ 1 refines every direction uniformly:
  /// 8·level rays per actuator, level elements per radial band. `with_hole` fixes
  /// the topology for a centre hole (the geometry must then have hole_radius > 0).
  ActuatorSection(int actuators, int level, bool with_hole, const SectionGeometry& reference);

  int actuators() const { return actuators_; }
  int num_nodes() const { return num_nodes_; }
  int num_quads() const { return static_cast<int>(quads_.size()); }
  /// 9-node quadrilaterals (VTK order, counter-clockwise), in section node ids.
  const std::vector<std::array<int, 9>>& quads() const { return quads_; }
  SectionRegion region(int quad) const { return region_[quad]; }
  int actuator(int quad) const { return actuator_of_[quad]; }
  /// Section node positions for the sizes at one height.
  std::vector<Eigen::Vector2d> positions(const SectionGeometry& geometry) const;
  /// Axis position of each actuator for these sizes.
  std::vector<Eigen::Vector2d> axes(const SectionGeometry& geometry) const;

 private:
  std::vector<Eigen::Vector2d> raw_points(const SectionGeometry& g) const;
  int actuators_, level_;
  bool hole_;
  int num_nodes_ = 0;
  std::vector<int> unique_of_raw_;
  std::vector<int> raw_of_unique_;
  std::vector<std::array<int, 9>> quads_;
  std::vector<SectionRegion> region_;
  std::vector<int> actuator_of_;
};

}  // namespace softarm::fem

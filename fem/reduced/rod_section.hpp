#pragma once
// Cross-sections of the reduced (rod) model of RRAs and 3CAs, integrated in
// strips normal to the bending direction. Planar bending (Euler–Bernoulli,
// plane sections stay plane and normal to the axis) with large stretch: the
// fibre at distance y from the section's reference point (the 3CA axis, or the
// RRA axis) has stretch λ(y) = λ0 − κ·y, κ = dθ/dS per reference length, so
// only the area of each material at each y matters. Each strip keeps the area
// of every material between y − Δy/2 and y + Δy/2: exact for the circles
// (tubes, chambers, centre hole), Gauss–Legendre across sub-rows for the
// sheath's envelope (the Minkowski sum of the axes' triangle and a disc of
// radius r_o + t_s), so the section is a smooth function of the geometry.
//
// What the section leaves out (our definitions: docs/definitions.md, The definitions, row
// "reduced model"):
// - rings carry no axial load: they are discrete, in series with silicone gaps,
//   so the tube wall and the core around a ring count as silicone for stiffness;
//   the rings' mass is smeared along the segment;
// - the chamber's pressure acts as an axial force p·A_c at the chamber's axis
//   (A_c = π r_c² of the undeformed chamber at that height, held by the rings),
//   which the end caps transmit; the rod model multiplies it by a factor
//   calibrated against the axisymmetric FEM (rra_calibration.hpp);
// - the end caps are solid tube material (the chamber's force area is taken at
//   the cap's inner face).
// Optionally (ArmRodSpec::ring_confinement) the rings hold the tube wall inside
// the grooves' bottom radius R_i (confined_wall.hpp): that wall gets the
// confined law and the chamber's force area becomes π R_i² on the ringed
// length (the end caps keep π r_c²).
#include <array>
#include <memory>
#include <vector>

#include "fem/mesh/tca_design.hpp"
#include "fem/reduced/fibre_law.hpp"

namespace softarm::fem {

/// Materials of a section's fibres.
enum class FibreMaterial { tube = 0, sheath = 1 };

struct FibreStrip {
  double y = 0;          // strip centre along the bending direction, mm
  double tube_area = 0;  // mm² of tube material in the strip
  double sheath_area = 0;
  double confined_area = 0;  // mm² of tube wall held by the rings (confined_wall.hpp)
};

struct RodSection {
  std::vector<FibreStrip> strips;
  /// Chamber k (k = 0..count-1): position along the bending direction and the
  /// area its pressure acts on (mm²).
  std::vector<double> chamber_y, chamber_force_area;
  double tube_area = 0, sheath_area = 0;  // mm², sums over the strips
  double confined_area = 0;
  std::shared_ptr<const FibreLaw> confined_law;  // the confined wall's law at this height (null: none)
};

/// The 3CA section at height z (0 = bottom, l = top), bending towards the unit
/// direction at angle `bend_direction_rad` in the section plane (chamber 1's
/// axis at angle 0, chamber k at (k − 1)·120°). `strips` strips across the
/// envelope, `subrows` midpoint rows per strip.
RodSection tca_section(const TcaDesign& design, double z, double bend_direction_rad, int strips = 48, int subrows = 6,
                       const HyperelasticLaw* tube_law = nullptr);

/// The lone RRA's section at height z (axisymmetric: the bending direction is irrelevant).
RodSection rra_section(const RraDesign& design, double z, int strips = 32);

/// Chamber radius for the pressure force at height z: r_c(z) inside the
/// chamber, r_c at the nearer cap face inside a cap.
double chamber_force_radius(const RraDesign& design, double z);
/// Radius the rings hold at height z (the grooves' bottom, r_o − d_r/2; square rings: half
/// their side); 0 in an end cap or without rings.
double confinement_radius(const RraDesign& design, double z);
/// True where z lies inside an end cap (solid tube material).
bool in_end_cap(const RraDesign& design, double z);

}  // namespace softarm::fem

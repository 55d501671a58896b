#pragma once
// What the reduced rods (arm_rod.hpp: planar; spatial_rod.hpp: spatial) are
// made of: pieces in series from the clamp to the tip (RRAs, 3CA segments,
// rigid connectors), their nodes along the reference arc length, and the mass
// of each interval between nodes. Both rods share this layout, so they agree on
// the geometry and the weight and differ only in their kinematics.
#include <array>
#include <vector>

#include "fem/materials/material.hpp"
#include "fem/mesh/spl_design.hpp"
#include "fem/mesh/tca_design.hpp"
#include "fem/reduced/section_equilibrium.hpp"

namespace softarm::fem {

/// Multiplier of the chambers' pressure force p·A_c, as a function of pressure
/// (piecewise linear, constant beyond the ends): 1 without calibration.
struct ForceFactor {
  std::vector<double> pressure_kPa, factor;
  double at(double p_kPa) const;
};

struct RodPiece {
  enum class Kind { rra, tca, connector } kind = Kind::tca;
  TcaDesign design;        // tca: the segment; rra: design.actuator
  double length_mm = 0;    // connector only
  double mass_kg = 0;      // connector only
  ForceFactor force_factor;
};

struct ArmRodSpec {
  std::vector<RodPiece> pieces;  // from the clamp to the tip
  Material tube, rings, sheath;
  int nodes_per_segment = 33;
  double bend_direction_rad = 0;  // planar rod: in each 3CA's section, 0 = towards chamber 1
  bool ring_confinement = false;  // 3CA sections: rigid rings hold the tube wall (confined_wall.hpp; rings of
                                  // less than 100x the tube's shear modulus hold nothing)
};

struct RodPartMasses {
  double tube = 0, rings = 0, sheath = 0, connectors = 0;
};

/// Fibre extremes of one piece at a state (for stress, stretch and durability measures).
struct PieceExtremes {
  double tube_max_stretch = 1, tube_min_stretch = 1, sheath_max_stretch = 1, sheath_min_stretch = 1;
  double chamber_max_stretch = 1;  // largest axial stretch at a pressurised chamber's axis
  /// Widens the tube and sheath extremes by one section's (the first section sets them).
  void widen(const FibreExtremes& section, bool first);
};

/// Axial forces (N) of a piece's chambers at pressures p_k (kPa) on areas A_k (mm²): c(p)·p·A_k.
std::vector<double> chamber_forces_N(const RodPiece& piece, const std::array<double, 3>& pressure_kPa,
                                     const std::vector<double>& force_area_mm2);

struct RodLayout {
  struct Node {
    int piece = -1;
    bool rigid = false;  // a connector's end
    double z = 0;        // height in its piece (0 = the piece's distal end; RRA and 3CA frames)
  };
  std::vector<Node> nodes;             // from the clamp to the tip
  std::vector<double> s;               // reference arc length per node, mm
  std::vector<double> interval_mass;   // kg between node j and j + 1
  RodPartMasses masses;
};

/// The nodes of every piece: a 3CA or RRA in three zones (top cap, chamber,
/// bottom cap) with a node on each side of the zone boundaries (ΔS = 0 between
/// them, where the section jumps), a connector as its two ends.
RodLayout rod_nodes(const ArmRodSpec& spec);
/// Fills the layout's interval masses: exact part masses (rra_design.hpp),
/// distributed along each piece as its section areas (per node) are.
void distribute_masses(RodLayout& layout, const ArmRodSpec& spec, const std::vector<double>& tube_area_mm2,
                       const std::vector<double>& sheath_area_mm2);

/// The SPL's pieces from the shoulder to the tip: shoulder connector, segment 1,
/// connector 1–2, segment 2, connector 2–3, segment 3. A connector fills the
/// 3CA's envelope at its joint; its mass is the design's, else from `connector`'s density.
std::vector<RodPiece> spl_rod_pieces(const SplDesign& design, const Material& connector);

}  // namespace softarm::fem

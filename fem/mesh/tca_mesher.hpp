#pragma once
// Hexahedral meshes of the 3D actuators: the three-chambered actuator (3CA) and
// a lone RRA, by extruding their cross-section (actuator_section.hpp) through
// layers (layered_extrusion.hpp): end caps, rings (equal-area squares,
// tca_design.hpp) and the gaps between rings each get their own element
// layers, so every material interface is a mesh surface.
//
// Levels refine uniformly: level L has 8L rays around each chamber, L elements
// across each radial band (chamber, wall, inner and outer half of the ring band,
// core) and L elements through each axial band (cap, ring, gap; bands longer than
// 4 mm get more). `axial_level` refines along the axis alone, so a convergence study
// can take one direction at a time where a uniform level 2 would not fit in memory.
#include "fem/mesh/mesh.hpp"
#include "fem/mesh/rra_design.hpp"
#include "fem/mesh/spl_design.hpp"
#include "fem/mesh/tca_design.hpp"

namespace softarm::fem {

struct SolidMeshOptions {
  int level = 1;
  int order = 2;                     // 1: Hex8, 2: Hex27 (or Hex20 with `serendipity`)
  bool half = false;                 // keep y ≥ 0: a half model on the symmetry plane y = 0
  double first_axis_angle_rad = 0;   // 3CA: angle of chamber 1's axis about the 3CA axis
  bool serendipity = false;          // order 2: drop face and body centres (serendipity_mesh.hpp)
  int axial_level = 0;               // element layers per axial band as at this level; 0: `level`
};

/// The level whose element layers a mesh gets: `axial_level`, or `level` where it is 0 (unset).
inline int layers_level(int level, int axial_level) { return axial_level > 0 ? axial_level : level; }

/// A 3CA along z ∈ [0, l]: parts "tube", "rings", "sheath"; chambers 1–3, chamber k
/// about the axis at first_axis_angle + (k − 1)·120°. Node sets "top" (z = l),
/// "bottom" (z = 0), "symmetry" (y = 0, half models only). With `half`, the
/// symmetry plane y = 0 is a mirror plane of the geometry only if chamber 1
/// (or the midpoint between chambers 2 and 3) lies on it: first_axis_angle 0 or π.
Mesh mesh_tca(const TcaDesign& design, const SolidMeshOptions& options);

/// One ring pitch of a 3CA about ring k (1 = nearest the bottom), z ∈ [0, pitch]: half a
/// gap, the ring, half a gap, as a prism of the section at the ring's centre (the taper
/// over one pitch left out), so the cell is mirror-symmetric about its mid-plane. Its
/// chambers are open at both end faces and closed there by lids (chamber_lids.hpp).
/// Node sets "bottom", "top" and, in half models, "symmetry". Throws std::logic_error
/// for a ring outside 1..ring_count.
Mesh mesh_tca_cell(const TcaDesign& design, int ring, const SolidMeshOptions& options);

enum class TcaEnd { bottom, top };

/// An end of a 3CA as meshed by mesh_tca, from its end face to the middle of the gap after its
/// `rings`-th ring: the cap, the rings near it and the taper there, z ∈ [0, rings·pitch] (bottom)
/// or [l − rings·pitch, l] (top), in the 3CA's own z. Its chambers, open at the cut, are closed
/// there by lids (chamber_lids.hpp). Node sets "bottom", "top" and, in half models, "symmetry".
/// Throws std::logic_error unless 1 ≤ rings and 2·rings < ring_count.
Mesh mesh_tca_end(const TcaDesign& design, TcaEnd end, int rings, const SolidMeshOptions& options);

/// A lone RRA along z ∈ [0, l] in 3D: parts "tube", "rings"; chamber 1; node sets
/// as mesh_tca. The 3D twin of the axisymmetric model with square rings.
Mesh mesh_rra_3d(const RraDesign& design, const SolidMeshOptions& options);

/// The SPL along z ∈ [0, L] (tip at z = 0, shoulder at z = L): parts "tube", "rings",
/// "sheath", "connector"; chambers 1–9 (segment n holds 3n − 2 … 3n, chamber 1 of
/// every segment on the axis at first_axis_angle); node sets "top" (the shoulder),
/// "bottom" (the tip face), "segment_n_top" and "segment_n_bottom" (n = 1..3: the joints).
Mesh mesh_spl(const SplDesign& design, const SolidMeshOptions& options);

}  // namespace softarm::fem

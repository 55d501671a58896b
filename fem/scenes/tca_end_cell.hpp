#pragma once
// An end of a 3CA on its own: the cap, the first few rings and the taper there
// (tca_mesher.hpp, mesh_tca_end), cut in the middle of a gap where the section's
// response is again the ring-pitch cell's (tca_cell.hpp). What the cells leave out
// by construction lives here: the cap holds the chambers' walls near it, so the
// pitches beside it bulge and bend less than a pitch far from it, and the cap itself
// turns and stretches a little as the chambers push on it.
//
// Supports, by what the end face is attached to (EndFaceSupport):
// - bonded (the 3CA's clamp; an SPL segment's ends on its rigid connectors): the end face
//   fixed ("ENCASTRE"; bonded to a rigid body it moves with that body, and the end's
//   deformation is the same up to a rigid motion); the cut stays plane
//   (plane_face_form.hpp) with its tilt and offset free, in-plane motion free;
// - free (the 3CA's free end, the SPL's tip): the end face free; the cut held on its rest
//   plane, in-plane motion free but for the rigid motions.
// Under pressure alone (no gravity, no end load) the end turns by the rotation between its
// two faces, which the cell rods (cell_rod.hpp, spatial_cell_rod.hpp) take instead of their
// cells' κ₀ over the same length. A free face's turn is measured as the 3D scene measures
// the 3CA's bending (spec §4): its vector area now against at rest; a bonded end's is the
// cut's plane's tilt.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "fem/mesh/tca_mesher.hpp"
#include "fem/scenes/pressure_path.hpp"
#include "fem/scenes/tca_scene.hpp"

namespace softarm::fem {

/// What an end face is attached to (header).
enum class EndFaceSupport { bonded, free };

struct TcaEndState {
  double pressure_kPa = 0;   // of the most pressurised chamber
  double rotation_rad = 0;   // between the end face and the cut; > 0 towards the scene's bend
  /// The same rotation as a vector about the user's x and y: the upper face's (nearer z = length)
  /// against the lower one's, as a ring-pitch cell's κ₀ times its length (tca_cell.hpp).
  Eigen::Vector2d rotation_vector_rad = Eigen::Vector2d::Zero();
  double elongation_mm = 0;  // of the end's axis (the arc through both faces' centroids)
  int newton_iterations = 0;
  bool is_output = false;
};

struct TcaEndCellResult {
  ModelChoice model;
  TcaEnd end = TcaEnd::bottom;
  EndFaceSupport face = EndFaceSupport::free;
  int rings = 0;
  double length_mm = 0;  // from the end face to the cut
  std::string element_name;
  int dofs = 0;
  std::vector<TcaEndState> states;  // every converged state, rest included
  PressurePathResult path;
  double seconds = 0;
};

/// Runs `end` of spec's 3CA through its first `rings` rings (2·rings < ring_count), its end face
/// supported as `face`, under the spec's chamber pressures, mesh, outputs and solver settings;
/// gravity is ignored.
TcaEndCellResult run_tca_end_cell(const TcaSceneSpec& spec, TcaEnd end, int rings, EndFaceSupport face);

/// The 3CA scene's supports: the top end clamped (bonded), the bottom one free.
EndFaceSupport tca_scene_end_support(TcaEnd end);

}  // namespace softarm::fem

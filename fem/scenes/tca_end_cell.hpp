#pragma once
// An end of a 3CA on its own: the cap, the first few rings and the taper there
// (tca_mesher.hpp, mesh_tca_end), cut in the middle of a gap where the section's
// response is again the ring-pitch cell's (tca_cell.hpp). What the cells leave out
// by construction lives here: the cap holds the chambers' walls near it, so the
// pitches beside it bulge and bend less than a pitch far from it, and the cap itself
// turns and stretches a little as the chambers push on it.
//
// Supports, as in the whole 3CA:
// - the top end (the clamp): its end face fixed ("ENCASTRE"); the cut stays plane
//   (plane_face_form.hpp) with its tilt and offset free, in-plane motion free;
// - the bottom end (the free end): its end face free; the cut held on its rest plane,
//   in-plane motion free but for the rigid motions.
// Under pressure alone (no gravity, no end load) the end turns by the angle between its
// two faces, which the cell rod (cell_rod.hpp) takes instead of its cells' κ₀ over the
// same length. At the free end that angle is measured as the 3D scene measures the
// 3CA's bending (spec §4): the free face's vector area now against at rest.
#include <string>
#include <vector>

#include "fem/mesh/tca_mesher.hpp"
#include "fem/scenes/pressure_path.hpp"
#include "fem/scenes/tca_scene.hpp"

namespace softarm::fem {

struct TcaEndState {
  double pressure_kPa = 0;   // of the most pressurised chamber
  double rotation_rad = 0;   // between the end face and the cut; > 0 towards the scene's bend
  double elongation_mm = 0;  // of the end's axis (the arc through both faces' centroids)
  int newton_iterations = 0;
  bool is_output = false;
};

struct TcaEndCellResult {
  ModelChoice model;
  TcaEnd end = TcaEnd::bottom;
  int rings = 0;
  double length_mm = 0;  // from the end face to the cut
  std::string element_name;
  int dofs = 0;
  std::vector<TcaEndState> states;  // every converged state, rest included
  PressurePathResult path;
  double seconds = 0;
};

/// Runs `end` of spec's 3CA through its first `rings` rings (2·rings < ring_count) under the
/// spec's chamber pressures, mesh, outputs and solver settings; gravity is ignored.
TcaEndCellResult run_tca_end_cell(const TcaSceneSpec& spec, TcaEnd end, int rings);

}  // namespace softarm::fem

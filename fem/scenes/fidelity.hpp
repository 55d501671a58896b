#pragma once
// The fidelity ladder (issue 6): for each scene, the models softarm has, each
// with its measured error against the best reference this machine can compute
// and its cost, cheapest first. A scene asks for "fidelity" (fast, balanced,
// accurate) or a "target_error_percent" in its "model" object; the cheapest
// level whose measured error meets the target is used, and softarm prints
// which and why. Models dominated by a cheaper, more accurate one (RRA Q2/P1
// level 2, every Q1/P0 level beyond 1, the 3CA's Hex8, which locks, and on the
// thesis 3CA every 3D mesh coarser than the reference but the 8-point Hex20 level
// 1, which is both cheaper and closer to it) are not on the ladder.
//
// The numbers are measurements on the thesis designs (docs/validation.md, The
// thesis RRA, and the rest of docs/validation.md; docs/reduced-model.md,
// Checked against the FEM; how each was measured: docs/fidelity-ladder.md),
// not estimates; a design far from the thesis' may see other errors.
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace softarm::fem {

struct ModelLevel {
  std::string name;               // "axisymmetric Q2/P1, level 1"
  bool reduced = false;           // the rod of fem/reduced instead of the FEM
  int mesh_level = 1, element_order = 2;
  double error_percent = 0;       // measured, against `reference`; 0 for the reference itself
  std::string error_measure;      // what was compared
  double seconds = 0;             // typical wall time on this 2-core machine (threads: see each ladder)
  int dofs = 0;
  bool serendipity = false;       // 3D: Hex20 instead of Hex27 (element_order 2)
  bool reduced_integration = false;  // 3D Hex20 at 2×2×2 Gauss points
  int axial_level = 0;            // 3D: element layers along the axis as at this level (mesh.axial_level); 0: mesh_level
  /// With `reduced`: the cell rod (fem/reduced/cell_rod.hpp; the SPL's spatial_cell_rod.hpp), whose
  /// ring-pitch cells are 3D models of the mesh settings above, instead of the fibre-section rod.
  bool cell_rod = false;
  /// With `cell_rod`: both ends of each 3CA through this many rings as 3D end cells
  /// (fem/scenes/tca_end_cell.hpp); 0: rigid caps on the cells' response.
  int end_rings = 0;
};

struct FidelityLadder {
  std::string scene, reference;   // reference: what the errors are measured against
  std::vector<ModelLevel> levels;  // cheapest first
};

const FidelityLadder& fidelity_ladder(const std::string& scene);

/// The "target" of fidelity "fast": the cheapest model of the ladder, whatever its measured error
/// (which is printed with it). A percentage would pick a slow model where the reduced one misses it:
/// the SPL's spatial rod is 44 % off, its cell rod 4.6 % at ~4 minutes, and every 3D rung but a locking
/// preview takes 17 to 96 minutes.
inline constexpr double kCheapestModel = std::numeric_limits<double>::infinity();

/// Target error of a named fidelity: fast kCheapestModel, balanced 2 %, accurate 0.5 %.
double fidelity_target_percent(const std::string& fidelity);

struct ModelSelection {
  ModelLevel level;
  std::string reason;  // "cheapest level within 2 % (measured 0.61 % vs …)"
};
/// The cheapest level within `target_percent`; if none is, the most accurate, and the reason says so.
ModelSelection select_model(const std::string& scene, double target_percent);

}  // namespace softarm::fem

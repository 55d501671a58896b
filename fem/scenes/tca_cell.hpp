#pragma once
// A ring-pitch cell of a 3CA: the section's own response to its chamber pressures,
// free of the end caps, the clamp and the taper. One ring pitch about ring k, as a
// prism of the section at the ring's centre (tca_mesher.hpp, mesh_tca_cell), with
// its chambers closed by lids on the cut faces (chamber_lids.hpp). The bottom face
// stays on z = 0 and the top face on a plane z = L + a + b·(x − u_x) + c·(y − u_y), u the
// in-plane displacement of the bottom face's centre node (plane_face_form.hpp); their
// in-plane motion is free, its rigid part held by the bottom face's mean displacement
// (cell_supports.hpp), which then carries no force. By the cell's mirror symmetry
// about its mid-plane this is a slice of a long, uniformly bent and stretched 3CA:
// the homogenised beam of Buannic & Cartraud (2001) at the scale of one ring.
//
// What it gives, at every pressure: the free axial stretch λ₀ = 1 + a/L of the 3CA
// axis and the free curvature κ₀ = atan(|(b, c)|)/L per reference length, signed
// positive towards the side the full scene bends to (away from the pressurised
// chambers). Optional dead end loads (an axial force, a moment) give the section's
// stiffness by difference. Gravity is not a uniform bending load and is left out.
//
// This is the calibration a rod (fem/reduced) can take from the FEM instead of its
// fibre section: the 3CA's bending angle is ∫ κ₀ dz along its ringed length plus
// what the caps and the clamp add, which the cell leaves out by construction.
#include <optional>
#include <string>
#include <vector>

#include "fem/reduced/cell_rod.hpp"
#include "fem/reduced/spatial_cell_rod.hpp"
#include "fem/scenes/tca_end_cell.hpp"
#include "fem/scenes/tca_scene.hpp"

namespace softarm::fem {

struct TcaCellState {
  double pressure_kPa = 0;      // of the most pressurised chamber
  double stretch = 1;           // λ₀ of the 3CA axis
  double curvature_per_mm = 0;  // κ₀, per reference length; > 0 towards the scene's bend
  double chamber_volume_mm3 = 0;  // Σ f_i V_i over the loaded chambers, whole cell
  double plane_gap_mm = 0;      // largest distance of an end-face node from its plane (the penalty's slack)
  /// At output states: the tangent's response to an end moment about the bend axis with the
  /// axial force held, dκ/dM (1/(N·mm²); 1/EI of a plain beam), and to an axial force with the
  /// moment held, dλ/dN (1/N). 0 where the tangent is not positive definite (past a limit point).
  double bending_compliance_per_Nmm2 = 0;
  double axial_compliance_per_N = 0;
  /// The same in the user frame, as vectors: the rate along +z of the section's rotation vector,
  /// κ = (κx, κy) per reference length (κ₀ is |κ|, signed), and at output states the tangent's
  /// d(κx, κy)/d(Mx, My) for end moments about x and y (0 where not positive definite). A half
  /// model sees only moments about its mirror plane's normal; the other diagonal entry is taken
  /// equal to it (an isotropic section: exact for the unpressurised 3CA's threefold symmetry).
  Eigen::Vector2d curvature_vector_per_mm = Eigen::Vector2d::Zero();
  Eigen::Matrix2d bending_compliance_matrix_per_Nmm2 = Eigen::Matrix2d::Zero();
  int newton_iterations = 0;
  bool is_output = false;
};

struct TcaCellResult {
  ModelChoice model;
  int ring = 0;
  double ring_centre_z_mm = 0, pitch_mm = 0;
  std::string element_name;
  int dofs = 0;
  double mass_per_length_kg_per_mm = 0;  // the whole cell's mass over its pitch (rings smeared)
  std::vector<TcaCellState> states;  // every converged state, rest included
  PressurePathResult path;
  double seconds = 0;
  // Where the seconds went (benchmarks): the problem's evaluations (assembly) and, at the
  // output states, the end-face compliances' own tangent, factorisation and solves.
  double assembly_s = 0;
  int evaluations = 0;
  double compliance_s = 0;
};

/// Dead loads on the cell's top face besides the pressures (user frame, about the axis).
struct CellEndLoad {
  double axial_force_N = 0;                               // tension > 0
  Eigen::Vector2d moment_Nmm = Eigen::Vector2d::Zero();  // about x and y, right-handed
};

/// Runs the cell about `ring` (1..ring_count) of spec.design with the spec's materials,
/// mesh, chamber pressures, outputs and solver settings; spec.gravity is ignored.
TcaCellResult run_tca_cell(const TcaSceneSpec& spec, int ring, const CellEndLoad& end_load = {});

/// The cell's torsional stiffness GJ (N·mm²) at rest: the cell about `ring` with periodic faces
/// (periodic_face_form.hpp; warping free, the same on both), the linear twist per unit torque. This
/// is Saint-Venant's torsion of the ringed 3CA, rings and chambers included; NaN where the tangent
/// is not positive definite. On the half model with its mirror plane held as a twist's odd symmetry
/// asks (twist_compliance.hpp), the full model where spec.allow_symmetry is off: the same GJ.
double cell_torsion_stiffness(const TcaSceneSpec& spec, int ring);

/// The same cell's GJ along the spec's pressure ramp (the periodic cell stretching and bending freely
/// under its pressures), at the rest state and every output the ramp reached.
struct CellTorsionState {
  double pressure_kPa = 0;
  double stiffness_Nmm2 = 0;  // NaN where the tangent is not positive definite
};
std::vector<CellTorsionState> cell_torsion_along_ramp(const TcaSceneSpec& spec, int ring);

/// A cell's output states as a table for the cell rod (cell_rod.hpp): those with a
/// positive definite tangent, in order.
CellTable cell_table(const TcaCellResult& cell);

/// A cell's output states as the spatial cell rod's table (spatial_cell_rod.hpp), along the load
/// level p/peak_kPa (an unloaded cell's one state holds at every level); its torsion is left to the
/// caller (cell_torsion_stiffness).
SpatialCellTable spatial_cell_table(const TcaCellResult& cell, double peak_kPa);

/// An end cell's output states as the cell rod's end table (cell_rod.hpp, EndTable).
EndTable end_table(const TcaEndCellResult& end);

/// An end cell's output states as the spatial cell rod's end table (spatial_cell_rod.hpp), along the
/// load level p/peak_kPa.
SpatialEndTable spatial_end_table(const TcaEndCellResult& end, double peak_kPa);

/// The cell rod of spec's 3CA from its cells and end cells, if any (cell_rod.hpp): length, caps,
/// ends, and the spec's gravity resolved along the pressures' bend direction and the axis (user
/// frame).
CellRodSpec tca_cell_rod(const TcaSceneSpec& spec, const std::vector<TcaCellResult>& cells,
                         const std::vector<TcaEndCellResult>& ends = {});

/// The rings a cell rod takes its cells about: the first, middle and last (fewer when the 3CA has
/// fewer; none without rings).
std::vector<int> cell_rod_rings(int ring_count);

/// The rings an end cell takes when `asked` for (0: none): a 3CA (or SPL segment) has end cells only
/// where it has more than twice as many rings; and the note that says so where it has not.
int end_cell_rings(int asked, int ring_count);
std::string no_end_cells_note(int asked, int ring_count);

}  // namespace softarm::fem

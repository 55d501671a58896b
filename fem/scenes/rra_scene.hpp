#pragma once
// The ring-reinforced actuator (RRA) extension scene: one end fixed, the
// chamber pressurised quasi-statically, gravity off (thesis Ch. 5: the RRA's
// mass is negligible). Axisymmetric: a lone RRA under internal pressure is
// a body of revolution under a load of revolution, so the 2D model is exact
// in the geometry of revolution and ~100× cheaper than 3D.
#include <chrono>
#include <functional>
#include <vector>

#include "fem/forms/elastic_form.hpp"
#include "fem/io/abaqus_writer.hpp"
#include "fem/materials/burst_criteria.hpp"
#include "fem/materials/material.hpp"
#include "fem/mesh/mesh.hpp"
#include "fem/mesh/rra_design.hpp"
#include "fem/scenes/pressure_path.hpp"

namespace softarm::fem {

struct RraSceneSpec {
  RraDesign design;
  Material tube_material, ring_material;
  int mesh_level = 1;
  int element_order = 2;  // 1: Q1/P0, 2: Q2/P1
  VolumetricTreatment treatment = VolumetricTreatment::projected_dilatation;
  PressurePathSpec path;
  double peak_averaging_radius_mm = kDefaultPeakAveragingRadius_mm;  // RraCurvePoint::averaged
};

/// One state of the pressure–extension curve.
struct RraCurvePoint {
  double pressure_kPa = 0, extension_mm = 0, chamber_volume_mm3 = 0, pv_stiffness_kPa_per_mm3 = 0;
  double tube_max_stretch = 1, tube_max_principal_stress_MPa = 0, ring_max_principal_stress_MPa = 0;
  double tube_max_log_strain = 0;
  /// The tube's peaks as the criteria read them: the largest averages over a ball of radius
  /// RraSceneSpec::peak_averaging_radius_mm (the tube_max_* above are single Gauss points, at
  /// the groove lip's singular corner; they are reported, never judged).
  struct AveragedPeaks {
    double stretch = 1, stress_MPa = 0, log_strain = 0;
  } averaged;
  int newton_iterations = 0;
};

struct RraTimings {
  double mesh_s = 0, setup_s = 0, solve_s = 0, total_s = 0;  // wall-clock seconds
  double assembly_s = 0;  // inside solve_s: energy, gradient and Hessian evaluations
  int evaluations = 0;
};

struct RraResult {
  Mesh mesh;
  std::vector<RraCurvePoint> curve;     // at the requested output pressures (and the last reached state)
  PressurePathResult path;
  Vector final_positions;
  std::vector<Vector> curve_positions;  // the positions at each curve point (deformed.pvd's frames)
  std::vector<ElementResult> final_element_results;
  std::string element_name;
  double tube_mass_kg = 0, ring_mass_kg = 0;
  int dofs = 0;
  RraTimings timings;
};

using RraProgress = std::function<void(const RraCurvePoint&)>;

RraResult run_rra_scene(const RraSceneSpec& spec, const RraProgress& progress = {});

/// The scene's mesh (Q1 or Q2 per spec.element_order) and the material of each of its parts.
Mesh rra_mesh(const RraSceneSpec& spec);
std::vector<Material> rra_part_materials(const Mesh& mesh, const RraSceneSpec& spec);

/// The same scene as an Abaqus/CalculiX deck at one pressure (mesh must outlive the deck).
AbaqusDeck rra_abaqus_deck(const RraSceneSpec& spec, const Mesh& mesh, double pressure_kPa);

}  // namespace softarm::fem

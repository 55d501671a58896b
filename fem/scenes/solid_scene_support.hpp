#pragma once
// What the 3D actuator scenes (3CA, SPL) share: the choice between a half and a
// full model, the supports, the frame rotation, per-part peaks and masses, and
// the measures of a deformed face (position and orientation of a joint or tip).
#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include <memory>

#include "fem/assembly/energy_problem.hpp"
#include "fem/forms/chamber_pressure_form.hpp"
#include "fem/forms/elastic_form.hpp"
#include "fem/materials/material.hpp"
#include "fem/mesh/mesh.hpp"
#include "fem/mesh/tca_mesher.hpp"

namespace softarm::fem {

/// Which model a scene is solved on, and why.
struct ModelChoice {
  std::string name;      // e.g. "half model (mirror plane through chamber 1)"
  std::string reason;
  bool half = false;
  int mirror_chamber = 0;          // 1–3 when half (the same in every segment)
  double frame_angle_rad = 0;      // solver frame = user frame rotated by −this about z
};

/// The mesh options of a 3D scene spec (its mesh level, axial level, element order and
/// serendipity) on `model`: half or full, the mirror chamber on +x of the solver frame.
template <class SceneSpec>
SolidMeshOptions solid_mesh_options(const SceneSpec& spec, const ModelChoice& model) {
  SolidMeshOptions options;
  options.level = spec.mesh_level;
  options.axial_level = spec.axial_level;
  options.order = spec.element_order;
  options.serendipity = spec.serendipity;
  options.half = model.half;
  options.first_axis_angle_rad = -model.frame_angle_rad;
  return options;
}

/// A half model on the plane through the arm's axis and chamber k (k = 1..3, axes at
/// (k − 1)·120°, the same in every segment) when, in every segment, the other two
/// chambers are at equal pressure and gravity lies in that plane; else the full model.
/// `pressures_kPa` holds 3 entries per segment.
ModelChoice choose_mirror_model(const std::vector<double>& pressures_kPa, const Eigen::Vector3d& gravity_m_s2,
                                bool allow_symmetry);

Eigen::Matrix3d rotation_about_z(double angle);
/// Rotates every node-major 3-vector block of x about z.
Vector rotated_about_z(const Vector& x, double angle);

/// The pressure forms of the chambers with a peak pressure > 0 (and facets in the
/// mesh: a half model lacks one chamber per segment), added to `problem`, with
/// their shares of the largest peak for run_pressure_path.
struct ChamberLoads {
  std::vector<std::shared_ptr<ChamberPressureForm>> forms;
  std::vector<const ChamberPressureForm*> loaded;
  std::vector<double> fractions;
  double peak_kPa = 0;  // the largest peak (0 when no chamber is loaded)
};
ChamberLoads add_chamber_loads(const Mesh& mesh, const std::vector<double>& peaks_kPa, const LoadState& load,
                               EnergyProblem& problem);

/// The Gauss rule a scene asks for where the mesh is Hex20 (the only element with a
/// reduced rule); `full` on Hex8 and Hex27 meshes (a --element-order 1 override of
/// a Hex20 config runs Hex8 at its own rule; the report names the element used).
inline ElementIntegration hex20_integration(const Mesh& mesh, ElementIntegration asked) {
  return mesh.dim == 3 && mesh.nodes_per_element == 20 ? asked : ElementIntegration::full;
}

/// The parts whose initial shear modulus is at least kStiffInclusionRatio times the softest
/// part's (the ABS rings and connectors among silicones, ~3,000×), as StiffInclusions: their
/// rotations are applied exactly by Newton's update and the predictor.
constexpr double kStiffInclusionRatio = 100.0;
StiffInclusions stiff_parts(const Mesh& mesh, const std::vector<Material>& part_materials);

/// The dofs a half model holds for a motion odd under its mirror y → −y (a twist about the axis:
/// u(x, −y, z) = −M u(x, y, z), M = diag(1, −1, 1)): on the plane such a motion has no x or z
/// component, so the "symmetry" set's x and z dofs, its y ones free; none in a full model. The
/// antisymmetric counterpart of a bending half model's u_y = 0.
std::vector<int> antisymmetric_plane_dofs(const Mesh& mesh);

/// The node set `clamped` fixed in all directions; the "symmetry" set (if any) keeps u_y = 0.
DirichletConstraints clamped_with_symmetry(const Mesh& mesh, const std::string& clamped);

struct PartPeak {
  std::string part;
  double max_principal_stretch = 1, max_principal_stress_MPa = 0, max_principal_log_strain = 0;
};
std::vector<PartPeak> part_peaks(const Mesh& mesh, const std::vector<ElementResult>& results);

/// Mass of each part (kg), `copies` times the mesh's (2 for a half model).
std::vector<std::pair<std::string, double>> part_masses_kg(const Mesh& mesh, const std::vector<Material>& materials,
                                                           double copies);

/// Position and orientation of a face: the centroid, and the rotation that best maps
/// its nodes' rest positions (about their centroid) onto the current ones (Kabsch).
struct FacePose {
  Eigen::Vector3d position_mm = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  double tilt_deg = 0;   // angle between the face's axis (z at rest) now and at rest
};
/// `mirrored`: the nodes are the y ≥ 0 half of a face symmetric about y = 0 (half
/// models); their mirror images complete it.
FacePose face_pose(const std::vector<int>& nodes, const Vector& rest, const Vector& now, bool mirrored = false);

}  // namespace softarm::fem

#include "fem/scenes/tca_end_cell.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "fem/forms/make_elastic_form.hpp"
#include "fem/forms/plane_face_form.hpp"
#include "fem/post/face_measures.hpp"
#include "fem/scenes/cell_supports.hpp"
#include "fem/scenes/solid_scene_support.hpp"

namespace softarm::fem {

EndFaceSupport tca_scene_end_support(TcaEnd end) {
  return end == TcaEnd::top ? EndFaceSupport::bonded : EndFaceSupport::free;
}

namespace {
/// The end cell's supports: a bonded end face clamped (and, in a half model, the cut's pilot held from
/// sloping across the mirror plane), or a free end face with the cut held on its rest plane, its in-plane
/// rigid motion held by `hold`'s forms; the mirror plane's normal displacement fixed either way.
DirichletConstraints end_cell_constraints(const Mesh& mesh, int pilot, bool bonded, bool half, double mu,
                                          const std::string& end_set, const std::string& cut_set, InPlaneHold& hold) {
  DirichletConstraints bc;
  if (bonded) {
    bc = clamped_with_symmetry(mesh, end_set);
    if (half) bc.fix(3 * pilot + 2);  // no slope across the mirror plane
    return bc;
  }
  if (const auto it = mesh.node_sets.find("symmetry"); it != mesh.node_sets.end())
    for (int n : it->second) bc.fix(3 * n + 1);
  for (int d = 0; d < 3; ++d) bc.fix(3 * pilot + d);  // the cut stays on its rest plane
  hold = hold_in_plane_rigid_motion(mesh, mesh.node_sets.at(cut_set), half, mu, bc);
  return bc;
}

/// What an end cell's state says: its faces' turn and the axis' elongation between them, measured on
/// both faces (a half model's completed by its mirror image).
struct EndCellFaces {
  std::vector<std::vector<int>> end_face, cut_face;
  bool half = false, bonded = false;
  bool moving_face_is_upper = false;  // the cut where the end face is bonded, else the end face
  int pilot = 0;
  double theta = 0, length_mm = 0;
  Eigen::Vector3d bend = Eigen::Vector3d::Zero();  // user frame, unit (or zero)
  FaceMeasure end_rest;

  FaceMeasure measure(const std::vector<std::vector<int>>& facets, const Vector& x) const {
    const FaceMeasure m = measure_face(facets, x);
    return half ? mirror_completed(m) : m;
  }

  TcaEndState state(double pressure_kPa, const Vector& x) const {
    TcaEndState s;
    s.pressure_kPa = pressure_kPa;
    const FaceMeasure e = measure(end_face, x), c = measure(cut_face, x);
    // The moving face's turn from rest, solver frame. The cut's plane z = z₀ + a + b·x + c·y has
    // the normal (−b, −c, 1): e_z turned by atan|(b, c)| about e_z × (−b, −c, 1) ∝ (c, −b, 0). A
    // free face's from its vector area now against at rest.
    Eigen::Vector3d turn = Eigen::Vector3d::Zero();
    if (bonded) {
      const Eigen::Vector2d slope(x[3 * pilot + 1], x[3 * pilot + 2]);
      if (slope.norm() > 0) turn = Eigen::Vector3d(slope.y(), -slope.x(), 0) * (std::atan(slope.norm()) / slope.norm());
    } else {
      const Eigen::Vector3d n0 = end_rest.vector_area.normalized(), n1 = e.vector_area.normalized();
      const Eigen::Vector3d axis = n0.cross(n1);
      if (axis.norm() > 0) turn = axis.normalized() * std::atan2(axis.norm(), n0.dot(n1));
    }
    // The upper face's rotation against the lower one's, user frame; towards the bend about e_z × bend.
    const Eigen::Vector3d phi = rotation_about_z(theta) * (moving_face_is_upper ? turn : Eigen::Vector3d(-turn));
    s.rotation_vector_rad = phi.head<2>();
    s.rotation_rad = phi.dot(Eigen::Vector3d::UnitZ().cross(bend));
    // The axis as an arc of constant curvature between the faces' centroids: chord·(φ/2)/sin(φ/2).
    const double chord = (e.centroid - c.centroid).norm(), half_turn = 0.5 * phi.norm();
    s.elongation_mm = chord * (half_turn > 1e-12 ? half_turn / std::sin(half_turn) : 1.0) - length_mm;
    return s;
  }
};

/// An unloaded end cell's path: its rest state alone.
void rest_only(TcaEndCellResult& out, const EndCellFaces& faces, const Vector& x) {
  out.states.push_back(faces.state(0.0, x));
  out.states.back().is_output = true;
  out.path.path.completed = true;
  out.path.path.reached_level = 1.0;
  out.path.path.message = "no load: the rest state";
  out.path.outcome = PathOutcome::completed;
  out.path.diagnosis = out.path.path.message;
}
}  // namespace

TcaEndCellResult run_tca_end_cell(const TcaSceneSpec& spec, TcaEnd end, int rings, EndFaceSupport face) {
  const auto t0 = std::chrono::steady_clock::now();
  validate(spec.design);
  TcaEndCellResult out;
  out.end = end;
  out.face = face;
  out.rings = rings;
  out.length_mm = rings * spec.design.actuator.pitch();
  TcaSceneSpec frame_spec = spec;
  frame_spec.gravity_m_s2 = Eigen::Vector3d::Zero();
  out.model = choose_tca_model(frame_spec);
  const Mesh mesh = mesh_tca_end(spec.design, end, rings, solid_mesh_options(spec, out.model));
  const std::vector<Material> materials = tca_part_materials(spec);
  const bool top = end == TcaEnd::top, bonded = face == EndFaceSupport::bonded;
  const std::string cut_set = top ? "bottom" : "top", end_set = top ? "top" : "bottom";

  // Positions: the mesh's nodes, then the cut plane's pilot (a, b, c) at the origin.
  const int pilot = mesh.num_nodes();
  Vector X = Vector::Zero(3 * (pilot + 1));
  X.head(3 * pilot) = flattened_positions(mesh);
  const double mu = stiffest_silicone_shear_modulus(mesh, materials);
  InPlaneHold hold;
  EnergyProblem problem(X, end_cell_constraints(mesh, pilot, bonded, out.model.half, mu, end_set, cut_set, hold));
  auto elastic = make_elastic_form(mesh, materials, VolumetricTreatment::projected_dilatation,
                                   hex20_integration(mesh, spec.integration));
  out.element_name = elastic->element_name();
  problem.add_form(elastic);
  for (const auto& form : hold.forms) problem.add_form(form);
  const double cut_z = top ? spec.design.actuator.length_mm - out.length_mm : out.length_mm;
  problem.add_form(std::make_shared<PlaneFaceForm>(mesh.node_sets.at(cut_set), pilot, cut_z, kPlanePenaltyRatio * mu));
  if (spec.newton.rotate_stiff_parts) problem.set_stiff_inclusions(stiff_parts(mesh, materials));
  LoadState load;
  load.chamber_pressure_MPa.assign(mesh.chambers.size(), 0.0);
  const ChamberLoads chambers = add_chamber_loads(
      mesh, {spec.chamber_pressure_kPa.begin(), spec.chamber_pressure_kPa.end()}, load, problem);
  problem.finalize();
  out.dofs = problem.num_dofs();

  EndCellFaces faces;
  faces.end_face = boundary_faces_in(mesh, mesh.node_sets.at(end_set));
  faces.cut_face = boundary_faces_in(mesh, mesh.node_sets.at(cut_set));
  faces.half = out.model.half;
  faces.bonded = bonded;
  // The moving face is the upper one where the end's own face is not: a bonded bottom end, a free top end.
  faces.moving_face_is_upper = bonded == !top;
  faces.pilot = pilot;
  faces.theta = out.model.frame_angle_rad;
  faces.length_mm = out.length_mm;
  faces.bend = tca_bend_direction(spec.chamber_pressure_kPa);
  if (faces.bend.norm() > 0) faces.bend.normalize();
  faces.end_rest = faces.measure(faces.end_face, X);
  Vector x = X;
  if (chambers.loaded.empty()) {
    rest_only(out, faces, x);
  } else {  // the ramp records the rest state first
    const auto record = [&](const PressureState& p, const Vector& xs, const ConvergedTangent&) {
      out.states.push_back(faces.state(p.pressure_kPa, xs));
      out.states.back().newton_iterations = p.newton_iterations;
      out.states.back().is_output = p.is_output;
    };
    out.path = run_pressure_path(problem, chambers.loaded, load, x, tca_pressure_path(spec, chambers, false, 0), record);
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace softarm::fem

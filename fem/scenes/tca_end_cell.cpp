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
  const double theta = out.model.frame_angle_rad;
  const Mesh mesh = mesh_tca_end(spec.design, end, rings, solid_mesh_options(spec, out.model));
  const std::vector<Material> materials = tca_part_materials(spec);
  const bool top = end == TcaEnd::top, bonded = face == EndFaceSupport::bonded;
  const std::string cut_set = top ? "bottom" : "top", end_set = top ? "top" : "bottom";

  // Positions: the mesh's nodes, then the cut plane's pilot (a, b, c) at the origin.
  const int pilot = mesh.num_nodes();
  Vector X = Vector::Zero(3 * (pilot + 1));
  X.head(3 * pilot) = flattened_positions(mesh);
  DirichletConstraints bc;
  if (bonded) {
    bc = clamped_with_symmetry(mesh, end_set);
    if (out.model.half) bc.fix(3 * pilot + 2);  // no slope across the mirror plane
  } else {
    if (const auto it = mesh.node_sets.find("symmetry"); it != mesh.node_sets.end())
      for (int n : it->second) bc.fix(3 * n + 1);
    for (int d = 0; d < 3; ++d) bc.fix(3 * pilot + d);  // the cut stays on its rest plane
    hold_in_plane_rigid_motion(mesh, mesh.node_sets.at(cut_set), out.model.half, bc);
  }
  EnergyProblem problem(X, bc);
  auto elastic = make_elastic_form(mesh, materials, VolumetricTreatment::projected_dilatation,
                                   hex20_integration(mesh, spec.integration));
  out.element_name = elastic->element_name();
  problem.add_form(elastic);
  const double cut_z = top ? spec.design.actuator.length_mm - out.length_mm : out.length_mm;
  const double mu = stiffest_silicone_shear_modulus(mesh, materials);
  problem.add_form(std::make_shared<PlaneFaceForm>(mesh.node_sets.at(cut_set), pilot, cut_z, kPlanePenaltyRatio * mu));
  if (spec.newton.rotate_stiff_parts) problem.set_stiff_inclusions(stiff_parts(mesh, materials));
  LoadState load;
  load.chamber_pressure_MPa.assign(mesh.chambers.size(), 0.0);
  const ChamberLoads chambers = add_chamber_loads(
      mesh, {spec.chamber_pressure_kPa.begin(), spec.chamber_pressure_kPa.end()}, load, problem);
  problem.finalize();
  out.dofs = problem.num_dofs();

  // Both faces' measures; a half model's are completed by its mirror image.
  const auto end_face = boundary_faces_in(mesh, mesh.node_sets.at(end_set));
  const auto cut_face = boundary_faces_in(mesh, mesh.node_sets.at(cut_set));
  const auto measure = [&](const std::vector<std::vector<int>>& facets, const Vector& x) {
    const FaceMeasure m = measure_face(facets, x);
    return out.model.half ? mirror_completed(m) : m;
  };
  Eigen::Vector3d bend = tca_bend_direction(spec.chamber_pressure_kPa);  // user frame
  if (bend.norm() > 0) bend.normalize();
  const FaceMeasure end_rest = measure(end_face, X);
  // The moving face (the cut where the end face is bonded, else the end face) is the upper one
  // where the end's own face is not: a bonded bottom end, a free top end.
  const bool moving_face_is_upper = bonded == !top;
  const auto state_of = [&](double pressure_kPa, const Vector& x) {
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
    s.elongation_mm = chord * (half_turn > 1e-12 ? half_turn / std::sin(half_turn) : 1.0) - out.length_mm;
    return s;
  };
  Vector x = X;
  if (chambers.loaded.empty()) {
    out.states.push_back(state_of(0.0, x));
    out.states.back().is_output = true;
    out.path.path.completed = true;
    out.path.path.reached_level = 1.0;
    out.path.path.message = "no load: the rest state";
    out.path.outcome = PathOutcome::completed;
    out.path.diagnosis = out.path.path.message;
  } else {  // the ramp records the rest state first
    out.path = run_pressure_path(problem, chambers.loaded, load, x, tca_pressure_path(spec, chambers, false, 0), [&](const PressureState& p, const Vector& xs) {
      out.states.push_back(state_of(p.pressure_kPa, xs));
      out.states.back().newton_iterations = p.newton_iterations;
      out.states.back().is_output = p.is_output;
    });
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace softarm::fem

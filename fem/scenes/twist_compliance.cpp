#include "fem/scenes/twist_compliance.hpp"

#include <cmath>

#include "fem/assembly/energy_problem.hpp"
#include "fem/forms/make_elastic_form.hpp"
#include "fem/reduced/spatial_cell_rod.hpp"
#include "fem/scenes/solid_scene_support.hpp"
#include "fem/scenes/tca_cell.hpp"
#include "fem/solver/linear_solver.hpp"

namespace softarm::fem {
namespace {
/// The scene's mesh options on the full model (a twist is not mirror-symmetric).
SolidMeshOptions full_model_options(const TcaSceneSpec& spec) {
  TcaSceneSpec full = spec;
  full.allow_symmetry = false;
  full.gravity_m_s2.setZero();
  full.chamber_pressure_kPa = {0, 0, 0};
  return solid_mesh_options(full, choose_tca_model(full));
}
}  // namespace

double face_twist_compliance(const Mesh& mesh, const std::vector<Material>& part_materials,
                             ElementIntegration integration, const std::string& held, const std::string& twisted,
                             TwistedFace twisted_face) {
  // Small enough that the rest tangent carries it (the error is O(φ) relative), large enough that
  // the reaction stands well above round-off in the stresses.
  constexpr double kTwistRad = 1e-5;
  const Vector X = flattened_positions(mesh);
  DirichletConstraints bc;
  for (int n : mesh.node_sets.at(held))
    for (int d = 0; d < 3; ++d) bc.fix(3 * n + d);
  const std::vector<int>& face = mesh.node_sets.at(twisted);
  for (int n : face) {
    bc.fix(3 * n, -kTwistRad * X[3 * n + 1]);
    bc.fix(3 * n + 1, kTwistRad * X[3 * n]);
    if (twisted_face == TwistedFace::warping_held) bc.fix(3 * n + 2);
  }
  EnergyProblem problem(X, bc);
  const auto elastic = make_elastic_form(mesh, part_materials, VolumetricTreatment::projected_dilatation,
                                         hex20_integration(mesh, integration));
  problem.add_form(elastic);
  problem.finalize();
  Vector x = X;
  problem.apply_constraints(x, 1.0);
  const Evaluation e = problem.evaluate(x, true, true);
  LinearSolver solver;
  if (!e.status.ok || solver.factorize(e.hessian) != LinearSolver::Status::positive_definite) return std::nan("");
  x -= solver.solve(e.gradient);
  // The reaction on the twisted face: the elastic force at its nodes (the gradient that
  // evaluate() zeroes at prescribed dofs).
  Vector force = Vector::Zero(x.size());
  if (!elastic->add(x, nullptr, &force, nullptr).ok) return std::nan("");
  double torque = 0;
  for (int n : face) torque += X[3 * n] * force[3 * n + 1] - X[3 * n + 1] * force[3 * n];
  return torque > 0 ? kTwistRad / torque : std::nan("");
}

double end_cell_twist_compliance(const TcaSceneSpec& spec, TcaEnd end, int rings) {
  validate(spec.design);
  const Mesh mesh = mesh_tca_end(spec.design, end, rings, full_model_options(spec));
  const bool top = end == TcaEnd::top;
  return face_twist_compliance(mesh, tca_part_materials(spec), spec.integration, top ? "top" : "bottom",
                               top ? "bottom" : "top", TwistedFace::warping_free);
}

std::vector<double> tca_rod_twist_compliances(const TcaSceneSpec& spec, const std::vector<int>& end_rings) {
  TcaSceneSpec rest = spec;
  rest.chamber_pressure_kPa = {0, 0, 0};
  rest.output_pressures_kPa.clear();
  SpatialCellPiece piece;
  piece.length_mm = spec.design.actuator.length_mm;
  piece.cap_mm = spec.design.actuator.end_cap_thickness_mm;
  for (int ring : cell_rod_rings(spec.design.actuator.ring_count)) {
    piece.cells.push_back(spatial_cell_table(run_tca_cell(rest, ring), 0));
    piece.cells.back().torsion_compliance_per_Nmm2 = 1 / cell_torsion_stiffness(rest, ring);
  }
  std::vector<double> out;
  for (int rings : end_rings) {
    SpatialCellRodSpec rod;
    rod.pieces = {piece};
    for (const TcaEnd end : {TcaEnd::bottom, TcaEnd::top}) {
      if (rings <= 0) break;
      SpatialEndTable t;  // the end's twist only: no turn, no elongation at rest
      t.at_top = end == TcaEnd::top;
      t.length_mm = rings * spec.design.actuator.pitch();
      t.level = {0, 1};
      t.rotation_rad.assign(2, Eigen::Vector2d::Zero());
      t.elongation_mm = {0, 0};
      t.twist_compliance_per_Nmm = end_cell_twist_compliance(spec, end, rings);
      rod.pieces[0].ends.push_back(t);
    }
    out.push_back(spatial_cell_rod_twist_compliance(rod, 0));
  }
  return out;
}

double tca_twist_compliance(const TcaSceneSpec& spec) {
  validate(spec.design);
  const Mesh mesh = mesh_tca(spec.design, full_model_options(spec));
  return face_twist_compliance(mesh, tca_part_materials(spec), spec.integration, "top", "bottom",
                               TwistedFace::warping_held);
}

}  // namespace softarm::fem

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
/// K with the rows and columns of the prescribed dofs replaced by the identity's.
SparseMatrix with_identity_at(SparseMatrix K, const std::vector<char>& prescribed) {
  for (int k = 0; k < K.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(K, k); it; ++it)
      if (prescribed[it.row()] || prescribed[it.col()]) it.valueRef() = it.row() == it.col() ? 1.0 : 0.0;
  return K;
}
}  // namespace

double face_twist_compliance(const Mesh& mesh, const std::vector<Material>& part_materials,
                             ElementIntegration integration, const std::string& held, const std::string& twisted,
                             TwistedFace twisted_face) {
  // The linear response at rest to a unit twist φ = 1 of the twisted face, u_p = (−Y, X) there:
  // K₀ the elastic tangent at the undeformed state (no supports), u = u_p + δ with K_ff δ = −(K₀ u_p)_f
  // over the free dofs f, and the torque the reaction's moment about the axis, T = Σ (X × f)_z over
  // the face, f = K₀ u. Exact for the tangent at rest, whatever the twist's size.
  const Vector X = flattened_positions(mesh);
  std::vector<char> prescribed(X.size(), 0);
  for (int n : mesh.node_sets.at(held))
    for (int d = 0; d < 3; ++d) prescribed[3 * n + d] = 1;
  const std::vector<int>& face = mesh.node_sets.at(twisted);
  Vector turn = Vector::Zero(X.size());
  for (int n : face) {
    turn[3 * n] = -X[3 * n + 1];
    turn[3 * n + 1] = X[3 * n];
    prescribed[3 * n] = prescribed[3 * n + 1] = 1;
    if (twisted_face == TwistedFace::warping_held) prescribed[3 * n + 2] = 1;
  }
  for (int dof : antisymmetric_plane_dofs(mesh)) prescribed[dof] = 1;
  EnergyProblem unsupported(X, {});
  unsupported.add_form(make_elastic_form(mesh, part_materials, VolumetricTreatment::projected_dilatation,
                                         hex20_integration(mesh, integration)));
  unsupported.finalize();
  const Evaluation rest = unsupported.evaluate(X, false, true);
  if (!rest.status.ok) return std::nan("");
  const SparseMatrix& K0 = rest.hessian;
  Vector rhs = -(K0 * turn);
  for (Eigen::Index i = 0; i < rhs.size(); ++i)
    if (prescribed[i]) rhs[i] = 0;
  LinearSolver solver;
  if (solver.factorize(with_identity_at(K0, prescribed)) != LinearSolver::Status::positive_definite) return std::nan("");
  const Vector u = turn + solver.solve(rhs);
  const Vector force = K0 * u;
  double torque = 0;
  for (int n : face) torque += X[3 * n] * force[3 * n + 1] - X[3 * n + 1] * force[3 * n];
  // A half model carries half the torque: its mirror image's nodes turn the face as its own do, and
  // on the plane the other half's elements add as much force across it again.
  if (mesh.node_sets.count("symmetry")) torque *= 2;
  return torque > 0 ? 1 / torque : std::nan("");
}

double end_cell_twist_compliance(const TcaSceneSpec& spec, TcaEnd end, int rings) {
  validate(spec.design);
  const Mesh mesh = mesh_tca_end(spec.design, end, rings, tca_twist_mesh_options(spec));
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
  const Mesh mesh = mesh_tca(spec.design, tca_twist_mesh_options(spec));
  return face_twist_compliance(mesh, tca_part_materials(spec), spec.integration, "top", "bottom",
                               TwistedFace::warping_held);
}

}  // namespace softarm::fem

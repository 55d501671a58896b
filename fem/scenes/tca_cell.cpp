#include "fem/scenes/tca_cell.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <memory>
#include <stdexcept>

#include <Eigen/Geometry>

#include "fem/core/elapsed_seconds.hpp"
#include "fem/core/parallel.hpp"
#include "fem/forms/make_elastic_form.hpp"
#include "fem/forms/periodic_face_form.hpp"
#include "fem/forms/plane_face_form.hpp"
#include "fem/mesh/tca_mesher.hpp"
#include "fem/scenes/cell_supports.hpp"
#include "fem/solver/linear_solver.hpp"
#include "fem/solver/load_stepper.hpp"

namespace softarm::fem {
namespace {
/// The output states a rod's table takes: those with a positive definite tangent.
bool is_table_row(const TcaCellState& s) { return s.is_output && s.bending_compliance_per_Nmm2 > 0; }

/// K⁻¹u for each u, K the tangent at xs: by CG on the path's factor (ConvergedTangent) to 10⁻¹⁰ (the
/// path's own dp/dV takes 10⁻⁵, pressure_path.cpp), else from K's own factorisation in `solver` (K
/// assembled where the path has not handed it on); false where K is not positive definite. The path
/// has just solved with K, so CG costs a few sweeps for each u where a factorisation of K costs dozens.
bool solve_with_tangent(const EnergyProblem& problem, const Vector& xs, const ConvergedTangent& tangent,
                        LinearSolver& solver, std::initializer_list<const Eigen::VectorXd*> u,
                        std::initializer_list<Eigen::VectorXd*> k_inverse_u) {
  const auto by_cg = [&] {
    if (!tangent.solve_on_path_factor) return false;
    auto out = k_inverse_u.begin();
    for (const Eigen::VectorXd* b : u)
      if (!tangent.solve_on_path_factor(*b, 1e-10, **out++)) return false;
    return true;
  };
  if (by_cg()) return true;
  Evaluation assembled;
  const SparseMatrix* K = tangent.matrix;
  if (!K) K = &(assembled = problem.evaluate(xs, false, true)).hessian;
  if (solver.factorize(*K) != LinearSolver::Status::positive_definite) return false;
  auto out = k_inverse_u.begin();
  for (const Eigen::VectorXd* b : u) **out++ = solver.solve(*b);
  return true;
}

/// The half or full model the cell is solved on: the mirror plane from the pressures and the end
/// moment (gravity has no part here); a moment keeps the plane only if it turns about its normal.
ModelChoice cell_model(const TcaSceneSpec& spec, const CellEndLoad& end_load) {
  TcaSceneSpec frame_spec = spec;
  frame_spec.gravity_m_s2 = Eigen::Vector3d::Zero();
  ModelChoice model = choose_tca_model(frame_spec);
  if (!model.half) return model;
  const double angle = model.frame_angle_rad;
  if (std::abs(end_load.moment_Nmm.dot(Eigen::Vector2d(std::cos(angle), std::sin(angle)))) <=
      1e-12 * (1 + end_load.moment_Nmm.norm()))
    return model;
  frame_spec.allow_symmetry = false;
  model = choose_tca_model(frame_spec);
  model.reason = "the end moment turns out of the mirror plane";
  return model;
}

/// One ring pitch of the 3CA as an energy problem: the mesh's nodes, then the pilot (a, b, c) of
/// the top face's plane z = a + b·x + c·y at the origin; the bottom face held in its plane, the top
/// face on the pilot's plane (PlaneFaceForm), the end loads on the pilot and the chamber pressures.
struct CellProblem {
  Mesh mesh;
  std::vector<Material> materials;
  int pilot = 0;
  double share = 1.0;  // a half model carries half of every load
  Eigen::Vector2d moment_solver_frame = Eigen::Vector2d::Zero();
  bool end_loaded = false;
  std::unique_ptr<EnergyProblem> problem;
  std::shared_ptr<PlaneFaceForm> plane;
  LoadState load;
  ChamberLoads chambers;
};

void build_cell_problem(const TcaSceneSpec& spec, int ring, const CellEndLoad& end_load, TcaCellResult& out,
                        CellProblem& cell) {
  const double theta = out.model.frame_angle_rad;
  cell.mesh = mesh_tca_cell(spec.design, ring, solid_mesh_options(spec, out.model));
  cell.materials = tca_part_materials(spec);
  const Mesh& mesh = cell.mesh;
  cell.pilot = mesh.num_nodes();
  const int pilot = cell.pilot;
  Vector X(3 * (pilot + 1));
  X.head(3 * pilot) = flattened_positions(mesh);
  X.tail<3>().setZero();
  DirichletConstraints bc;
  for (int n : mesh.node_sets.at("bottom")) bc.fix(3 * n + 2);
  if (const auto it = mesh.node_sets.find("symmetry"); it != mesh.node_sets.end())
    for (int n : it->second) bc.fix(3 * n + 1);
  const double mu = stiffest_silicone_shear_modulus(mesh, cell.materials);
  // The top face's plane follows the bottom face's centre node in x, y: the cell's energy is then
  // invariant under in-plane translation, which the bottom face's mean displacement holds.
  const InPlaneHold hold = hold_in_plane_rigid_motion(mesh, mesh.node_sets.at("bottom"), out.model.half, mu, bc);
  if (out.model.half) bc.fix(3 * pilot + 2);  // no slope across the mirror plane
  cell.problem = std::make_unique<EnergyProblem>(X, bc);
  EnergyProblem& problem = *cell.problem;
  auto elastic = make_elastic_form(mesh, cell.materials, VolumetricTreatment::projected_dilatation,
                                   hex20_integration(mesh, spec.integration));
  out.element_name = elastic->element_name();
  problem.add_form(elastic);
  for (const auto& form : hold.forms) problem.add_form(form);
  cell.plane = std::make_shared<PlaneFaceForm>(mesh.node_sets.at("top"), pilot, out.pitch_mm, kPlanePenaltyRatio * mu,
                                               hold.centre, mesh.X.row(hold.centre).head<2>().transpose());
  problem.add_form(cell.plane);
  if (spec.newton.rotate_stiff_parts) problem.set_stiff_inclusions(stiff_parts(mesh, cell.materials));
  cell.load.chamber_pressure_MPa.assign(mesh.chambers.size(), 0.0);
  // End loads on the pilot, before the pressures (DofLoadForm): the axial force on a, and the
  // moment's work M·φ with the face's rotation φ = (c, −b) about the solver's x and y
  // (z = a + b·x + c·y: turning by φ_y about +y gives b = −φ_y, by φ_x about +x gives c = φ_x).
  cell.moment_solver_frame = rotation_about_z(-theta).topLeftCorner<2, 2>() * end_load.moment_Nmm;
  const Eigen::Vector2d& m = cell.moment_solver_frame;
  cell.share = out.model.half ? 0.5 : 1.0;
  cell.end_loaded = end_load.axial_force_N != 0 || end_load.moment_Nmm.norm() > 0;
  problem.add_form(std::make_shared<DofLoadForm>(
      std::vector<int>{3 * pilot, 3 * pilot + 1, 3 * pilot + 2},
      std::vector<double>{cell.share * end_load.axial_force_N, -cell.share * m.y(), cell.share * m.x()}, cell.load));
  cell.chambers = add_chamber_loads(mesh, {spec.chamber_pressure_kPa.begin(), spec.chamber_pressure_kPa.end()},
                                    cell.load, problem);
  problem.finalize();
  out.dofs = problem.num_dofs();
}

/// Reads a converged state of the cell off its pilot: the stretch and curvature of the pitch, and
/// the end face's compliances from the tangent there.
class CellFaceReader {
 public:
  CellFaceReader(const TcaSceneSpec& spec, const CellProblem& cell, const TcaCellResult& out)
      : cell_(cell), L_(out.pitch_mm), half_(out.model.half) {
    const double theta = out.model.frame_angle_rad;
    // The scene bends away from its pressurised chambers (tca_bend_direction), solver frame.
    const Eigen::Vector2d bend =
        (rotation_about_z(-theta) * tca_bend_direction(spec.chamber_pressure_kPa)).head<2>();
    const Eigen::Vector2d& m = cell.moment_solver_frame;
    // The direction the curvature is signed by: the pressures' bend, else the end moment's, else x.
    d_ = bend.norm() > 0 ? bend : Eigen::Vector2d(m.y(), -m.x());
    d_ = d_.norm() > 0 ? d_.normalized() : Eigen::Vector2d::UnitX();
    // Solver frame → user frame (the mirror plane's turn about z), and the face's rotation
    // φ = (c, −b) = T·(b, c) about the solver's x and y, whose work-conjugate moment M gives the
    // generalised forces (F_b, F_c) = Tᵀ·M.
    to_user_ = rotation_about_z(theta).topLeftCorner<2, 2>();
    T_ << 0, 1, -1, 0;
  }

  TcaCellState state(double pressure_kPa, double volume_mm3, const Vector& xs) const {
    TcaCellState c;
    c.pressure_kPa = pressure_kPa;
    const int pilot = cell_.pilot;
    const double a = xs[3 * pilot], b = xs[3 * pilot + 1], cy = xs[3 * pilot + 2];
    c.stretch = 1 + a / L_;
    const Eigen::Vector2d towards(-b, -cy);  // the end face's normal leans this way
    c.curvature_per_mm = std::atan(towards.norm()) / L_;
    if (towards.dot(d_) < 0) c.curvature_per_mm = -c.curvature_per_mm;
    const Eigen::Vector2d phi = T_ * Eigen::Vector2d(b, cy);
    if (phi.norm() > 0) c.curvature_vector_per_mm = to_user_ * phi * (std::atan(phi.norm()) / phi.norm() / L_);
    c.chamber_volume_mm3 = volume_mm3 / cell_.share;
    c.plane_gap_mm = cell_.plane->max_gap(xs);
    return c;
  }

  /// The end face's compliance from the tangent at xs: uᵀK⁻¹u for a unit generalised force u on a
  /// (the axial force), and on (b, c) along d (a moment about the axis normal to d: turning the face
  /// towards d lowers the plane along d). dφ = uᵀK⁻¹u·share·dM, κ = φ/L; dλ = uᵀK⁻¹u·share·dN/L.
  /// In a half model d lies in the mirror plane and c is fixed. Left at zero where the tangent is
  /// not positive definite. `tangent`: K at xs where the path has it (assembled here where not).
  void add_compliance(TcaCellState& c, const Vector& xs, const ConvergedTangent& tangent, double& seconds) {
    const AddElapsedSeconds timer(seconds);  // every return below counts
    const EnergyProblem& problem = *cell_.problem;
    const auto unit = [&](int component) {
      Eigen::VectorXd u = Eigen::VectorXd::Zero(problem.num_dofs());
      u[3 * cell_.pilot + component] = 1;
      problem.zero_prescribed(u);
      return u;
    };
    const Eigen::VectorXd ua = unit(0), ub = unit(1), uc = unit(2);
    Eigen::VectorXd ka, kb, kc;
    if (!solve_with_tangent(problem, xs, tangent, solver_, {&ua, &ub, &uc}, {&ka, &kb, &kc})) return;
    Eigen::Matrix2d g;  // the plane's (b, c) under unit (F_b, F_c)
    g << ub.dot(kb), ub.dot(kc), uc.dot(kb), uc.dot(kc);
    const double share = cell_.share;
    c.bending_compliance_per_Nmm2 = d_.dot(g * d_) * share / L_;
    c.axial_compliance_per_N = ua.dot(ka) * share / L_;
    Eigen::Matrix2d k = T_ * g * T_.transpose() * share / L_;  // d(κx, κy)/d(Mx, My), solver frame
    if (half_) k(0, 0) = k(1, 1);  // about the mirror plane's normal only: isotropic (header)
    c.bending_compliance_matrix_per_Nmm2 = to_user_ * k * to_user_.transpose();
  }

 private:
  const CellProblem& cell_;
  double L_;
  bool half_;
  Eigen::Vector2d d_;
  Eigen::Matrix2d to_user_, T_;
  LinearSolver solver_;  // one symbolic analysis for every state (the pattern never changes)
};

/// No pressure: the end loads alone, in one step (the controller cuts back if it must); the rest
/// state itself where there is no load at all (Newton has no residual to scale by).
void run_end_loads_only(const TcaSceneSpec& spec, CellProblem& cell, CellFaceReader& face, Vector& x,
                        TcaCellResult& out) {
  LinearSolver solver;
  PathCallbacks callbacks;
  callbacks.apply_load = [&](double level) { cell.load.gravity_scale = level; };
  callbacks.on_converged = [](double, const Vector&, bool, const NewtonReport&) {};
  StepSettings one_step = spec.steps;
  one_step.initial_increment = one_step.max_increment = 1.0;
  if (cell.end_loaded) {
    out.path.path = follow_load_path(*cell.problem, x, solver, {1.0}, callbacks, spec.newton, one_step);
  } else {
    out.path.path.completed = true;
    out.path.path.reached_level = 1.0;
    out.path.path.message = "no load: the rest state";
  }
  out.path.outcome = out.path.path.completed ? PathOutcome::completed : PathOutcome::stalled;
  out.path.diagnosis = out.path.path.message;
  out.states.push_back(face.state(0.0, 0.0, x));
  out.states.back().newton_iterations = out.path.path.stats.newton_iterations;
  out.states.back().is_output = true;
  if (out.path.path.completed) face.add_compliance(out.states.back(), x, {}, out.compliance_s);
}
}  // namespace

TcaCellResult run_tca_cell(const TcaSceneSpec& spec, int ring, const CellEndLoad& end_load) {
  const auto t0 = std::chrono::steady_clock::now();
  validate(spec.design);
  TcaCellResult out;
  out.ring = ring;
  out.pitch_mm = spec.design.actuator.pitch();
  out.ring_centre_z_mm = ring >= 1 ? spec.design.actuator.ring_centre_z(ring) : 0.0;
  out.model = cell_model(spec, end_load);
  CellProblem cell;
  build_cell_problem(spec, ring, end_load, out, cell);
  double kg = 0;
  for (const auto& part : part_masses_kg(cell.mesh, cell.materials, 1 / cell.share)) kg += part.second;
  out.mass_per_length_kg_per_mm = kg / out.pitch_mm;

  CellFaceReader face(spec, cell, out);
  Vector x = cell.problem->reference_positions();
  if (cell.chambers.loaded.empty()) {
    run_end_loads_only(spec, cell, face, x, out);
  } else {
    const PressurePathSpec path = tca_pressure_path(spec, cell.chambers, cell.end_loaded, 0);
    out.path = run_pressure_path(*cell.problem, cell.chambers.loaded, cell.load, x, path,
                                 [&](const PressureState& s, const Vector& xs, const ConvergedTangent& tangent) {
                                   out.states.push_back(face.state(s.pressure_kPa, s.chamber_volume_mm3, xs));
                                   out.states.back().newton_iterations = s.newton_iterations;
                                   out.states.back().is_output = s.is_output;
                                   if (s.is_output) face.add_compliance(out.states.back(), xs, tangent, out.compliance_s);
                                 });
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out.assembly_s = cell.problem->assembly_seconds();
  out.evaluations = cell.problem->evaluations();
  return out;
}

namespace {
/// A ring-pitch cell with periodic faces for its torsion (periodic_face_form.hpp): the mesh, its
/// reference positions with the two pilot nodes after the mesh's, and its forms, the elastic one and
/// the periodic faces (on a half model, the pairs on the mirror plane at half weight).
struct TorsionCell {
  Mesh mesh;
  std::vector<Material> materials;
  Vector X;
  int twist_pilot = 0, bend_pilot = 0;
  std::vector<char> on_plane;  // per node: on a half model's mirror plane (all 0 in a full model)
  std::vector<std::shared_ptr<Form>> forms;
};

TorsionCell torsion_cell(const TcaSceneSpec& spec, int ring, const SolidMeshOptions& options) {
  TorsionCell c;
  c.mesh = mesh_tca_cell(spec.design, ring, options);
  c.materials = tca_part_materials(spec);
  const int n = c.mesh.num_nodes();
  c.twist_pilot = n, c.bend_pilot = n + 1;
  c.X = Vector::Zero(3 * (n + 2));
  c.X.head(3 * n) = flattened_positions(c.mesh);
  c.forms.push_back(make_elastic_form(c.mesh, c.materials, VolumetricTreatment::projected_dilatation,
                                      hex20_integration(c.mesh, spec.integration)));
  const auto pairs = facing_nodes(c.mesh.node_sets.at("top"), c.mesh.node_sets.at("bottom"), c.X, 1e-9);
  c.on_plane.assign(n, 0);
  if (const auto it = c.mesh.node_sets.find("symmetry"); it != c.mesh.node_sets.end())
    for (int node : it->second) c.on_plane[node] = 1;
  std::vector<double> weights(pairs.size(), 1.0);
  for (std::size_t k = 0; k < pairs.size(); ++k)
    if (c.on_plane[pairs[k].second]) weights[k] = 0.5;
  const double mu = stiffest_silicone_shear_modulus(c.mesh, c.materials);
  c.forms.push_back(std::make_shared<PeriodicFaceForm>(pairs, c.X, c.twist_pilot, c.bend_pilot,
                                                       kPlanePenaltyRatio * mu, weights));
  return c;
}

/// The cell's GJ at rest on the half model y ≥ 0 (chamber 1 on the mirror plane; turning the cell
/// about its axis leaves its torsion as it is). A twist is odd under that mirror, and so are the
/// pilots' t_y, φ and c: the plane is held in x and z and free across it, the even pilots t_x, a and
/// b are held, and the rigid motions left (a shift in y, turns about x and z) by the bottom face: y
/// at the node nearest the axis and at the farthest one on the plane, z at the one farthest off it.
/// The half model's energy is half the full model's for every odd motion (its plane's pairs at half
/// weight), so its φ per unit torque is twice the full model's: GJ = 2 L / (dφ/dT)_half.
double half_cell_torsion_stiffness(const TcaSceneSpec& spec, int ring) {
  TcaSceneSpec half = spec;
  half.allow_symmetry = true;
  const TorsionCell cell = torsion_cell(half, ring, tca_twist_mesh_options(half));
  const Mesh& mesh = cell.mesh;
  const std::vector<char>& on_plane = cell.on_plane;
  DirichletConstraints bc;
  for (int dof : antisymmetric_plane_dofs(mesh)) bc.fix(dof);
  bc.fix(3 * cell.twist_pilot);
  bc.fix(3 * cell.bend_pilot), bc.fix(3 * cell.bend_pilot + 1);
  const std::vector<int>& bottom = mesh.node_sets.at("bottom");
  const auto radius = [&](int node) { return mesh.X.row(node).head<2>().norm(); };
  int centre = -1, far = -1, off = -1;
  for (int b : bottom) {
    if (on_plane[b]) {
      if (centre < 0 || radius(b) < radius(centre)) centre = b;
      if (far < 0 || radius(b) > radius(far)) far = b;
    } else if (off < 0 || std::abs(mesh.X(b, 1)) > std::abs(mesh.X(off, 1))) {
      off = b;
    }
  }
  if (centre < 0 || off < 0 || centre == far) return std::nan("");
  bc.fix(3 * centre + 1), bc.fix(3 * far + 1), bc.fix(3 * off + 2);
  EnergyProblem problem(cell.X, bc);
  for (const auto& form : cell.forms) problem.add_form(form);
  problem.finalize();
  Eigen::VectorXd u = Eigen::VectorXd::Zero(problem.num_dofs()), ku;
  u[3 * cell.twist_pilot + 2] = 1;
  problem.zero_prescribed(u);
  LinearSolver solver;
  if (!solve_with_tangent(problem, cell.X, {}, solver, {&u}, {&ku})) return std::nan("");
  return 2 * spec.design.actuator.pitch() / u.dot(ku);
}
}  // namespace

std::vector<CellTorsionState> cell_torsion_along_ramp(const TcaSceneSpec& spec, int ring) {
  TcaSceneSpec full = spec;
  full.allow_symmetry = false;  // a twist is not mirror-symmetric, nor the loaded cell's state in general
  full.gravity_m_s2.setZero();
  const TorsionCell cell = torsion_cell(full, ring, solid_mesh_options(full, choose_tca_model(full)));
  const Mesh& mesh = cell.mesh;
  // The whole cell's rigid motions: the bottom node nearest the axis holds x, y, z; the one
  // farthest from it its tangential direction and z; the one most across from that its z.
  const std::vector<int>& bottom = mesh.node_sets.at("bottom");
  int centre = bottom.front(), far = bottom.front(), across = bottom.front();
  for (int b : bottom) {
    if (mesh.X.row(b).head<2>().norm() < mesh.X.row(centre).head<2>().norm()) centre = b;
    if (mesh.X.row(b).head<2>().norm() > mesh.X.row(far).head<2>().norm()) far = b;
  }
  const Eigen::Vector2d f = mesh.X.row(far).head<2>().transpose();
  for (int b : bottom) {
    const auto cross = [&](int node) { return std::abs(f.x() * mesh.X(node, 1) - f.y() * mesh.X(node, 0)); };
    if (cross(b) > cross(across)) across = b;
  }
  DirichletConstraints bc;
  for (int d = 0; d < 3; ++d) bc.fix(3 * centre + d);
  bc.fix(3 * far + (std::abs(f.x()) < std::abs(f.y()) ? 0 : 1));
  bc.fix(3 * far + 2);
  bc.fix(3 * across + 2);
  EnergyProblem problem(cell.X, bc);
  for (const auto& form : cell.forms) problem.add_form(form);
  if (full.newton.rotate_stiff_parts) problem.set_stiff_inclusions(stiff_parts(mesh, cell.materials));
  LoadState load;
  load.chamber_pressure_MPa.assign(mesh.chambers.size(), 0.0);
  const ChamberLoads chambers = add_chamber_loads(
      mesh, {full.chamber_pressure_kPa.begin(), full.chamber_pressure_kPa.end()}, load, problem);
  problem.finalize();
  // GJ = L / (dφ/dT) from the tangent at a state: φ's response to a unit torque (NaN where the tangent
  // is not positive definite).
  LinearSolver solver;  // one symbolic analysis for every state
  const auto stiffness_at = [&](const Vector& x, const ConvergedTangent& tangent) {
    Eigen::VectorXd u = Eigen::VectorXd::Zero(problem.num_dofs()), ku;
    u[3 * cell.twist_pilot + 2] = 1;
    problem.zero_prescribed(u);
    if (!solve_with_tangent(problem, x, tangent, solver, {&u}, {&ku})) return std::nan("");
    return spec.design.actuator.pitch() / u.dot(ku);
  };
  std::vector<CellTorsionState> out;
  Vector x = cell.X;
  if (chambers.loaded.empty()) {
    out.push_back({0.0, stiffness_at(x, {})});
    return out;
  }
  run_pressure_path(problem, chambers.loaded, load, x, tca_pressure_path(full, chambers, false, 0),
                    [&](const PressureState& p, const Vector& xs, const ConvergedTangent& tangent) {
                      if (p.is_output) out.push_back({p.pressure_kPa, stiffness_at(xs, tangent)});
                    });
  return out;
}

double cell_torsion_stiffness(const TcaSceneSpec& spec, int ring) {
  if (spec.allow_symmetry) return half_cell_torsion_stiffness(spec, ring);
  TcaSceneSpec rest = spec;
  rest.chamber_pressure_kPa = {0, 0, 0};
  return cell_torsion_along_ramp(rest, ring).front().stiffness_Nmm2;
}

CellTable cell_table(const TcaCellResult& cell) {
  CellTable t;
  t.z_mm = cell.ring_centre_z_mm;
  t.mass_per_length_kg_per_mm = cell.mass_per_length_kg_per_mm;
  for (const TcaCellState& s : cell.states)
    if (is_table_row(s)) {
      t.pressure_kPa.push_back(s.pressure_kPa);
      t.stretch.push_back(s.stretch);
      t.curvature_per_mm.push_back(s.curvature_per_mm);
      t.bending_compliance_per_Nmm2.push_back(s.bending_compliance_per_Nmm2);
    }
  return t;
}

SpatialCellTable spatial_cell_table(const TcaCellResult& cell, double peak_kPa) {
  SpatialCellTable t;
  t.z_mm = cell.ring_centre_z_mm;
  t.mass_per_length_kg_per_mm = cell.mass_per_length_kg_per_mm;
  for (const TcaCellState& s : cell.states)
    if (is_table_row(s)) {
      t.level.push_back(peak_kPa > 0 ? s.pressure_kPa / peak_kPa : 0.0);
      t.stretch.push_back(s.stretch);
      t.curvature_per_mm.push_back(s.curvature_vector_per_mm);
      t.bending_compliance_per_Nmm2.push_back(s.bending_compliance_matrix_per_Nmm2);
      t.axial_compliance_per_N.push_back(s.axial_compliance_per_N);
    }
  if (peak_kPa <= 0 && t.level.size() == 1) {
    t.level.push_back(1.0);
    t.stretch.push_back(t.stretch.front());
    t.curvature_per_mm.push_back(t.curvature_per_mm.front());
    t.bending_compliance_per_Nmm2.push_back(t.bending_compliance_per_Nmm2.front());
    t.axial_compliance_per_N.push_back(t.axial_compliance_per_N.front());
  }
  return t;
}

EndTable end_table(const TcaEndCellResult& end) {
  EndTable t;
  t.at_clamp = end.end == TcaEnd::top;
  t.length_mm = end.length_mm;
  // Up the ramp only: past a limit point volume control may report states at falling pressure.
  for (const TcaEndState& s : end.states)
    if (s.is_output && (t.pressure_kPa.empty() || s.pressure_kPa > t.pressure_kPa.back())) {
      t.pressure_kPa.push_back(s.pressure_kPa);
      t.rotation_rad.push_back(s.rotation_rad);
      t.elongation_mm.push_back(s.elongation_mm);
    }
  return t;
}

SpatialEndTable spatial_end_table(const TcaEndCellResult& end, double peak_kPa) {
  SpatialEndTable t;
  t.at_top = end.end == TcaEnd::top;
  t.length_mm = end.length_mm;
  // Up the ramp only, as end_table.
  for (const TcaEndState& s : end.states)
    if (s.is_output && (t.level.empty() || s.pressure_kPa > peak_kPa * t.level.back())) {
      t.level.push_back(peak_kPa > 0 ? s.pressure_kPa / peak_kPa : 0.0);
      t.rotation_rad.push_back(s.rotation_vector_rad);
      t.elongation_mm.push_back(s.elongation_mm);
    }
  if (peak_kPa <= 0 && t.level.size() == 1) {  // unloaded: its rest state holds at every level
    t.level.push_back(1.0);
    t.rotation_rad.push_back(t.rotation_rad.front());
    t.elongation_mm.push_back(t.elongation_mm.front());
  }
  return t;
}

CellRodSpec tca_cell_rod(const TcaSceneSpec& spec, const std::vector<TcaCellResult>& cells,
                         const std::vector<TcaEndCellResult>& ends) {
  CellRodSpec rod;
  rod.length_mm = spec.design.actuator.length_mm;
  rod.cap_mm = spec.design.actuator.end_cap_thickness_mm;
  for (const auto& c : cells) rod.cells.push_back(cell_table(c));
  for (const auto& e : ends) rod.ends.push_back(end_table(e));
  Eigen::Vector3d bend = tca_bend_direction(spec.chamber_pressure_kPa);
  if (bend.norm() > 0) bend.normalize();
  rod.gravity_along_bend_m_s2 = spec.gravity_m_s2.dot(bend);
  rod.gravity_along_axis_m_s2 = spec.gravity_m_s2.z();
  return rod;
}

int end_cell_rings(int asked, int ring_count) { return asked > 0 && 2 * asked < ring_count ? asked : 0; }

std::string no_end_cells_note(int asked, int ring_count) {
  return "no end cells: " + std::to_string(ring_count) + " rings, and ends through " + std::to_string(asked) +
         " rings need more than " + std::to_string(2 * asked) + "; rigid caps";
}

std::vector<int> cell_rod_rings(int ring_count) {
  std::vector<int> rings;
  if (ring_count < 1) return rings;
  for (int ring : {1, (ring_count + 1) / 2, ring_count})
    if (rings.empty() || rings.back() != ring) rings.push_back(ring);
  return rings;
}

}  // namespace softarm::fem

#pragma once
// The strain energy of a solid body with the projected-dilatation treatment,
// written once for every element family (axisymmetric quadrilaterals,
// hexahedra). See elastic_form.hpp for the formulation:
//     Π_e = ∫ W̄(C) dV + ∫ U(θ) dV,   θ = Π_h J (L² projection of J onto the element's dilatation space),
// with the pointwise U(J) for laws without the volumetric split or on request.
//
// An element family is a namespace (fem::axisym, fem::hex) that provides, for each
// element type E (kNodes, kGaussPoints, kDilatationModes, name):
//   ReferencePoint<E> (members dV and phi), and the functions found by
//   argument-dependent lookup reference_points<E>, deformation_gradient<E>,
//   add_Bt_times<E> and add_BtDB_upper<E>, working on the `Active` components
//   `Components` (row 3i+J of the row-major 9-vector of F) that vary in that family.
// Included only by the .cpp files that instantiate it.
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <array>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "fem/core/parallel.hpp"
#include "fem/forms/elastic_form.hpp"
#include "fem/materials/drucker_stability.hpp"
#include "fem/materials/principal_stress.hpp"
#include "fem/materials/symmetric_eigen3.hpp"

namespace softarm::fem {

template <class E, template <class> class Point, int Dim, int Active, const std::array<int, Active>& Components>
class ProjectedDilatationForm final : public ElasticForm {
  static constexpr int kDofs = Dim * E::kNodes, kModes = E::kDilatationModes;
  using VecA = Eigen::Matrix<double, Active, 1>;
  using MatA = Eigen::Matrix<double, Active, Active>;
  using Coordinates = Eigen::Matrix<double, E::kNodes, Dim>;
  using ElementVector = Eigen::Matrix<double, kDofs, 1>;
  using ElementMatrix = Eigen::Matrix<double, kDofs, kDofs>;
  using ModeVector = Eigen::Matrix<double, kModes, 1>;
  using ModeMatrix = Eigen::Matrix<double, kModes, kModes>;
  using Points = std::array<Point<E>, E::kGaussPoints>;

  struct ElementEnergy {
    double W = 0.0;
    ElementVector g = ElementVector::Zero();
    ElementMatrix K;  // set only where the Hessian is asked for (a line search's energies need none)
  };

  // Active components of a 3×3 tensor.
  static VecA active(const Mat3& M) {
    VecA v;
    for (int k = 0; k < Active; ++k) v[k] = M(Components[k] / 3, Components[k] % 3);
    return v;
  }

  // ∂²J/∂F∂F = J (F⁻¹_Ji F⁻¹_Lk − F⁻¹_Jk F⁻¹_Li), active block.
  static MatA jacobian_hessian(double J, const Mat3& Finv) {
    MatA H;
    for (int r = 0; r < Active; ++r) {
      const int i = Components[r] / 3, Ji = Components[r] % 3;
      for (int c = 0; c < Active; ++c) {
        const int k = Components[c] / 3, L = Components[c] % 3;
        H(r, c) = J * (Finv(Ji, i) * Finv(L, k) - Finv(Ji, k) * Finv(L, i));
      }
    }
    return H;
  }

 public:
  ProjectedDilatationForm(const Mesh& mesh, std::vector<Material> materials, VolumetricTreatment treatment)
      : mesh_(mesh), materials_(std::move(materials)), treatment_(treatment) {
    if (materials_.size() < mesh.part_names.size())
      throw std::logic_error("elastic form: a material is missing for a mesh part");
    const int ne = mesh.num_elements();
    reference_.resize(ne);
    projection_inverse_.resize(ne);
    for (int e = 0; e < ne; ++e) {
      const Coordinates Xe = nodal(mesh.X, e);
      if (!reference_points<E>(Xe, reference_[e]))
        throw std::logic_error("mesh element " + std::to_string(e) + " is inverted or degenerate");
      // L² projection onto the dilatation space: M θ = ∫ φ J dV, M = ∫ φ φᵀ dV.
      ModeMatrix M = ModeMatrix::Zero();
      for (const auto& p : reference_[e]) M += p.dV * p.phi * p.phi.transpose();
      projection_inverse_[e] = M.inverse();
    }
  }

  /// The element's name, saying "pointwise U(J)" where the volumetric energy is not projected.
  std::string element_name() const override {
    if (treatment_ != VolumetricTreatment::pointwise) return E::name;
    std::string name = E::name;
    if (const auto p1 = name.find("/P1"); p1 != std::string::npos) name.erase(p1, 3);  // no dilatation space
    const auto at = name.find("projected dilatation");
    return at == std::string::npos ? name + ", pointwise U(J)" : name.replace(at, 20, "pointwise U(J)");
  }

  void declare_pattern(SparsePattern& pattern) override {
    blocks_.resize(mesh_.num_elements());
    for (int e = 0; e < mesh_.num_elements(); ++e) {
      std::array<int, kDofs> dofs;
      for (int a = 0; a < E::kNodes; ++a)
        for (int i = 0; i < Dim; ++i) dofs[Dim * a + i] = Dim * mesh_.element(e)[a] + i;
      blocks_[e] = pattern.declare_block(dofs);
    }
  }

  FormStatus add(const Vector& x, double* value, Vector* gradient, HessianAccumulator* hessian) const override {
    const int threads = thread_count();
    if (threads == 1) return add_in_order(x, value, gradient, hessian);
    std::vector<double> values(threads, 0.0);
    std::vector<Vector> gradients(gradient ? threads : 0, Vector::Zero(x.size()));
    std::vector<FormStatus> status(threads);
    parallel_for(mesh_.num_elements(), [&](int begin, int end, int t) {
      for (int e = begin; e < end; ++e) {
        ElementEnergy E_;
        status[t] = element(e, x, gradient != nullptr, hessian != nullptr, E_);
        if (!status[t].ok) return;
        accumulate(e, E_, t, values[t], gradient ? &gradients[t] : nullptr, hessian);
      }
    });
    for (const auto& s : status)
      if (!s.ok) return s;
    for (int t = 0; t < threads; ++t) {
      if (value) *value += values[t];
      if (gradient) *gradient += gradients[t];
    }
    return FormStatus::fine();
  }

  // Element e's energy, gradient and tangent added into thread t's sums.
  void accumulate(int e, const ElementEnergy& E_, int t, double& W, Vector* g, HessianAccumulator* hessian) const {
    W += E_.W;
    const int* nodes = mesh_.element(e);
    if (g)
      for (int a = 0; a < E::kNodes; ++a) g->template segment<Dim>(Dim * nodes[a]) += E_.g.template segment<Dim>(Dim * a);
    if (hessian) hessian->add_block(t, blocks_[e], E_.K.data());
  }

  // One thread: the elements summed in their order, as the loop above does on one thread, each
  // element's energy computed here or, inside a cell rod's task once other cells have ended, by an
  // idle worker of parallel_tasks into lent_ (visit_in_order_with_help): the same bits either way.
  FormStatus add_in_order(const Vector& x, double* value, Vector* gradient, HessianAccumulator* hessian) const {
    const int n = mesh_.num_elements();
    double W = 0.0;
    Vector g = gradient ? Vector::Zero(x.size()) : Vector();
    FormStatus status = FormStatus::fine();
    if (lent_.size() != static_cast<std::size_t>(n)) lent_.resize(n);
    visit_in_order_with_help(
        n,
        [&](int e) {
          ElementEnergy E_;
          status = element(e, x, gradient != nullptr, hessian != nullptr, E_);
          if (status.ok) accumulate(e, E_, 0, W, gradient ? &g : nullptr, hessian);
          return status.ok;
        },
        [&](int e) {
          if (!lent_[e]) lent_[e] = std::make_unique<LentElement>();
          LentElement& l = *lent_[e];
          l.energy.W = 0.0;
          l.energy.g.setZero();
          l.status = element(e, x, gradient != nullptr, hessian != nullptr, l.energy);
        },
        [&](int e) {
          status = lent_[e]->status;
          if (status.ok) accumulate(e, lent_[e]->energy, 0, W, gradient ? &g : nullptr, hessian);
          return status.ok;
        });
    if (!status.ok) return status;
    if (value) *value += W;
    if (gradient) *gradient += g;
    return FormStatus::fine();
  }

  std::vector<ElementResult> element_results(const Vector& x) const override {
    std::vector<ElementResult> results(mesh_.num_elements());
    for (int e = 0; e < mesh_.num_elements(); ++e) {
      const HyperelasticLaw& law = *materials_[mesh_.part[e]].law;
      const auto xe = nodal(x, e);
      const bool projected = law.has_volumetric_split() && treatment_ == VolumetricTreatment::projected_dilatation;
      std::array<Mat3, E::kGaussPoints> F;
      std::array<double, E::kGaussPoints> J, theta;
      for (int q = 0; q < E::kGaussPoints; ++q) {
        F[q] = deformation_gradient<E>(reference_[e][q], xe);
        J[q] = F[q].determinant();
      }
      dilatations(e, J, theta);
      ElementResult& r = results[e];
      r.max_principal_cauchy_MPa = -1e300;
      r.max_principal_stretch = 0.0;
      r.min_principal_stretch = 1e300;
      double volume = 0.0, theta_sum = 0.0, valid_volume = 0.0;
      double stretch_sum = 0.0, stress_sum = 0.0, log_strain_sum = 0.0;
      for (int q = 0; q < E::kGaussPoints; ++q) {
        const double Jv = projected ? theta[q] : J[q];
        theta_sum += Jv * reference_[e][q].dV;
        volume += reference_[e][q].dV;
        const auto s = evaluate_principal(law, F[q], false);
        if (!s || !(J[q] > 0.0) || !(Jv > 0.0)) continue;
        // Stretches of F̄ = (θ/J)^(1/3) F: the kinematics the energy actually sees.
        const Mat3 Fbar = std::cbrt(Jv / J[q]) * F[q];
        const Eigen::Vector3d c = ascending_eigenvalues(Fbar.transpose() * Fbar);
        const double lmax = std::sqrt(c[2]);
        r.max_principal_stretch = std::max(r.max_principal_stretch, lmax);
        r.min_principal_stretch = std::min(r.min_principal_stretch, std::sqrt(c[0]));
        r.max_principal_log_strain = std::max(r.max_principal_log_strain, std::log(lmax));
        // Kirchhoff stress of the principal part over the volume ratio, plus the pressure U'(θ).
        Mat3 sigma = s->P * F[q].transpose() / Jv;
        if (law.has_volumetric_split()) sigma += law.volumetric(Jv).dU * Mat3::Identity();
        const double sigma_max = ascending_eigenvalues(sigma)[2];
        r.max_principal_cauchy_MPa = std::max(r.max_principal_cauchy_MPa, sigma_max);
        const double dV = reference_[e][q].dV;
        valid_volume += dV;
        stretch_sum += dV * lmax;
        stress_sum += dV * sigma_max;
        log_strain_sum += dV * std::log(lmax);
      }
      r.dilatation = theta_sum / volume;
      if (valid_volume > 0.0) {
        r.mean_principal_stretch = stretch_sum / valid_volume;
        r.mean_principal_cauchy_MPa = stress_sum / valid_volume;
        r.mean_principal_log_strain = log_strain_sum / valid_volume;
      }
    }
    return results;
  }

  int element_corner_node(int e) const override { return mesh_.element(e)[0]; }

  MaterialInstability material_instability(const Vector& x) const override {
    MaterialInstability out;
    for (int e = 0; e < mesh_.num_elements(); ++e) {
      const HyperelasticLaw& law = *materials_[mesh_.part[e]].law;
      if (!law.has_volumetric_split()) continue;
      const auto xe = nodal(x, e);
      for (int q = 0; q < E::kGaussPoints; ++q) {
        const Mat3 F = deformation_gradient<E>(reference_[e][q], xe);
        const double J = F.determinant();
        ++out.checked_points;
        if (!(J > 0.0)) continue;  // an inverted point is the element's failure, not the law's
        // Isochoric log strains ε_a = ln(λ_a J^(-1/3)), summing to zero: the state of w(ε1, ε2).
        const Eigen::Vector3d eps = 0.5 * ascending_eigenvalues(F.transpose() * F).array().log() - std::log(J) / 3.0;
        if (drucker_stable_at(law, eps[2], eps[0])) continue;
        const double stretch = std::exp(eps[2]);
        if (++out.unstable_points == 1 || stretch > out.max_stretch) {
          out.element = e;
          out.max_stretch = stretch;
          out.min_stretch = std::exp(eps[0]);
        }
      }
    }
    return out;
  }

 private:
  template <class Positions>
  Coordinates nodal(const Positions& x, int e) const {
    Coordinates xe;
    const int* nodes = mesh_.element(e);
    for (int a = 0; a < E::kNodes; ++a) {
      if constexpr (std::is_same_v<Positions, Vector>)
        xe.row(a) = x.template segment<Dim>(Dim * nodes[a]).transpose();
      else
        xe.row(a) = x.row(nodes[a]);
    }
    return xe;
  }

  // θ at the Gauss points: the L² projection of J onto the dilatation space.
  void dilatations(int e, const std::array<double, E::kGaussPoints>& J, std::array<double, E::kGaussPoints>& theta) const {
    ModeVector rhs = ModeVector::Zero();
    for (int q = 0; q < E::kGaussPoints; ++q) rhs += reference_[e][q].dV * J[q] * reference_[e][q].phi;
    const ModeVector coeffs = projection_inverse_[e] * rhs;
    for (int q = 0; q < E::kGaussPoints; ++q) theta[q] = reference_[e][q].phi.dot(coeffs);
  }

  // Energy, gradient and Hessian of one element.
  //   Volumetric part Π_v = Σ_q U(θ_q) dV_q with θ = φᵀ M⁻¹ G_J, G_J = Σ_q φ_q J_q dV_q.
  //   Gradient: Σ_q dV_q Bᵀ ∂J/∂F · s_q, with the "pressure" s_q = φ_qᵀ M⁻¹ Σ_p U'(θ_p) φ_p dV_p.
  //   Hessian: Σ_q dV_q Bᵀ s_q ∂²J/∂F² B + Gᵀ M⁻¹ D M⁻¹ G, D = Σ_q U''(θ_q) φ_q φ_qᵀ dV_q,
  //   G = Σ_q φ_q dV_q (Bᵀ ∂J/∂F)ᵀ. For a constant φ this is the mean-dilatation element.
  FormStatus element(int e, const Vector& x, bool want_gradient, bool want_hessian, ElementEnergy& out) const {
    const HyperelasticLaw& law = *materials_[mesh_.part[e]].law;
    const bool split = law.has_volumetric_split();
    const bool projected = split && treatment_ == VolumetricTreatment::projected_dilatation;
    const auto xe = nodal(x, e);
    const Points& points = reference_[e];

    std::array<Mat3, E::kGaussPoints> F;
    std::array<double, E::kGaussPoints> J, theta;
    for (int q = 0; q < E::kGaussPoints; ++q) {
      F[q] = deformation_gradient<E>(points[q], xe);
      J[q] = F[q].determinant();
      if (!(J[q] > 0.0)) return FormStatus::inverted(e, "inverted element (det F <= 0 at a Gauss point)");
    }
    ModeVector pressure = ModeVector::Zero();  // M⁻¹ Σ U'(θ) φ dV
    ModeMatrix D = ModeMatrix::Zero();
    if (projected) {
      dilatations(e, J, theta);
      ModeVector u = ModeVector::Zero();
      for (int q = 0; q < E::kGaussPoints; ++q) {
        if (!(theta[q] > 0.0)) return FormStatus::inverted(e, "inverted element (projected dilatation <= 0)");
        const VolumetricResponse U = law.volumetric(theta[q]);
        out.W += U.U * points[q].dV;
        u += U.dU * points[q].dV * points[q].phi;
        D += U.d2U * points[q].dV * points[q].phi * points[q].phi.transpose();
      }
      pressure = projection_inverse_[e] * u;
    }

    Eigen::Matrix<double, kModes, kDofs> G = Eigen::Matrix<double, kModes, kDofs>::Zero();
    // Σ_q Bᵀ D_q B dV_q, upper triangle (the kernels' row-major accumulator), mirrored after the loop.
    Eigen::Matrix<double, kDofs, kDofs, Eigen::RowMajor> K_upper;
    if (want_hessian) K_upper.setZero();
    for (int q = 0; q < E::kGaussPoints; ++q) {
      const Point<E>& p = points[q];
      const auto s = evaluate_principal<Active>(law, F[q], want_hessian, Components);  // A on the active components
      if (!s) return FormStatus::inverted(e, "inverted element (det F <= 0 at a Gauss point)");
      out.W += s->W * p.dV;
      if (!want_gradient && !want_hessian) {
        if (split && !projected) out.W += law.volumetric(J[q]).U * p.dV;
        continue;
      }
      VecA stress = active(s->P);
      MatA tangent;
      if (want_hessian) tangent = s->A;
      if (split) {
        const Mat3 Finv = F[q].inverse();
        const VecA dJ = active(Mat3(J[q] * Finv.transpose()));  // ∂J/∂F = J F⁻ᵀ
        double dU;
        if (projected) {
          dU = p.phi.dot(pressure);
          if (want_hessian) {
            ElementVector BdJ = ElementVector::Zero();  // dV Bᵀ ∂J/∂F
            add_Bt_times<E>(p, dJ, p.dV, BdJ);
            G.noalias() += p.phi * BdJ.transpose();
          }
        } else {  // pointwise U(J)
          const VolumetricResponse U = law.volumetric(J[q]);
          out.W += U.U * p.dV;
          dU = U.dU;
          if (want_hessian) tangent.noalias() += U.d2U * dJ * dJ.transpose();
        }
        stress += dU * dJ;
        if (want_hessian) tangent += dU * jacobian_hessian(J[q], Finv);
      }
      if (want_gradient) add_Bt_times<E>(p, stress, p.dV, out.g);
      if (want_hessian) add_BtDB_upper<E>(p, MatA(p.dV * tangent), K_upper);
    }
    if (projected && want_hessian) {  // the volumetric term, symmetric: its upper triangle alone
      const auto PG = (projection_inverse_[e] * G).eval();
      const auto DPG = (D * PG).eval();
      K_upper.template triangularView<Eigen::Upper>() += PG.transpose() * DPG;
    }
    if (want_hessian) out.K = K_upper.template selfadjointView<Eigen::Upper>();
    if (!std::isfinite(out.W)) return FormStatus::inverted(e, "non-finite strain energy");
    return FormStatus::fine();
  }

  const Mesh& mesh_;
  std::vector<Material> materials_;
  VolumetricTreatment treatment_;
  std::vector<Points> reference_;
  std::vector<ModeMatrix> projection_inverse_;
  std::vector<int> blocks_;
  // Elements an idle worker computed for add_in_order, kept for the next assembly (allocated as lent:
  // ~29 KB a Hex20 element, at most the mesh's). Mutable scratch, so add() on one form is for one
  // thread at a time, as every scene has it (each task assembles a problem of its own).
  struct LentElement {
    ElementEnergy energy;
    FormStatus status;
  };
  mutable std::vector<std::unique_ptr<LentElement>> lent_;
};

}  // namespace softarm::fem

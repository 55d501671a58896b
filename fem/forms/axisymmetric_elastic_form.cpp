#include "fem/forms/axisymmetric_elastic_form.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <cmath>
#include <stdexcept>

#include "fem/core/parallel.hpp"
#include "fem/materials/principal_stress.hpp"

namespace softarm::fem {
using namespace axisym;

namespace {
using Vec5 = Eigen::Matrix<double, kActive, 1>;
using Mat5 = Eigen::Matrix<double, kActive, kActive>;

// Active components of a 3×3 tensor (row 3i+J of its row-major 9-vector).
Vec5 active(const Mat3& M) {
  Vec5 v;
  for (int k = 0; k < kActive; ++k) v[k] = M(kActiveComponents[k] / 3, kActiveComponents[k] % 3);
  return v;
}

// Active block of the 9×9 tangent A(3i+J, 3k+L) = ∂P_iJ/∂F_kL.
Mat5 active(const Tangent9& A) {
  Mat5 a;
  for (int r = 0; r < kActive; ++r)
    for (int c = 0; c < kActive; ++c) a(r, c) = A(kActiveComponents[r], kActiveComponents[c]);
  return a;
}

// ∂²J/∂F∂F = J (F⁻¹_Ji F⁻¹_Lk − F⁻¹_Jk F⁻¹_Li), active block.
Mat5 jacobian_hessian(double J, const Mat3& Finv) {
  Mat5 H;
  for (int r = 0; r < kActive; ++r) {
    const int i = kActiveComponents[r] / 3, Ji = kActiveComponents[r] % 3;
    for (int c = 0; c < kActive; ++c) {
      const int k = kActiveComponents[c] / 3, L = kActiveComponents[c] % 3;
      H(r, c) = J * (Finv(Ji, i) * Finv(L, k) - Finv(Ji, k) * Finv(L, i));
    }
  }
  return H;
}

Eigen::Matrix<double, kNodes, 2> nodal(const Mesh& mesh, const int* nodes, const Vector& x) {
  Eigen::Matrix<double, kNodes, 2> xe;
  for (int a = 0; a < kNodes; ++a) xe.row(a) << x[2 * nodes[a]], x[2 * nodes[a] + 1];
  return xe;
}
}  // namespace

struct AxisymmetricElasticForm::ElementEnergy {
  double W = 0.0;
  ElementVector g = ElementVector::Zero();
  ElementMatrix K = ElementMatrix::Zero();
};

AxisymmetricElasticForm::AxisymmetricElasticForm(const Mesh& mesh, std::vector<Material> part_materials,
                                                 VolumetricTreatment treatment)
    : mesh_(mesh), materials_(std::move(part_materials)), treatment_(treatment) {
  if (mesh.dim != 2 || mesh.nodes_per_element != kNodes)
    throw std::logic_error("AxisymmetricElasticForm needs an axisymmetric Q1 mesh");
  if (materials_.size() < mesh.part_names.size())
    throw std::logic_error("AxisymmetricElasticForm: a material is missing for a mesh part");
  const int ne = mesh.num_elements();
  reference_.resize(ne);
  reference_volume_.resize(ne);
  for (int e = 0; e < ne; ++e) {
    Eigen::Matrix<double, kNodes, 2> Xe;
    for (int a = 0; a < kNodes; ++a) Xe.row(a) = mesh.X.row(mesh.element(e)[a]);
    if (!reference_points(Xe, reference_[e]))
      throw std::logic_error("mesh element " + std::to_string(e) + " is inverted or degenerate");
    reference_volume_[e] = 0.0;
    for (const auto& p : reference_[e]) reference_volume_[e] += p.dV;
  }
}

void AxisymmetricElasticForm::declare_pattern(SparsePattern& pattern) {
  blocks_.resize(mesh_.num_elements());
  for (int e = 0; e < mesh_.num_elements(); ++e) {
    std::array<int, kDofs> dofs;
    for (int a = 0; a < kNodes; ++a) {
      dofs[2 * a] = 2 * mesh_.element(e)[a];
      dofs[2 * a + 1] = 2 * mesh_.element(e)[a] + 1;
    }
    blocks_[e] = pattern.declare_block(dofs);
  }
}

FormStatus AxisymmetricElasticForm::element(int e, const Vector& x, bool want_gradient, bool want_hessian,
                                            ElementEnergy& out) const {
  const HyperelasticLaw& law = *materials_[mesh_.part[e]].law;
  const bool split = law.has_volumetric_split();
  const bool mean_dilatation = split && treatment_ == VolumetricTreatment::mean_dilatation;
  const auto xe = nodal(mesh_, mesh_.element(e), x);
  const auto& points = reference_[e];

  std::array<Mat3, kGaussPoints> F;
  std::array<double, kGaussPoints> J;
  double v = 0.0;  // current volume ∫ J dV
  for (int q = 0; q < kGaussPoints; ++q) {
    F[q] = deformation_gradient(points[q], xe);
    J[q] = F[q].determinant();
    if (!(J[q] > 0.0)) return FormStatus::inverted(e, "inverted element (det F <= 0 at a Gauss point)");
    v += J[q] * points[q].dV;
  }
  // Mean dilatation: one volumetric response per element, at J̄ = v / V.
  const double V = reference_volume_[e];
  VolumetricResponse Ubar;
  if (mean_dilatation) {
    Ubar = law.volumetric(v / V);
    out.W += V * Ubar.U;
  }

  ElementVector dv = ElementVector::Zero();  // ∂v/∂x_e (mean dilatation)
  for (int q = 0; q < kGaussPoints; ++q) {
    const ReferencePoint& p = points[q];
    const auto s = evaluate_principal(law, F[q], want_hessian);
    if (!s) return FormStatus::inverted(e, "inverted element (det F <= 0 at a Gauss point)");
    out.W += s->W * p.dV;
    if (!want_gradient && !want_hessian && !split) continue;
    const GradientOperator B = gradient_operator(p);
    Vec5 stress = active(s->P);  // ∂W/∂F, plus the volumetric part below
    Mat5 tangent;
    if (want_hessian) tangent = active(s->A);
    if (split) {
      const Mat3 Finv = F[q].inverse();
      const Vec5 dJ = active(Mat3(J[q] * Finv.transpose()));  // ∂J/∂F = J F⁻ᵀ
      // Mean dilatation: the gradient is U'(J̄) ∂v/∂x with ∂v/∂x = Σ dV Bᵀ ∂J/∂F, and the Hessian
      // U''(J̄)/V ∂v ∂vᵀ + U'(J̄) ∂²v, whose Gauss-point part U'(J̄) ∂²J/∂F² joins the tangent here.
      // Pointwise: U(J) at this point.
      const VolumetricResponse U = mean_dilatation ? Ubar : law.volumetric(J[q]);
      if (mean_dilatation) {
        dv.noalias() += p.dV * B.transpose() * dJ;
      } else {
        out.W += U.U * p.dV;
        if (want_hessian) tangent.noalias() += U.d2U * dJ * dJ.transpose();
      }
      stress += U.dU * dJ;
      if (want_hessian) tangent += U.dU * jacobian_hessian(J[q], Finv);
    }
    if (want_gradient) out.g.noalias() += p.dV * B.transpose() * stress;
    if (want_hessian) out.K.noalias() += B.transpose().lazyProduct((p.dV * tangent).lazyProduct(B));
  }
  if (mean_dilatation && want_hessian) out.K.noalias() += (Ubar.d2U / V) * dv * dv.transpose();
  if (!std::isfinite(out.W)) return FormStatus::inverted(e, "non-finite strain energy");
  return FormStatus::fine();
}

FormStatus AxisymmetricElasticForm::add(const Vector& x, double* value, Vector* gradient,
                                        HessianAccumulator* hessian) const {
  const int ne = mesh_.num_elements();
  const int threads = thread_count();
  std::vector<double> values(threads, 0.0);
  std::vector<Vector> gradients(gradient ? threads : 0, Vector::Zero(x.size()));
  std::vector<FormStatus> status(threads);
  parallel_for(ne, [&](int begin, int end, int t) {
    for (int e = begin; e < end; ++e) {
      ElementEnergy E;
      status[t] = element(e, x, gradient != nullptr, hessian != nullptr, E);
      if (!status[t].ok) return;
      values[t] += E.W;
      const int* nodes = mesh_.element(e);
      if (gradient)
        for (int a = 0; a < kNodes; ++a) {
          gradients[t][2 * nodes[a]] += E.g[2 * a];
          gradients[t][2 * nodes[a] + 1] += E.g[2 * a + 1];
        }
      if (hessian) hessian->add_block(t, blocks_[e], E.K.data());
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

std::vector<ElementResult> AxisymmetricElasticForm::element_results(const Vector& x) const {
  std::vector<ElementResult> results(mesh_.num_elements());
  for (int e = 0; e < mesh_.num_elements(); ++e) {
    const HyperelasticLaw& law = *materials_[mesh_.part[e]].law;
    const auto xe = nodal(mesh_, mesh_.element(e), x);
    const bool split = law.has_volumetric_split();
    double v = 0.0;
    for (const auto& p : reference_[e]) v += deformation_gradient(p, xe).determinant() * p.dV;
    const double Jbar = v / reference_volume_[e];
    ElementResult& r = results[e];
    r.dilatation = Jbar;
    r.max_principal_cauchy_MPa = -1e300;
    r.max_principal_stretch = 0.0;
    r.min_principal_stretch = 1e300;
    for (const auto& p : reference_[e]) {
      const Mat3 F = deformation_gradient(p, xe);
      const double J = F.determinant();
      const auto s = evaluate_principal(law, F, false);
      if (!s || !(J > 0.0) || !(Jbar > 0.0)) continue;
      // Stretches of F̄ = (J̄/J)^(1/3) F: the kinematics the energy actually sees.
      const Mat3 Fbar = split && treatment_ == VolumetricTreatment::mean_dilatation ? Mat3(std::cbrt(Jbar / J) * F) : F;
      Eigen::SelfAdjointEigenSolver<Mat3> eig(Fbar.transpose() * Fbar, Eigen::EigenvaluesOnly);
      const double lmax = std::sqrt(eig.eigenvalues()[2]);
      r.max_principal_stretch = std::max(r.max_principal_stretch, lmax);
      r.min_principal_stretch = std::min(r.min_principal_stretch, std::sqrt(eig.eigenvalues()[0]));
      r.max_principal_log_strain = std::max(r.max_principal_log_strain, std::log(lmax));
      Mat3 sigma = s->P * F.transpose() / J;
      if (split) sigma += law.volumetric(treatment_ == VolumetricTreatment::mean_dilatation ? Jbar : J).dU * Mat3::Identity();
      Eigen::SelfAdjointEigenSolver<Mat3> es(sigma, Eigen::EigenvaluesOnly);
      r.max_principal_cauchy_MPa = std::max(r.max_principal_cauchy_MPa, es.eigenvalues()[2]);
    }
  }
  return results;
}

}  // namespace softarm::fem

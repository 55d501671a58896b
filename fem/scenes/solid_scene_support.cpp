#include "fem/scenes/solid_scene_support.hpp"

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "fem/elements/reference_quadrature.hpp"
#include "fem/core/angles.hpp"

namespace softarm::fem {
namespace {
constexpr double kKgPerMm3PerGcm3 = 1e-6;

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}
}  // namespace

ModelChoice choose_mirror_model(const std::vector<double>& p, const Eigen::Vector3d& g, bool allow_symmetry) {
  ModelChoice full{"full model", "", false, 0, 0.0};
  if (!allow_symmetry) {
    full.reason = "symmetry disabled by the config";
    return full;
  }
  const double p_max = p.empty() ? 0.0 : *std::max_element(p.begin(), p.end());
  const std::size_t segments = p.size() / 3;
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const double theta = k * 2 * kPi / 3;
    const Eigen::Vector3d normal(-std::sin(theta), std::cos(theta), 0);
    bool symmetric = std::abs(g.dot(normal)) <= 1e-12 * std::max(1.0, g.norm());
    for (std::size_t s = 0; s < segments; ++s)
      symmetric = symmetric && std::abs(p[3 * s + i] - p[3 * s + j]) <= 1e-12 * std::max(1.0, p_max);
    if (!symmetric) continue;
    ModelChoice half{"half model (mirror plane through chamber " + std::to_string(k + 1) + ")", "", true, k + 1, theta};
    half.reason = "in every segment the chambers beside chamber " + std::to_string(k + 1) +
                  " are at equal pressure and gravity lies in the plane through the axis and chamber " +
                  std::to_string(k + 1) + ": geometry and loads are mirror-symmetric, so half the body gives the "
                  "whole answer with half the unknowns";
    return half;
  }
  full.reason = "no mirror plane carries both the chamber pressures (";
  for (std::size_t c = 0; c < p.size(); ++c) full.reason += (c ? ", " : "") + fmt(p[c]);
  full.reason += " kPa) and gravity";
  return full;
}

Eigen::Matrix3d rotation_about_z(double angle) {
  return Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

Vector rotated_about_z(const Vector& x, double angle) {
  const Eigen::Matrix3d R = rotation_about_z(angle);
  Vector y(x.size());
  for (Eigen::Index n = 0; n < x.size() / 3; ++n) y.segment<3>(3 * n) = R * x.segment<3>(3 * n);
  return y;
}

ChamberLoads add_chamber_loads(const Mesh& mesh, const std::vector<double>& peaks_kPa, const LoadState& load,
                               EnergyProblem& problem) {
  ChamberLoads out;
  for (double p : peaks_kPa) out.peak_kPa = std::max(out.peak_kPa, p);
  for (std::size_t c = 0; c < peaks_kPa.size() && c < mesh.chambers.size(); ++c)
    if (peaks_kPa[c] > 0 && !mesh.chambers[c].facets.empty()) {
      out.forms.push_back(std::make_shared<ChamberPressureForm>(mesh, static_cast<int>(c), load));
      problem.add_form(out.forms.back());
      out.loaded.push_back(out.forms.back().get());
      out.fractions.push_back(peaks_kPa[c] / out.peak_kPa);
    }
  return out;
}

std::vector<int> antisymmetric_plane_dofs(const Mesh& mesh) {
  std::vector<int> dofs;
  if (const auto it = mesh.node_sets.find("symmetry"); it != mesh.node_sets.end())
    for (int n : it->second) dofs.insert(dofs.end(), {3 * n, 3 * n + 2});
  return dofs;
}

DirichletConstraints clamped_with_symmetry(const Mesh& mesh, const std::string& clamped_set) {
  DirichletConstraints c;
  std::vector<char> clamped(mesh.num_nodes(), 0);
  for (int n : mesh.node_sets.at(clamped_set)) {
    clamped[n] = 1;
    for (int d = 0; d < 3; ++d) c.fix(3 * n + d);
  }
  if (const auto it = mesh.node_sets.find("symmetry"); it != mesh.node_sets.end())
    for (int n : it->second)
      if (!clamped[n]) c.fix(3 * n + 1);
  return c;
}

std::vector<PartPeak> part_peaks(const Mesh& mesh, const std::vector<ElementResult>& results) {
  std::vector<PartPeak> peaks;
  for (const auto& name : mesh.part_names) peaks.push_back({name});
  for (int e = 0; e < mesh.num_elements(); ++e) {
    const auto& r = results[e];
    PartPeak& peak = peaks[static_cast<std::size_t>(mesh.part[e])];
    peak.max_principal_stretch = std::max(peak.max_principal_stretch, r.max_principal_stretch);
    peak.max_principal_stress_MPa = std::max(peak.max_principal_stress_MPa, r.max_principal_cauchy_MPa);
    peak.max_principal_log_strain = std::max(peak.max_principal_log_strain, r.max_principal_log_strain);
  }
  return peaks;
}

std::vector<std::pair<std::string, double>> part_masses_kg(const Mesh& mesh, const std::vector<Material>& materials,
                                                           double copies) {
  const auto volumes = part_volumes_mm3(mesh);
  std::vector<std::pair<std::string, double>> masses;
  for (std::size_t i = 0; i < volumes.size(); ++i)
    masses.emplace_back(mesh.part_names[i], copies * volumes[i] * materials[i].density_g_cm3 * kKgPerMm3PerGcm3);
  return masses;
}

FacePose face_pose(const std::vector<int>& nodes, const Vector& rest, const Vector& now, bool mirrored) {
  std::vector<Eigen::Vector3d> P, Q;  // rest and current points
  for (int n : nodes) {
    P.push_back(rest.segment<3>(3 * n));
    Q.push_back(now.segment<3>(3 * n));
    if (mirrored && std::abs(P.back().y()) > 1e-9 * (1 + P.back().norm())) {  // nodes on the plane are their own image
      P.emplace_back(P.back().x(), -P.back().y(), P.back().z());
      Q.emplace_back(Q.back().x(), -Q.back().y(), Q.back().z());
    }
  }
  FacePose pose;
  Eigen::Vector3d c0 = Eigen::Vector3d::Zero(), c1 = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < P.size(); ++i) c0 += P[i], c1 += Q[i];
  c0 /= static_cast<double>(P.size());
  c1 /= static_cast<double>(P.size());
  // Kabsch: R = V diag(1, 1, det) Uᵀ from the SVD of H = Σ (X − c0)(x − c1)ᵀ.
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < P.size(); ++i) H += (P[i] - c0) * (Q[i] - c1).transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1.0 : 1.0;
  pose.rotation = svd.matrixV() * D * svd.matrixU().transpose();
  pose.position_mm = c1;
  pose.tilt_deg = std::acos(std::clamp((pose.rotation * Eigen::Vector3d::UnitZ()).z(), -1.0, 1.0)) * 180 / kPi;
  return pose;
}

StiffInclusions stiff_parts(const Mesh& mesh, const std::vector<Material>& part_materials) {
  double softest = std::numeric_limits<double>::infinity();
  for (const auto& m : part_materials) softest = std::min(softest, m.law->initial_shear_modulus());
  std::vector<int> stiff;
  for (std::size_t p = 0; p < part_materials.size(); ++p)
    if (part_materials[p].law->initial_shear_modulus() >= kStiffInclusionRatio * softest)
      stiff.push_back(static_cast<int>(p));
  return StiffInclusions::of_parts(mesh, stiff);
}

}  // namespace softarm::fem

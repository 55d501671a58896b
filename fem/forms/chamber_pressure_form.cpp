#include "fem/forms/chamber_pressure_form.hpp"

#include <array>
#include <cmath>
#include <stdexcept>

namespace softarm::fem {
namespace {
constexpr double kPi = 3.141592653589793;

struct EdgeDerivatives {
  double V;
  std::array<double, 4> g;       // ∂V/∂(r_a, z_a, r_b, z_b)
  std::array<double, 16> h;      // column-major 4×4
};

// Volume swept by edge (a → b) and its exact first and second derivatives.
EdgeDerivatives edge_volume(double ra, double za, double rb, double zb) {
  const double dz = zb - za;
  const double q = ra * ra + ra * rb + rb * rb;
  const double c = kPi / 3.0;
  EdgeDerivatives d{};
  d.V = c * dz * q;
  d.g = {c * dz * (2 * ra + rb), -c * q, c * dz * (ra + 2 * rb), c * q};
  auto H = [&](int i, int j, double v) { d.h[i + 4 * j] = v; d.h[j + 4 * i] = v; };
  H(0, 0, 2 * c * dz);
  H(0, 2, c * dz);
  H(2, 2, 2 * c * dz);
  H(0, 1, -c * (2 * ra + rb));
  H(0, 3, c * (2 * ra + rb));
  H(2, 1, -c * (ra + 2 * rb));
  H(2, 3, c * (ra + 2 * rb));
  return d;
}
}  // namespace

ChamberPressureForm::ChamberPressureForm(const Mesh& mesh, int chamber, const LoadState& load)
    : mesh_(mesh), chamber_(chamber), load_(load) {
  if (mesh.dim != 2) throw std::logic_error("ChamberPressureForm: only axisymmetric meshes so far");
  if (chamber < 0 || chamber >= static_cast<int>(mesh.chambers.size()))
    throw std::logic_error("ChamberPressureForm: no chamber " + std::to_string(chamber));
}

double ChamberPressureForm::pressure() const {
  return chamber_ < static_cast<int>(load_.chamber_pressure_MPa.size()) ? load_.chamber_pressure_MPa[chamber_] : 0.0;
}

void ChamberPressureForm::declare_pattern(SparsePattern& pattern) {
  blocks_.clear();
  for (const auto& f : mesh_.chambers[chamber_].facets) {
    const std::array<int, 4> dofs{2 * f[0], 2 * f[0] + 1, 2 * f[1], 2 * f[1] + 1};
    blocks_.push_back(pattern.declare_block(dofs));
  }
}

double ChamberPressureForm::volume(const Vector& x) const {
  double V = 0.0;
  for (const auto& f : mesh_.chambers[chamber_].facets)
    V += edge_volume(x[2 * f[0]], x[2 * f[0] + 1], x[2 * f[1]], x[2 * f[1] + 1]).V;
  return V;
}

Vector ChamberPressureForm::volume_gradient(const Vector& x) const {
  Vector g = Vector::Zero(x.size());
  for (const auto& f : mesh_.chambers[chamber_].facets) {
    const auto d = edge_volume(x[2 * f[0]], x[2 * f[0] + 1], x[2 * f[1]], x[2 * f[1] + 1]);
    const std::array<int, 4> dofs{2 * f[0], 2 * f[0] + 1, 2 * f[1], 2 * f[1] + 1};
    for (int i = 0; i < 4; ++i) g[dofs[i]] += d.g[i];
  }
  return g;
}

FormStatus ChamberPressureForm::add(const Vector& x, double* value, Vector* gradient,
                                    HessianAccumulator* hessian) const {
  const double p = pressure();
  const auto& facets = mesh_.chambers[chamber_].facets;
  for (std::size_t k = 0; k < facets.size(); ++k) {
    const auto& f = facets[k];
    const std::array<int, 4> dofs{2 * f[0], 2 * f[0] + 1, 2 * f[1], 2 * f[1] + 1};
    const auto d = edge_volume(x[dofs[0]], x[dofs[1]], x[dofs[2]], x[dofs[3]]);
    if (value) *value -= p * d.V;
    if (gradient)
      for (int i = 0; i < 4; ++i) (*gradient)[dofs[i]] -= p * d.g[i];
    if (hessian && p != 0.0) {
      std::array<double, 16> h;
      for (int i = 0; i < 16; ++i) h[i] = -p * d.h[i];
      hessian->add_block(0, blocks_[k], h.data());
    }
  }
  return FormStatus::fine();
}

}  // namespace softarm::fem

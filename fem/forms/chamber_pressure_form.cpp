#include "fem/forms/chamber_pressure_form.hpp"

#include <array>
#include <cmath>
#include <stdexcept>

namespace softarm::fem {
namespace {
constexpr double kPi = 3.141592653589793;
constexpr int kMaxNodes = 3;

// Edge dofs (r_0, z_0, r_1, z_1, ...) in the facet's node order.
struct EdgeDerivatives {
  int n = 0;                                     // nodes on the edge
  double V = 0.0;
  std::array<double, 2 * kMaxNodes> g{};         // ∂V/∂(r_a, z_a)
  std::array<double, 4 * kMaxNodes * kMaxNodes> h{};  // column-major (2n)×(2n)
};

// Lagrange shape functions on s ∈ [−1, 1] with nodes in facet order: ends first, then the middle.
void edge_shape(int n, double s, double* N, double* dN) {
  if (n == 2) {
    N[0] = 0.5 * (1 - s), N[1] = 0.5 * (1 + s);
    dN[0] = -0.5, dN[1] = 0.5;
  } else {  // facet (a, mid, b)
    N[0] = 0.5 * s * (s - 1), N[1] = 1 - s * s, N[2] = 0.5 * s * (s + 1);
    dN[0] = s - 0.5, dN[1] = -2 * s, dN[2] = s + 0.5;
  }
}

// V_edge = ∫ π r² z' ds and its exact first and second derivatives.
EdgeDerivatives edge_volume(const Vector& x, const std::vector<int>& nodes) {
  EdgeDerivatives d;
  d.n = static_cast<int>(nodes.size());
  const int m = 2 * d.n;
  // n-point Gauss–Legendre integrates the degree-(3n−4) integrand exactly.
  static const double g2[2] = {-0.5773502691896257, 0.5773502691896257}, w2[2] = {1, 1};
  static const double g3[3] = {-0.7745966692414834, 0.0, 0.7745966692414834}, w3[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  const double* gs = d.n == 2 ? g2 : g3;
  const double* ws = d.n == 2 ? w2 : w3;
  for (int q = 0; q < d.n; ++q) {
    double N[kMaxNodes], dN[kMaxNodes], r = 0, dz = 0;
    edge_shape(d.n, gs[q], N, dN);
    for (int a = 0; a < d.n; ++a) {
      r += N[a] * x[2 * nodes[a]];
      dz += dN[a] * x[2 * nodes[a] + 1];
    }
    const double w = ws[q] * kPi;
    d.V += w * r * r * dz;
    for (int a = 0; a < d.n; ++a) {
      d.g[2 * a] += w * 2 * r * N[a] * dz;  // ∂/∂r_a
      d.g[2 * a + 1] += w * r * r * dN[a];  // ∂/∂z_a
      for (int b = 0; b < d.n; ++b) {
        d.h[2 * a + m * (2 * b)] += w * 2 * N[a] * N[b] * dz;       // ∂²/∂r_a∂r_b
        d.h[2 * a + m * (2 * b + 1)] += w * 2 * r * N[a] * dN[b];   // ∂²/∂r_a∂z_b
        d.h[2 * b + 1 + m * (2 * a)] += w * 2 * r * N[a] * dN[b];   // ∂²/∂z_b∂r_a
      }
    }
  }
  return d;
}
}  // namespace

ChamberPressureForm::ChamberPressureForm(const Mesh& mesh, int chamber, const LoadState& load)
    : mesh_(mesh), chamber_(chamber), load_(load) {
  if (mesh.dim != 2) throw std::logic_error("ChamberPressureForm: only axisymmetric meshes so far");
  if (chamber < 0 || chamber >= static_cast<int>(mesh.chambers.size()))
    throw std::logic_error("ChamberPressureForm: no chamber " + std::to_string(chamber));
  for (const auto& f : mesh.chambers[chamber].facets)
    if (f.size() < 2 || f.size() > kMaxNodes) throw std::logic_error("ChamberPressureForm: edges need 2 or 3 nodes");
}

double ChamberPressureForm::pressure() const {
  return chamber_ < static_cast<int>(load_.chamber_pressure_MPa.size()) ? load_.chamber_pressure_MPa[chamber_] : 0.0;
}

void ChamberPressureForm::declare_pattern(SparsePattern& pattern) {
  blocks_.clear();
  for (const auto& f : mesh_.chambers[chamber_].facets) {
    std::vector<int> dofs;
    for (int n : f) dofs.insert(dofs.end(), {2 * n, 2 * n + 1});
    blocks_.push_back(pattern.declare_block(dofs));
  }
}

double ChamberPressureForm::volume(const Vector& x) const {
  double V = 0.0;
  for (const auto& f : mesh_.chambers[chamber_].facets) V += edge_volume(x, f).V;
  return V;
}

Vector ChamberPressureForm::volume_gradient(const Vector& x) const {
  Vector g = Vector::Zero(x.size());
  for (const auto& f : mesh_.chambers[chamber_].facets) {
    const auto d = edge_volume(x, f);
    for (int a = 0; a < d.n; ++a) g.segment<2>(2 * f[a]) += Eigen::Vector2d(d.g[2 * a], d.g[2 * a + 1]);
  }
  return g;
}

FormStatus ChamberPressureForm::add(const Vector& x, double* value, Vector* gradient,
                                    HessianAccumulator* hessian) const {
  const double p = pressure();
  const auto& facets = mesh_.chambers[chamber_].facets;
  for (std::size_t k = 0; k < facets.size(); ++k) {
    const auto& f = facets[k];
    const auto d = edge_volume(x, f);
    if (value) *value -= p * d.V;
    if (gradient)
      for (int a = 0; a < d.n; ++a) gradient->segment<2>(2 * f[a]) -= p * Eigen::Vector2d(d.g[2 * a], d.g[2 * a + 1]);
    if (hessian && p != 0.0) {
      std::array<double, 4 * kMaxNodes * kMaxNodes> h;
      for (int i = 0; i < 4 * d.n * d.n; ++i) h[i] = -p * d.h[i];
      hessian->add_block(0, blocks_[k], h.data());
    }
  }
  return FormStatus::fine();
}

}  // namespace softarm::fem

#include "fem/forms/chamber_pressure_form.hpp"

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <stdexcept>

#include "fem/elements/axisymmetric_quad.hpp"
#include "fem/elements/serendipity_quad.hpp"
#include "fem/core/angles.hpp"

namespace softarm::fem {
namespace {
constexpr int kMaxDofs = 27;  // a 9-node facet in 3D

// A facet's volume contribution and its exact derivatives with respect to its dofs
// (dim per node, in the facet's node order).
struct FacetDerivatives {
  int dofs = 0;
  double V = 0.0;
  std::array<double, kMaxDofs> g{};             // ∂V/∂x_a,i
  std::array<double, kMaxDofs * kMaxDofs> h{};  // column-major dofs × dofs
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

// Axisymmetric edge: V_edge = ∫ π r² z' ds and its exact first and second derivatives.
FacetDerivatives edge_volume(const Vector& x, const std::vector<int>& nodes) {
  FacetDerivatives d;
  const int n = static_cast<int>(nodes.size());
  const int m = d.dofs = 2 * n;
  // n-point Gauss–Legendre integrates the degree-(3n−4) integrand exactly.
  static const double g2[2] = {-0.5773502691896257, 0.5773502691896257}, w2[2] = {1, 1};
  static const double g3[3] = {-0.7745966692414834, 0.0, 0.7745966692414834}, w3[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  const double* gs = n == 2 ? g2 : g3;
  const double* ws = n == 2 ? w2 : w3;
  for (int q = 0; q < n; ++q) {
    double N[3], dN[3], r = 0, dz = 0;
    edge_shape(n, gs[q], N, dN);
    for (int a = 0; a < n; ++a) {
      r += N[a] * x[2 * nodes[a]];
      dz += dN[a] * x[2 * nodes[a] + 1];
    }
    const double w = ws[q] * kPi;
    d.V += w * r * r * dz;
    for (int a = 0; a < n; ++a) {
      d.g[2 * a] += w * 2 * r * N[a] * dz;  // ∂/∂r_a
      d.g[2 * a + 1] += w * r * r * dN[a];  // ∂/∂z_a
      for (int b = 0; b < n; ++b) {
        d.h[2 * a + m * (2 * b)] += w * 2 * N[a] * N[b] * dz;       // ∂²/∂r_a∂r_b
        d.h[2 * a + m * (2 * b + 1)] += w * 2 * r * N[a] * dN[b];   // ∂²/∂r_a∂z_b
        d.h[2 * b + 1 + m * (2 * a)] += w * 2 * r * N[a] * dN[b];   // ∂²/∂z_b∂r_a
      }
    }
  }
  return d;
}

// [v]×, the matrix of v × ·.
Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d S;
  S << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return S;
}

// 3D quadrilateral facet (Q = Quad4, Quad8 or Quad9 shape functions and its exact Gauss rule):
// V_f = (1/3) ∫ det[x, x_s, x_t] ds dt. det is trilinear in (x, x_s, x_t), so
//   ∂V/∂x_a = (1/3) ∫ N_a (x_s × x_t) + N_a,s (x_t × x) + N_a,t (x × x_s),
//   ∂²V/∂x_a∂x_b = (1/3) ∫ (N_a,s N_b − N_a N_b,s)[x_t]× + (N_a N_b,t − N_a,t N_b)[x_s]×
//                          + (N_a,t N_b,s − N_a,s N_b,t)[x]×.
template <class Q>
FacetDerivatives quad_facet_volume(const Vector& x, const std::vector<int>& nodes) {
  constexpr int n = Q::kNodes, m = 3 * n;
  FacetDerivatives d;
  d.dofs = m;
  for (int q = 0; q < Q::kGaussPoints; ++q) {
    double s, t, w, N[n], Ns[n], Nt[n];
    Q::gauss_point(q, s, t, w);
    Q::shape(s, t, N, Ns, Nt);
    Eigen::Vector3d p = Eigen::Vector3d::Zero(), ps = p, pt = p;
    for (int a = 0; a < n; ++a) {
      const Eigen::Vector3d xa = x.segment<3>(3 * nodes[a]);
      p += N[a] * xa, ps += Ns[a] * xa, pt += Nt[a] * xa;
    }
    const double w3 = w / 3.0;
    const Eigen::Vector3d ns = ps.cross(pt), n_ts = pt.cross(p), n_ps = p.cross(ps);
    const Eigen::Matrix3d S = skew(p), Ss = skew(ps), St = skew(pt);
    d.V += w3 * p.dot(ns);
    for (int a = 0; a < n; ++a) {
      const Eigen::Vector3d ga = w3 * (N[a] * ns + Ns[a] * n_ts + Nt[a] * n_ps);
      for (int i = 0; i < 3; ++i) d.g[3 * a + i] += ga[i];
      for (int b = 0; b < n; ++b) {
        const Eigen::Matrix3d H = w3 * ((Ns[a] * N[b] - N[a] * Ns[b]) * St + (N[a] * Nt[b] - Nt[a] * N[b]) * Ss +
                                        (Nt[a] * Ns[b] - Ns[a] * Nt[b]) * S);
        for (int j = 0; j < 3; ++j)
          for (int i = 0; i < 3; ++i) d.h[(3 * a + i) + m * (3 * b + j)] += H(i, j);
      }
    }
  }
  return d;
}

// A lid (mesh.hpp, chamber_lids.hpp): the cone from the loop's centroid c = (1/m) Σ x_l over the
// loop's edges, the last back to the first. A straight edge (a, b) adds the signed volume of its
// triangle's cone from the origin, T = (1/6) det[c, a, b]. On a quadratic mesh the loop runs
// corner, midside, corner, …, and its edges are the facets' parabolas γ(s) = Σ N_i(s) x_i through
// (a, m, b); the cone over γ adds (1/6) ∫ det[c, γ, γ'] ds = Σ_ij (1/6) M_ij det[c, x_i, x_j] with
// M_ij = ∫₋₁¹ N_i N_j' ds, whose antisymmetric part gives
//   (1/6) [ (4/3) det[c, a, m] + (4/3) det[c, m, b] − (1/3) det[c, a, b] ]
// (Simpson's weights; a straight edge with m at its middle gives det[c, a, b] back). Without it
// the fan of chords leaves slivers open between the chords and the facets' curved edges, and the
// volume is not a volume (it changes under a rigid translation; ~1 % of a chamber's section).
// An open chain (a half model's, ending on the mirror plane) closes with a straight edge.
// Every term is trilinear in (c, a, b):
//   ∂T/∂c = (a×b)/6, ∂T/∂a = (b×c)/6, ∂T/∂b = (c×a)/6,
//   ∂²T/∂c∂a = −[b]×/6, ∂²T/∂c∂b = [a]×/6, ∂²T/∂a∂b = −[c]×/6 (and their transposes),
// and c's share goes to every loop node with weight 1/m.
struct LidDerivatives {
  double V = 0.0;
  Eigen::VectorXd g;  // 3 per loop node
  Eigen::MatrixXd h;
};

/// The lid's cone terms: (i, j, w) adds w·(1/6) det[c, x_loop[i], x_loop[j]].
struct LidTerm {
  int i, j;
  double w;
};
std::vector<LidTerm> lid_terms(int m, bool quadratic) {
  std::vector<LidTerm> terms;
  int i = 0;
  if (quadratic)  // closed loops: every edge a parabola; open chains: the last corner closes straight
    for (; i + 2 <= m; i += 2) {
      const int a = i, mid = i + 1, b = (i + 2) % m;
      terms.push_back({a, mid, 4.0 / 3});
      terms.push_back({mid, b, 4.0 / 3});
      terms.push_back({a, b, -1.0 / 3});
    }
  for (; i < m; ++i) terms.push_back({i, (i + 1) % m, 1.0});
  return terms;
}

LidDerivatives lid_volume(const Vector& x, const std::vector<int>& loop, bool quadratic, bool want_hessian) {
  const int m = static_cast<int>(loop.size());
  LidDerivatives d;
  d.g = Eigen::VectorXd::Zero(3 * m);
  if (want_hessian) d.h = Eigen::MatrixXd::Zero(3 * m, 3 * m);
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int n : loop) c += x.segment<3>(3 * n);
  c /= m;
  Eigen::Vector3d gc = Eigen::Vector3d::Zero();   // ∂V/∂c
  Eigen::MatrixXd hc = Eigen::MatrixXd::Zero(3, 3 * m);  // ∂²V/∂c∂x_l through the terms' a and b
  for (const LidTerm& t : lid_terms(m, quadratic)) {
    const int i = t.i, j = t.j;
    const double w = t.w / 6;
    const Eigen::Vector3d a = x.segment<3>(3 * loop[i]), b = x.segment<3>(3 * loop[j]);
    d.V += w * c.dot(a.cross(b));
    gc += w * a.cross(b);
    d.g.segment<3>(3 * i) += w * b.cross(c);
    d.g.segment<3>(3 * j) += w * c.cross(a);
    if (!want_hessian) continue;
    hc.block<3, 3>(0, 3 * i) -= w * skew(b);
    hc.block<3, 3>(0, 3 * j) += w * skew(a);
    d.h.block<3, 3>(3 * i, 3 * j) -= w * skew(c);
    d.h.block<3, 3>(3 * j, 3 * i) += w * skew(c);
  }
  for (int l = 0; l < m; ++l) d.g.segment<3>(3 * l) += gc / m;
  if (want_hessian)
    for (int l = 0; l < m; ++l) {
      // c depends on every node: ∂²V/∂x_l∂x_k gains (1/m)(∂²V/∂c∂x_k) and its transpose.
      d.h.block(3 * l, 0, 3, 3 * m) += hc / m;
      d.h.block(0, 3 * l, 3 * m, 3) += hc.transpose() / m;
    }
  return d;
}

FacetDerivatives facet_volume(int dim, const Vector& x, const std::vector<int>& nodes) {
  if (dim == 2) return edge_volume(x, nodes);
  if (nodes.size() == 4) return quad_facet_volume<axisym::Quad4>(x, nodes);
  return nodes.size() == 8 ? quad_facet_volume<Quad8>(x, nodes) : quad_facet_volume<axisym::Quad9>(x, nodes);
}
}  // namespace

ChamberPressureForm::ChamberPressureForm(const Mesh& mesh, int chamber, const LoadState& load)
    : mesh_(mesh), chamber_(chamber), load_(load) {
  if (mesh.dim != 2 && mesh.dim != 3) throw std::logic_error("ChamberPressureForm: meshes are 2D or 3D");
  if (chamber < 0 || chamber >= static_cast<int>(mesh.chambers.size()))
    throw std::logic_error("ChamberPressureForm: no chamber " + std::to_string(chamber));
  for (const auto& f : mesh.chambers[chamber].facets) {
    const bool ok = mesh.dim == 2 ? (f.size() == 2 || f.size() == 3) : (f.size() == 4 || f.size() == 8 || f.size() == 9);
    if (!ok) throw std::logic_error("ChamberPressureForm: facets need 2 or 3 nodes (2D), 4, 8 or 9 nodes (3D)");
  }
  for (const auto& lid : mesh.chambers[chamber].lids)
    if (mesh.dim != 3 || lid.size() < 2) throw std::logic_error("ChamberPressureForm: lids are 3D loops of >= 2 nodes");
}

double ChamberPressureForm::pressure() const {
  return chamber_ < static_cast<int>(load_.chamber_pressure_MPa.size()) ? load_.chamber_pressure_MPa[chamber_] : 0.0;
}

void ChamberPressureForm::declare_pattern(SparsePattern& pattern) {
  blocks_.clear();
  for (const auto& f : mesh_.chambers[chamber_].facets) {
    std::vector<int> dofs;
    for (int n : f)
      for (int i = 0; i < mesh_.dim; ++i) dofs.push_back(mesh_.dim * n + i);
    blocks_.push_back(pattern.declare_block(dofs));
  }
  lid_blocks_.clear();
  for (const auto& lid : mesh_.chambers[chamber_].lids) {
    std::vector<int> dofs;
    for (int n : lid)
      for (int i = 0; i < 3; ++i) dofs.push_back(3 * n + i);
    lid_blocks_.push_back(pattern.declare_block(dofs));
  }
}

double ChamberPressureForm::volume(const Vector& x) const {
  double V = 0.0;
  for (const auto& f : mesh_.chambers[chamber_].facets) V += facet_volume(mesh_.dim, x, f).V;
  for (const auto& lid : mesh_.chambers[chamber_].lids) V += lid_volume(x, lid, quadratic_lids(), false).V;
  return V;
}

Vector ChamberPressureForm::volume_gradient(const Vector& x) const {
  Vector g = Vector::Zero(x.size());
  const int dim = mesh_.dim;
  for (const auto& f : mesh_.chambers[chamber_].facets) {
    const auto d = facet_volume(dim, x, f);
    for (int k = 0; k < d.dofs; ++k) g[dim * f[k / dim] + k % dim] += d.g[k];
  }
  for (const auto& lid : mesh_.chambers[chamber_].lids) {
    const auto d = lid_volume(x, lid, quadratic_lids(), false);
    for (int k = 0; k < d.g.size(); ++k) g[3 * lid[k / 3] + k % 3] += d.g[k];
  }
  return g;
}

FormStatus ChamberPressureForm::add(const Vector& x, double* value, Vector* gradient,
                                    HessianAccumulator* hessian) const {
  const double p = pressure();
  const int dim = mesh_.dim;
  const auto& facets = mesh_.chambers[chamber_].facets;
  for (std::size_t k = 0; k < facets.size(); ++k) {
    const auto& f = facets[k];
    const auto d = facet_volume(dim, x, f);
    if (value) *value -= p * d.V;
    if (gradient)
      for (int i = 0; i < d.dofs; ++i) (*gradient)[dim * f[i / dim] + i % dim] -= p * d.g[i];
    if (hessian && p != 0.0) {
      std::array<double, kMaxDofs * kMaxDofs> h;
      for (int i = 0; i < d.dofs * d.dofs; ++i) h[i] = -p * d.h[i];
      hessian->add_block(0, blocks_[k], h.data());
    }
  }
  const auto& lids = mesh_.chambers[chamber_].lids;
  for (std::size_t k = 0; k < lids.size(); ++k) {
    const auto d = lid_volume(x, lids[k], quadratic_lids(), hessian && p != 0.0);
    if (value) *value -= p * d.V;
    if (gradient)
      for (int i = 0; i < d.g.size(); ++i) (*gradient)[3 * lids[k][i / 3] + i % 3] -= p * d.g[i];
    if (hessian && p != 0.0) {
      const Eigen::MatrixXd h = -p * d.h;
      hessian->add_block(0, lid_blocks_[k], h.data());
    }
  }
  return FormStatus::fine();
}

}  // namespace softarm::fem

#pragma once
// The hexahedra's hot loop: the upper triangle of an element's K += Bᵀ D B at one Gauss point, for
// B the gradient operator of F's nine components (hexahedron.hpp, gradient_operator: dof (a, i)
// touches components 3i + J with weight ∂N_a/∂X_J) and D = ∂P/∂F there, on raw arrays:
//
//   DB = D B (9 × 3n, row-major), then K(3a + i, c) += a0·DB(3i, c) + a1·DB(3i+1, c) + a2·DB(3i+2, c)
//   for c ≥ 3a + i, (a0, a1, a2) = ∂N_a/∂X.
//
// Each entry is that sum of those products in that order, with no fused multiply-add and no
// reassociation, on every instruction set: a design must not change with the processor (test "The
// hexahedra's BᵀDB kernel"). Two instances: AVX (four doubles an instruction) and SSE2 (two).
namespace softarm::fem::hex::detail {

/// F's nine components (row-major): the rows of B and of D.
inline constexpr int kGradientComponents = 9;

/// DB = D B, 9 × 3n row-major, from ∂N/∂X (n × 3, column-major) and D (9 × 9, column-major).
template <int n>
[[gnu::always_inline]] inline void multiply_D_B(const double* dN, const double* D, double* DB) {
  constexpr int m = 3 * n;
  for (int r = 0; r < kGradientComponents; ++r)
    for (int k = 0; k < 3; ++k) {
      const double d0 = D[r + 9 * (3 * k)], d1 = D[r + 9 * (3 * k + 1)], d2 = D[r + 9 * (3 * k + 2)];
      double* out = DB + r * m + k;
      for (int b = 0; b < n; ++b) out[3 * b] = d0 * dN[b] + d1 * dN[b + n] + d2 * dN[b + 2 * n];
    }
}

/// Row 3a + i of K from its diagonal on: plain loops, which the compiler vectorises.
template <int n>
[[gnu::always_inline]] inline void add_row(const double* dN, const double* DB, int a, int i, double* K) {
  constexpr int m = 3 * n;
  const double a0 = dN[a], a1 = dN[a + n], a2 = dN[a + 2 * n];
  const int row = 3 * a + i;
  const double *x = DB + 3 * i * m, *y = x + m, *z = y + m;
  double* k = K + row * m;
  for (int c = row; c < m; ++c) k[c] += a0 * x[c] + a1 * y[c] + a2 * z[c];
}

/// W doubles, loaded and stored at any address (may_alias: they are read from and written to double
/// arrays).
template <int W>
struct Lanes;
template <>
struct Lanes<2> {
  typedef double type __attribute__((vector_size(16), aligned(8), may_alias));
};
template <>
struct Lanes<4> {
  typedef double type __attribute__((vector_size(32), aligned(8), may_alias));
};

/// Rows 3a + i of four nodes a0 … a0 + 3 at once, W columns a pass: the three rows of DB that
/// component i reads are loaded once for four rows of K instead of once for each, which makes the
/// loop bound by its arithmetic rather than by its loads (a scratch timing of Hex20's 27 points:
/// 14.9 → 11.4 µs an element with AVX). Each row starts at the multiple of W at or below its
/// diagonal, so up to W − 1 entries left of it, in the lower triangle, are written too: the kernel's
/// lower triangle is scratch (the form mirrors the upper one). Needs 3n a multiple of W.
template <int n, int W>
[[gnu::always_inline]] inline void add_four_rows(const double* dN, const double* DB, int a0, int i, double* K) {
  using V = typename Lanes<W>::type;
  constexpr int m = 3 * n;
  static_assert(m % W == 0, "whole passes of W columns to the row's end");
  const double *x = DB + 3 * i * m, *y = x + m, *z = y + m;
  V g0[4], g1[4], g2[4];  // ∂N_a/∂X of the four nodes, in every lane
  for (int j = 0; j < 4; ++j) {
    g0[j] = V{} + dN[a0 + j];
    g1[j] = V{} + dN[a0 + j + n];
    g2[j] = V{} + dN[a0 + j + 2 * n];
  }
  const int first = 3 * a0 + i;                // row of node a0; the others follow 3 apart
  const int shared = (first + 9) & ~(W - 1);   // from here on the four rows run together
  for (int j = 0; j < 3; ++j)
    for (int c = (first + 3 * j) & ~(W - 1); c < shared; c += W) {
      V* k = reinterpret_cast<V*>(K + (first + 3 * j) * m + c);
      *k = *k + (g0[j] * *reinterpret_cast<const V*>(x + c) + g1[j] * *reinterpret_cast<const V*>(y + c) +
                 g2[j] * *reinterpret_cast<const V*>(z + c));
    }
  for (int c = shared; c < m; c += W) {
    const V xc = *reinterpret_cast<const V*>(x + c), yc = *reinterpret_cast<const V*>(y + c),
            zc = *reinterpret_cast<const V*>(z + c);
    for (int j = 0; j < 4; ++j) {
      V* k = reinterpret_cast<V*>(K + (first + 3 * j) * m + c);
      *k = *k + (g0[j] * xc + g1[j] * yc + g2[j] * zc);
    }
  }
}

/// The kernel W doubles wide: four rows at a pass where the node count allows (Hex8, Hex20),
/// row by row otherwise (Hex27).
template <int n, int W>
[[gnu::always_inline]] inline void add_BtDB_upper_lanes(const double* dN, const double* D, double* K) {
  double DB[kGradientComponents * 3 * n];
  multiply_D_B<n>(dN, D, DB);
  for (int i = 0; i < 3; ++i) {
    if constexpr (n % 4 == 0) {
      for (int a = 0; a < n; a += 4) add_four_rows<n, W>(dN, DB, a, i, K);
    } else {
      for (int a = 0; a < n; ++a) add_row<n>(dN, DB, a, i, K);
    }
  }
}

#if defined(__x86_64__) || defined(__i386__)
#define SOFTARM_KERNEL_AVX 1
/// The kernel for processors with AVX.
template <int n>
[[gnu::target("avx")]] void add_BtDB_upper_avx(const double* dN, const double* D, double* K) {
  add_BtDB_upper_lanes<n, 4>(dN, D, K);
}
#endif
/// The kernel for any processor (on x86-64, SSE2).
template <int n>
void add_BtDB_upper_sse2(const double* dN, const double* D, double* K) {
  add_BtDB_upper_lanes<n, 2>(dN, D, K);
}

/// Whether this processor runs AVX instructions (asked once).
inline bool processor_has_avx() {
#ifdef SOFTARM_KERNEL_AVX
  static const bool has = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx") != 0;
  }();
  return has;
#else
  return false;
#endif
}

}  // namespace softarm::fem::hex::detail

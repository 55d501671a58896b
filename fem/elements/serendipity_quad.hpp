#pragma once
// The 8-node serendipity quadrilateral on (s, t) ∈ [−1, 1]², the face of a
// Hex20 (hexahedron.hpp): chamber walls and measured faces of serendipity
// meshes are integrated with it. Node order as the biquadratic Quad9 without
// its centre: corners counter-clockwise, then the mid-edge nodes of edges
// 0-1, 1-2, 2-3, 3-0 (VTK_QUADRATIC_QUAD). 3×3 Gauss points, as Quad9: the
// chamber-volume integrand det[x, x_s, x_t] is of degree ≤ 5 per direction, so
// the rule is exact.
#include "fem/elements/axisymmetric_quad.hpp"

namespace softarm::fem {

struct Quad8 {
  static constexpr int kNodes = 8, kGaussPoints = 9;
  /// Corners: N = ¼ (1 + ss_a)(1 + tt_a)(ss_a + tt_a − 1); mid-edge nodes on s_a = 0:
  /// N = ½ (1 − s²)(1 + tt_a), and likewise with s and t exchanged.
  static void shape(double s, double t, double* N, double* dN_ds, double* dN_dt) {
    constexpr int cs[8] = {-1, 1, 1, -1, 0, 1, 0, -1}, ct[8] = {-1, -1, 1, 1, -1, 0, 1, 0};
    for (int a = 0; a < 8; ++a) {
      const double fs = 1 + cs[a] * s, ft = 1 + ct[a] * t;
      if (a < 4) {
        const double g = cs[a] * s + ct[a] * t - 1;
        N[a] = 0.25 * fs * ft * g;
        dN_ds[a] = 0.25 * cs[a] * ft * (g + fs);
        dN_dt[a] = 0.25 * ct[a] * fs * (g + ft);
      } else if (cs[a] == 0) {
        N[a] = 0.5 * (1 - s * s) * ft;
        dN_ds[a] = -s * ft;
        dN_dt[a] = 0.5 * (1 - s * s) * ct[a];
      } else {
        N[a] = 0.5 * fs * (1 - t * t);
        dN_ds[a] = 0.5 * cs[a] * (1 - t * t);
        dN_dt[a] = -t * fs;
      }
    }
  }
  static void gauss_point(int q, double& s, double& t, double& w) { axisym::Quad9::gauss_point(q, s, t, w); }
};

}  // namespace softarm::fem

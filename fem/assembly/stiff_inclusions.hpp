#pragma once
// Stiff inclusions (the ABS rings in silicone, E ≈ 2 GPa against ~0.5 MPa) move almost
// rigidly, and a rotating rigid body is exactly what a linear update gets wrong: a Newton
// step δx = ω × r rotates a ring by |ω| but also stretches it by |ω|²/2, and at 2 GPa that
// spurious strain (a few tenths of a per cent for a few degrees of bend per step) dwarfs
// every silicone force. The residual then grows 10³–10⁴× after a full step, the line search
// cuts it, and the ring's geometric stiffness under that spurious stress makes the next
// tangent indefinite (docs/performance.md, Why a predicted state has a negative eigenvalue that
// its equilibrium has not).
//
// So on each inclusion (a connected group of stiff elements) the update applies the
// group's best-fit infinitesimal rotation ω as the finite rotation exp([ω]×) (Rodrigues),
// the rest of δx linearly. The map x ↦ x ⊕ δx agrees with x + δx to first order in δx, so
// it is a retraction (Absil, Mahony & Sepulchre 2008, §4.1) and Newton keeps its quadratic
// convergence; the line search searches along the curve α ↦ x ⊕ αδx, whose slope at 0 is δx.
// The same idea is the exponential-map update of geometrically exact rods (Simo &
// Vu-Quoc 1986).
#include <vector>

#include "fem/forms/form.hpp"
#include "fem/mesh/mesh.hpp"

namespace softarm::fem {

class StiffInclusions {
 public:
  StiffInclusions() = default;
  /// One group per connected set (elements sharing a node) of the elements of the given
  /// parts of a 3D mesh; none on an axisymmetric mesh (no rotation there to get wrong).
  static StiffInclusions of_parts(const Mesh& mesh, const std::vector<int>& parts);

  bool empty() const { return groups_.empty(); }
  int size() const { return static_cast<int>(groups_.size()); }
  const std::vector<std::vector<int>>& groups() const { return groups_; }

  /// x ⊕ δx into `out` (which must hold x + δx on entry): on each group, out_i += (R(ω) − I − [ω]×) r_i,
  /// with r_i the node's offset from the group's centroid and ω the group's best-fit rotation of δx.
  void correct_update(const Vector& x, const Vector& dx, Vector& out) const;

 private:
  std::vector<std::vector<int>> groups_;  // node indices
};

}  // namespace softarm::fem

#pragma once
// Periodic end faces: the top face of a ring-pitch cell moves as its bottom face does,
// plus the cell's homogenised strains, carried by the six dofs of two pilot nodes:
//     x_t − x_b = X_t − X_b + (t_x − φ·Y_b,  t_y + φ·X_b,  a + b·X_b + c·Y_b)
// for every top node t facing bottom node b (same X, Y). φ is the twist of the top face
// against the bottom one about the axis (x = y = 0), t_x and t_y the shear offsets, a the
// axial and (b, c) the bending ones; the faces' warping is free but the same on both. This
// is the periodic cell of a beam-like body (Buannic & Cartraud 2001), which is what a
// twisted cell needs: the plane sections of plane_face_form.hpp hold only by the mirror
// symmetry of stretch and bending, which torsion does not share (its sections warp).
//
// A penalty, linear in the dofs (reference coordinates in the offset), used for the
// tangent's compliances only: Π = ½ k Σ w |r|², r the residual of the relation above, w the
// pair's weight (1, or ½ for a pair on a half model's mirror plane, which the half model shares
// with its mirror image); gradient k w Jᵀr and Hessian k w JᵀJ with J = [I, −I, −G(X_b)] per pair.
#include <array>
#include <utility>
#include <vector>

#include "fem/forms/form.hpp"

namespace softarm::fem {

class PeriodicFaceForm : public Form {
 public:
  /// `pairs`: (top node, bottom node); `reference`: the mesh's reference positions (3 per
  /// node); the first pilot's x, y, z dofs are t_x, t_y (mm) and φ (rad), the second's a (mm),
  /// b and c (mm/mm); `penalty` k in N/mm per pair; `weights` one per pair (empty: all 1).
  PeriodicFaceForm(std::vector<std::pair<int, int>> pairs, const Vector& reference, int shear_twist_pilot,
                   int stretch_bend_pilot, double penalty, const std::vector<double>& weights = {});
  std::string name() const override { return "periodic faces"; }
  void declare_pattern(SparsePattern& pattern) override;
  FormStatus add(const Vector& x, double* value, Vector* gradient, HessianAccumulator* hessian) const override;

 private:
  struct Pair {
    int top, bottom;
    Eigen::Vector3d offset;  // X_t − X_b
    double X, Y;             // the bottom node's reference x, y
    double weight;
  };
  std::vector<Pair> pairs_;
  int p1_, p2_;
  double k_;
  std::vector<int> blocks_;
  std::array<int, 12> dofs(const Pair& p) const;
};

/// The top and bottom nodes facing each other (same x and y within `tolerance_mm`); throws
/// std::invalid_argument when a top node has no partner (the faces are not each other's copy).
std::vector<std::pair<int, int>> facing_nodes(const std::vector<int>& top, const std::vector<int>& bottom,
                                              const Vector& reference, double tolerance_mm = 1e-9);

}  // namespace softarm::fem

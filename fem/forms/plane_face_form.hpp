#pragma once
// Plane sections stay plane: the normal displacement of a cut face follows a plane
// driven by two generalised dofs, the face's offset a and slope b. They live in the
// first two coordinates of a pilot node that no element uses (reference position at
// the origin), so the solver treats them like any other dof.
//
// This is the end face of a ring-pitch cell of a beam-like body that repeats along
// z (the homogenisation of periodic beams, e.g. Buannic & Cartraud 2001): a cell
// that is mirror-symmetric about its mid-plane, bent and stretched uniformly, keeps
// both end faces plane, with their in-plane motion free. With the other face on
// z = 0 and the axis through x = y = 0, the cell's axial stretch is 1 + a/L and its
// end face's normal (−b, −c, 1)/|·|: the cell bends towards (−b, −c).
//
// The constraint z_i = z0 + a + b·x_i + c·y_i (current positions: exact for the face's
// own in-plane motion, which the chambers' ballooning makes large) is a penalty,
//     Π = ½ k Σ_i g_i²,   g_i = z_i − z0 − a − b·x_i − c·y_i,
// with gradient k g_i ∇g_i, ∇g_i = (∂x_i: −b, ∂y_i: −c, ∂z_i: 1, ∂a: −1, ∂b: −x_i,
// ∂c: −y_i), and Hessian k Σ (∇g_i ∇g_iᵀ + g_i ∇²g_i), ∇²g_i having only
// ∂²/∂b∂x_i = ∂²/∂c∂y_i = −1.
// k of 10⁴ times the face's stiffest shear modulus times 1 mm holds the plane to
// ~10⁻³ of the face's displacement (test_tca_cell.cpp) without spoiling Cholesky.
//
// With a reference node r, the plane's origin follows r's in-plane displacement
// u = (x_r − X_r, y_r − Y_r):  g_i = z_i − z0 − a − b·(x_i − u_x) − c·(y_i − u_y),
// adding ∂x_r: b, ∂y_r: c to ∇g_i and ∂²/∂b∂x_r = ∂²/∂c∂y_r = +1. a is then the
// plane's height at the axis carried along with r, and translating the whole body
// in x, y leaves every g_i as it was: the translation costs nothing and couples to
// nothing, so a mean can hold it (mean_displacement_form.hpp). Without r the plane's
// origin stays at x = y = 0, and a translation of the body must shift a by −b·t.
#include <array>
#include <vector>

#include "fem/forms/form.hpp"

namespace softarm::fem {

class PlaneFaceForm : public Form {
 public:
  /// `face_nodes` follow the plane; the pilot's x, y, z dofs are a (mm), b and c (mm/mm);
  /// `z0` is the face's reference height; `penalty` k in N/mm per node.
  PlaneFaceForm(std::vector<int> face_nodes, int pilot_node, double z0, double penalty);
  /// The same, with the plane's origin following node `reference_node`, whose reference
  /// position has the in-plane coordinates `reference_xy` (mm).
  PlaneFaceForm(std::vector<int> face_nodes, int pilot_node, double z0, double penalty, int reference_node,
                Eigen::Vector2d reference_xy);
  std::string name() const override { return "plane face"; }
  void declare_pattern(SparsePattern& pattern) override;
  FormStatus add(const Vector& x, double* value, Vector* gradient, HessianAccumulator* hessian) const override;

  /// Largest |g_i| at x: how far the face is from its plane, mm.
  double max_gap(const Vector& x) const;

 private:
  std::vector<int> nodes_;
  int pilot_;
  double z0_, k_;
  int reference_ = -1;  // r, or −1: the origin fixed
  Eigen::Vector2d reference_xy_ = Eigen::Vector2d::Zero();
  struct Plane {
    double a, b, c;
    Eigen::Vector2d origin;  // u, or zero
  };
  Plane plane(const Vector& x) const;
  double gap(const Vector& x, int node, const Plane& p) const;  // g_i
  int block_size() const { return reference_ >= 0 ? 8 : 6; }
  /// A face node's block: x_i, y_i, z_i, a, b, c, then x_r, y_r (the first block_size() count).
  std::array<int, 8> block_dofs(int node) const;
  std::vector<int> blocks_;
};

/// Dead generalised forces on single dofs, applied with the self-weight preload:
/// Π = −s Σ f_d x_d, s = LoadState::gravity_scale (pressure_path.hpp applies it before the
/// pressure ramp). A cell's end face takes an axial force and a moment this way, through
/// its pilot's dofs.
class DofLoadForm : public Form {
 public:
  DofLoadForm(std::vector<int> dofs, std::vector<double> forces, const LoadState& load)
      : dofs_(std::move(dofs)), forces_(std::move(forces)), load_(load) {}
  std::string name() const override { return "dof loads"; }
  bool is_load() const override { return true; }
  void declare_pattern(SparsePattern&) override {}
  FormStatus add(const Vector& x, double* value, Vector* gradient, HessianAccumulator*) const override {
    const double s = load_.gravity_scale;
    for (std::size_t i = 0; i < dofs_.size(); ++i) {
      if (value) *value -= s * forces_[i] * x[dofs_[i]];
      if (gradient) (*gradient)[dofs_[i]] -= s * forces_[i];
    }
    return FormStatus::fine();
  }

 private:
  std::vector<int> dofs_;
  std::vector<double> forces_;
  const LoadState& load_;
};

}  // namespace softarm::fem

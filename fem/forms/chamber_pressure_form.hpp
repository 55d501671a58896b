#pragma once
// Pressure in a closed chamber as the potential −p·V(x) (PolyFEM, and
// e.g. Bonet & Wood §6.5 "enclosed volume"): its gradient is the exact
// follower pressure load on the discretised chamber wall and its Hessian the
// exact load stiffness, symmetric because the load is conservative for a
// closed chamber. Dropping this stiffness is what makes solvers stall on
// pressurised tubes (see shared/spec/calculix-notes.md).
//
// Axisymmetric volume of a chamber whose (r, z) boundary is a chain of
// edges: V = ∮ π r² dz (divergence theorem for a body of revolution; the
// closing segment on the axis contributes nothing). Along an edge with
// Lagrange shape functions N_a(s), r = Σ N_a r_a and dz = Σ N_a' z_a ds, so
// π r² z' is a polynomial of degree 3(n−1) − 1 in s, integrated exactly by
// Gauss–Legendre with n points (2-node: exact trapezoid of revolution,
// 3-node: exact for the quadratic edge).
//
// 3D: V = Σ_facets (1/3) ∫ x·n dA (divergence theorem with div x = 3), with
// n dA = (x_s × x_t) ds dt on a bilinear (4-node), serendipity (8-node) or
// biquadratic (9-node) quadrilateral facet in the node order of
// axisymmetric_quad.hpp's Quad4 / Quad9 and serendipity_quad.hpp's Quad8
// (VTK's), oriented so that x_s × x_t points out of the cavity. The integrand
// det[x, x_s, x_t] has degree ≤ 2 in each of s, t on a bilinear facet and ≤ 5
// on a quadratic one, so 2×2 and 3×3 Gauss–Legendre integrate it exactly.
// The facets must close the cavity: on an open surface (1/3)∫ x·n dA is not a
// volume and its gradient is not the pressure load. Where a cut leaves the cavity
// open (a ring-pitch cell), the chamber's lids (mesh.hpp) close it: each adds the
// cone from its centroid over its edges, (1/6) det[c, x_i, x_i+1] per straight edge
// and Simpson's weights over a quadratic one (chamber_pressure_form.cpp), so the
// fluid's push on the cut is part of the same potential and the tangent stays symmetric.
#include "fem/forms/form.hpp"
#include "fem/mesh/mesh.hpp"

namespace softarm::fem {

class ChamberPressureForm : public Form {
 public:
  /// `chamber` indexes mesh.chambers; the pressure is read from load.chamber_pressure_MPa[chamber].
  ChamberPressureForm(const Mesh& mesh, int chamber, const LoadState& load);
  std::string name() const override { return "pressure(" + mesh_.chambers[chamber_].name + ")"; }
  bool is_load() const override { return true; }
  void declare_pattern(SparsePattern& pattern) override;
  FormStatus add(const Vector& x, double* value, Vector* gradient, HessianAccumulator* hessian) const override;

  /// Index of the chamber in mesh.chambers (and in LoadState::chamber_pressure_MPa).
  int chamber() const { return chamber_; }
  /// Chamber volume at positions x, mm³.
  double volume(const Vector& x) const;
  /// ∂V/∂x (full dof vector).
  Vector volume_gradient(const Vector& x) const;

 private:
  double pressure() const;
  bool quadratic_lids() const { return mesh_.nodes_per_element > 8; }  // lid loops: corner, midside, …
  const Mesh& mesh_;
  int chamber_;
  const LoadState& load_;
  std::vector<int> blocks_, lid_blocks_;
};

}  // namespace softarm::fem

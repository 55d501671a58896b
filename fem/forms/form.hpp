#pragma once
// A form is one term of the total potential energy Π(x) (PolyFEM's design):
// elastic strain energy, chamber pressure work, gravity... Each provides its
// value, gradient and Hessian at the current nodal positions x, and is checked
// against finite differences in the tests. The solver only ever sees the sum,
// so the tangent is the exact Hessian of one scalar: symmetric by construction.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "fem/sparse/sparse_pattern.hpp"

namespace softarm::fem {

/// Current positions: node-major, `dim` entries per node (r, z) or (x, y, z).
using Vector = Eigen::VectorXd;

/// Why a form could not be evaluated at x.
struct FormStatus {
  bool ok = true;
  int element = -1;          // first offending element
  std::string reason;        // e.g. "inverted element (det F <= 0)"
  static FormStatus fine() { return {}; }
  static FormStatus inverted(int e, std::string why) { return {false, e, std::move(why)}; }
};

class Form {
 public:
  virtual ~Form() = default;
  virtual std::string name() const = 0;
  /// True for external loads (pressure, gravity): their gradient sets the force
  /// scale that Newton's residual is measured against.
  virtual bool is_load() const { return false; }
  /// Declares the dof blocks this form couples (called once per mesh).
  virtual void declare_pattern(SparsePattern& pattern) = 0;
  /// Adds this form's energy to `value`, its gradient to `gradient` and its Hessian
  /// to `hessian` (each may be null) at positions x.
  virtual FormStatus add(const Vector& x, double* value, Vector* gradient, HessianAccumulator* hessian) const = 0;
};

/// The loads a load level maps to; forms read it, the load stepper writes it.
struct LoadState {
  std::vector<double> chamber_pressure_MPa;  // indexed like Mesh::chambers
  double dirichlet_scale = 0.0;              // fraction of the prescribed displacements applied
  double gravity_scale = 0.0;
};

}  // namespace softarm::fem

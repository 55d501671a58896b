#pragma once
// The lowest eigenpairs of a factorised symmetric positive definite tangent K,
// restricted to the free dofs: subspace (block inverse) iteration with a
// Rayleigh–Ritz step per iteration (Bathe, Finite Element Procedures, §11.6).
// Each iteration is one solve per vector with the factor already in the
// LinearSolver, so no further factorisation is needed.
//
// Why: under pressure control a structure loses stability where the tangent's
// lowest eigenvalue reaches zero. The chamber's dp/dV (pressure_path.hpp) sees
// only what changes the loaded volume; a wall that balloons between two rings
// of a long 3CA barely does, but its mode is the tangent's lowest, and that
// mode shows where it is.
#include <vector>

#include "fem/solver/linear_solver.hpp"

namespace softarm::fem {

struct LowestModes {
  std::vector<double> eigenvalues;    // ascending, N/mm (the tangent's units)
  std::vector<Eigen::VectorXd> modes;  // unit vectors, zero at prescribed dofs
  int iterations = 0;
  bool converged = false;             // every wanted eigenvalue settled to the tolerance
};

/// `count` lowest eigenpairs of K, whose factorisation `solver` holds (it must be the
/// positive definite factor of K). `prescribed`: dofs with identity rows, left out.
LowestModes lowest_modes(LinearSolver& solver, const Eigen::SparseMatrix<double>& K, const std::vector<char>& prescribed,
                         int count = 2, int max_iterations = 60, double tolerance = 1e-6);

/// How many of the nodes (of `dofs_per_node` dofs each) a mode moves: the participation
/// ratio (Σ a_n)² / (N Σ a_n²) with a_n the node's squared amplitude, 1 when every node moves
/// alike, ~1/N when one node does. And the node that moves most.
struct ModeExtent {
  double participation = 0;
  int peak_node = -1;
};
ModeExtent mode_extent(const Eigen::VectorXd& mode, int dofs_per_node);

}  // namespace softarm::fem

// Design space: validation of a Problem/Options pair, the normalisation of the
// continuous and integer variables to [0,1] (so that tolerances and
// finite-difference steps are uniform across variables of any unit), the
// snapping of a design to a real one (integers integral, categorical index
// valid) and the enumeration of categorical combinations.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/optimiser/optimiser.hpp"

namespace softarm::optimise::detail {

/// Throws std::invalid_argument naming the offending variable or option.
void validate(const Problem& problem, const Options& options);

class DesignSpace {
 public:
  explicit DesignSpace(const std::vector<Variable>& variables);

  std::size_t size() const { return variables_.size(); }
  const Variable& variable(std::size_t i) const { return variables_[i]; }
  /// Indices of the variables of one kind, in order.
  std::vector<std::size_t> indices(VariableKind kind) const;
  /// Continuous and integer indices (the ones a continuous search moves), in order.
  std::vector<std::size_t> searchable() const;

  /// Normalised coordinate of a continuous or integer variable, clamped to [0,1].
  double to_unit(std::size_t i, double physical) const;
  /// Physical value (relaxed: an integer may come out fractional), u clamped to [0,1].
  double to_physical(std::size_t i, double unit) const;

  /// A real design: continuous clamped to the bounds, integers rounded and
  /// clamped, categorical indices rounded and clamped.
  std::vector<double> snapped(std::vector<double> x) const;
  /// Cache key of a snapped design (continuous at 1e-12 of the range).
  std::vector<std::int64_t> key(const std::vector<double>& x) const;

  /// The centre of the box; categorical choices 0.
  std::vector<double> centre() const;
  /// Every combination of categorical choice indices (one entry per
  /// categorical variable, in order), the first combination first.
  std::vector<std::vector<int>> categorical_combinations() const;
  /// "material=ecoflex, ring=square" for a design.
  std::string categorical_label(const std::vector<double>& x) const;

 private:
  std::vector<Variable> variables_;
};

}  // namespace softarm::optimise::detail

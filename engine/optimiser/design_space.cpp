// Design space: validation, normalisation to [0,1], snapping and categorical
// combinations (see design_space.hpp).
#include "engine/optimiser/design_space.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace softarm::optimise::detail {

namespace {

[[noreturn]] void bad(const std::string& what) {
  throw std::invalid_argument("optimiser: " + what);
}

std::string quoted(const Variable& v) { return "variable '" + v.name + "'"; }

}  // namespace

void validate(const Problem& problem, const Options& options) {
  if (problem.variables.empty()) bad("the problem has no variables");
  if (!problem.evaluate) bad("the problem has no evaluate function");
  for (const Variable& v : problem.variables) {
    if (v.kind == VariableKind::categorical) {
      if (v.choices.empty()) bad(quoted(v) + " is categorical but has no choices");
      if (v.fixed_choice >= static_cast<int>(v.choices.size()))
        bad(quoted(v) + " is held at choice " + std::to_string(v.fixed_choice) + " of " +
            std::to_string(v.choices.size()));
      continue;
    }
    if (!std::isfinite(v.lower) || !std::isfinite(v.upper) || !(v.lower < v.upper)) {
      std::ostringstream s;
      s << quoted(v) << " needs finite bounds with lower < upper (got [" << v.lower << ", "
        << v.upper << "])";
      bad(s.str());
    }
    if (v.kind == VariableKind::integer &&
        (v.lower != std::round(v.lower) || v.upper != std::round(v.upper)))
      bad(quoted(v) + " is integer but its bounds are not integral");
  }
  if (options.max_evaluations < 1) bad("max_evaluations must be at least 1");
  if (options.starts < 1) bad("starts must be at least 1");
  if (options.categorical_keep < 1) bad("categorical_keep must be at least 1");
  if (!(options.relative_tolerance > 0)) bad("relative_tolerance must be positive");
  if (!(options.constraint_tolerance >= 0)) bad("constraint_tolerance must be non-negative");
  if (!(options.finite_difference_step > 0 && options.finite_difference_step <= 0.5))
    bad("finite_difference_step must be in (0, 0.5] (normalised space)");
  if (!options.x0.empty()) {
    if (options.x0.size() != problem.variables.size()) {
      std::ostringstream s;
      s << "x0 has " << options.x0.size() << " values, the problem " << problem.variables.size()
        << " variables";
      bad(s.str());
    }
    for (std::size_t i = 0; i < options.x0.size(); ++i) {
      const Variable& v = problem.variables[i];
      const double x = options.x0[i];
      const bool inside =
          v.kind == VariableKind::categorical
              ? (x >= 0 && std::round(x) < static_cast<double>(v.choices.size()))
              : (x >= v.lower && x <= v.upper);
      if (!std::isfinite(x) || !inside) {
        std::ostringstream s;
        s << "x0 of " << quoted(v) << " is " << x << ", outside its range";
        bad(s.str());
      }
    }
  }
}

DesignSpace::DesignSpace(const std::vector<Variable>& variables) : variables_(variables) {}

std::vector<std::size_t> DesignSpace::indices(VariableKind kind) const {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < variables_.size(); ++i)
    if (variables_[i].kind == kind) out.push_back(i);
  return out;
}

std::vector<std::size_t> DesignSpace::searchable() const {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < variables_.size(); ++i)
    if (variables_[i].kind != VariableKind::categorical) out.push_back(i);
  return out;
}

double DesignSpace::to_unit(std::size_t i, double physical) const {
  const Variable& v = variables_[i];
  return std::clamp((physical - v.lower) / (v.upper - v.lower), 0.0, 1.0);
}

double DesignSpace::to_physical(std::size_t i, double unit) const {
  const Variable& v = variables_[i];
  const double u = std::clamp(std::isfinite(unit) ? unit : 0.5, 0.0, 1.0);
  return std::clamp(v.lower + u * (v.upper - v.lower), v.lower, v.upper);
}

std::vector<double> DesignSpace::snapped(std::vector<double> x) const {
  for (std::size_t i = 0; i < variables_.size(); ++i) {
    const Variable& v = variables_[i];
    switch (v.kind) {
      case VariableKind::continuous:
        x[i] = std::clamp(x[i], v.lower, v.upper);
        break;
      case VariableKind::integer:
        x[i] = std::clamp(std::round(x[i]), v.lower, v.upper);
        break;
      case VariableKind::categorical:
        x[i] = v.fixed_choice >= 0 ? v.fixed_choice
                                   : std::clamp(std::round(x[i]), 0.0, static_cast<double>(v.choices.size() - 1));
        break;
    }
  }
  return x;
}

std::vector<std::int64_t> DesignSpace::key(const std::vector<double>& x) const {
  std::vector<std::int64_t> k(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const Variable& v = variables_[i];
    if (v.kind == VariableKind::continuous)
      k[i] = std::llround((x[i] - v.lower) / (v.upper - v.lower) * 1e12);
    else
      k[i] = std::llround(x[i]);
  }
  return k;
}

std::vector<double> DesignSpace::centre() const {
  std::vector<double> x(variables_.size(), 0.0);
  for (std::size_t i = 0; i < variables_.size(); ++i)
    if (variables_[i].kind != VariableKind::categorical)
      x[i] = 0.5 * (variables_[i].lower + variables_[i].upper);
  return x;
}

std::vector<std::vector<int>> DesignSpace::categorical_combinations() const {
  const std::vector<std::size_t> cat = indices(VariableKind::categorical);
  std::vector<std::vector<int>> out{std::vector<int>(cat.size(), 0)};
  for (std::size_t j = cat.size(); j-- > 0;) {  // last variable varies fastest
    std::vector<std::vector<int>> next;
    for (const auto& combo : out)
      for (int c = 0; c < static_cast<int>(variables_[cat[j]].choices.size()); ++c) {
        if (variables_[cat[j]].fixed_choice >= 0 && c != variables_[cat[j]].fixed_choice) continue;
        next.push_back(combo);
        next.back()[j] = c;
      }
    out = std::move(next);
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string DesignSpace::categorical_label(const std::vector<double>& x) const {
  std::string label;
  for (std::size_t i : indices(VariableKind::categorical)) {
    if (!label.empty()) label += ", ";
    const auto c = static_cast<std::size_t>(std::llround(x[i]));
    label += variables_[i].name + "=" + variables_[i].choices.at(c);
  }
  return label;
}

}  // namespace softarm::optimise::detail

#include "engine/design/design_problem.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "engine/design/design_measures.hpp"
#include "engine/design/measures_memo.hpp"
#include "fem/core/input_error.hpp"
#include "fem/core/parallel.hpp"

namespace softarm::engine {

std::vector<double> baseline_values(const DesignConfig& config) {
  std::vector<double> x;
  for (const auto& v : config.variables) x.push_back(v.baseline);
  return x;
}

objectives::ArmCandidate make_candidate(const DesignConfig& config, const std::vector<double>& x) {
  fem::SplParameters geometry = config.baseline_geometry;
  std::string tube = config.baseline_tube, sheath = config.baseline_sheath;
  for (std::size_t i = 0; i < config.variables.size(); ++i) {
    const auto& v = config.variables[i].variable;
    if (v.name == "tube_material") tube = v.choices.at(static_cast<std::size_t>(std::lround(x[i])));
    else if (v.name == "sheath_material") sheath = v.choices.at(static_cast<std::size_t>(std::lround(x[i])));
    else geometry.set(v.name, x[i]);  // in the variable's unit, replacing its twin in the other
  }
  objectives::ArmCandidate c;
  c.design = fem::build_spl_design(geometry);
  c.tube = fem::builtin_material(tube, "materials.tube");
  c.sheath = fem::builtin_material(sheath, "materials.sheath");
  c.rings = fem::builtin_material("digital_abs", "materials.rings");
  c.connector = c.rings;
  return c;
}

ConstraintValues constraints_of(const DesignConfig& config, const objectives::ArmMeasures& m, double reference_strain) {
  const Requirements& q = config.requirements;
  ConstraintValues c;
  c.names = {"mass", "payload", "bending", "burst", "durability"};
  c.values = {m.mass_kg / q.max_mass_kg - 1,
              q.min_payload_kg > 0 ? 1 - m.payload_kg / q.min_payload_kg : -m.payload_kg,
              1 - m.min_bending_deg / q.bending_per_segment_deg,
              m.burst_utilisation - 1,
              m.durability_log_strain / reference_strain / q.allowed_strain_ratio() - 1};
  // Extra bounds, relative to |limit| (absolute below 1 in the measure's unit).
  for (const MeasureBound& b : config.extra_constraints) {
    const double v = design_measure(b.measure, "constraints").value(m, config.model, reference_strain);
    const double scale = std::max(std::abs(b.limit), 1.0);
    std::ostringstream name;
    name << b.measure << (b.is_min ? " >= " : " <= ") << b.limit;
    c.names.push_back(name.str());
    c.values.push_back(b.is_min ? (b.limit - v) / scale : (v - b.limit) / scale);
  }
  return c;
}

bool meets_every_requirement(const DesignConfig& config, const objectives::ArmMeasures& m, double reference_strain) {
  for (double g : constraints_of(config, m, reference_strain).values)
    if (!(g <= 1e-9)) return false;
  return true;
}

double objective_of(const DesignConfig& config, const objectives::ArmMeasures& m, double reference_strain) {
  const double v = design_measure(config.objective_measure, "objective").value(m, config.model, reference_strain);
  return config.maximise ? -v : v;
}

ConstraintValues corrected_constraints(ConstraintValues raw, const SolidCorrection& c) {
  for (std::size_t i = 0; i < raw.names.size(); ++i) {
    double& g = raw.values[i];
    if (raw.names[i] == "bending") g = 1 - c.bending_factor * (1 - g);  // 1 − β_θ·θ/θ_target
    if (raw.names[i] == "burst") g = c.burst_factor * (g + 1) - 1;      // β_u·u − 1
  }
  return raw;
}

std::vector<double> normalised_design(const DesignConfig& config, const std::vector<double>& x) {
  std::vector<double> u;
  for (std::size_t i = 0; i < config.variables.size(); ++i) {
    const optimise::Variable& v = config.variables[i].variable;
    if (v.kind == optimise::VariableKind::categorical)
      u.push_back(0.0);  // the discrepancy's linear term does not extrapolate from one material to another
    else
      u.push_back((x[i] - v.lower) / (v.upper - v.lower));
  }
  return u;
}

ConstraintValues corrected_constraints_at(const DesignConfig& config, const objectives::ArmMeasures& m,
                                          double reference_strain, const SolidCorrection& correction,
                                          const DiscrepancyModel* discrepancy, const std::vector<double>& x) {
  ConstraintValues g = corrected_constraints(constraints_of(config, m, reference_strain), correction);
  if (discrepancy && !discrepancy->empty()) {
    const std::vector<double> delta = discrepancy->at(normalised_design(config, x));
    for (std::size_t i = 0; i < g.values.size() && i < delta.size(); ++i) g.values[i] += delta[i];
  }
  return g;
}

std::vector<optimise::Variable> trust_region(const DesignConfig& config, const std::vector<double>& x, double radius,
                                             bool keep_choices) {
  std::vector<optimise::Variable> out;
  for (std::size_t i = 0; i < config.variables.size(); ++i) {
    optimise::Variable v = config.variables[i].variable;
    if (v.kind == optimise::VariableKind::categorical) {
      if (keep_choices) v.fixed_choice = static_cast<int>(std::lround(x[i]));
    } else {
      const double half = radius * (v.upper - v.lower);
      double lo = std::max(v.lower, x[i] - half), hi = std::min(v.upper, x[i] + half);
      if (v.kind == optimise::VariableKind::integer) {
        lo = std::floor(lo), hi = std::ceil(hi);
        if (hi <= lo) {
          if (hi < v.upper) hi += 1;
          else lo -= 1;
        }
      }
      v.lower = lo, v.upper = hi;
    }
    out.push_back(v);
  }
  return out;
}

optimise::Problem design_problem(const DesignConfig& config, double reference_strain,
                                 const SolidCorrection& correction, DesignCheckpoint* checkpoint,
                                 const DiscrepancyModel* discrepancy, MeasuresMemo* memo) {
  optimise::Problem p;
  for (const auto& v : config.variables) p.variables.push_back(v.variable);
  p.constraint_names = constraints_of(config, {}, reference_strain).names;
  p.evaluate = [&config, reference_strain, correction, checkpoint, discrepancy, memo,
                names = p.constraint_names](const std::vector<double>& x) {
    std::optional<optimise::Evaluation> raw = checkpoint ? checkpoint->evaluation(x) : std::nullopt;
    if (!raw) {
      raw.emplace();
      try {
        const objectives::ArmMeasures m = memo ? memo->measures(x, make_candidate(config, x), config.model)
                                               : objectives::evaluate_arm(make_candidate(config, x), config.model);
        raw->objective = objective_of(config, m, reference_strain);
        raw->constraints = constraints_of(config, m, reference_strain).values;
      } catch (const fem::InputError& err) {
        raw->ok = false;  // a geometry that cannot be built is an infeasible point, with the reason
        raw->failure_reason = err.what();
      }
      if (checkpoint) checkpoint->add(x, *raw);
    }
    optimise::Evaluation e = *raw;
    if (e.ok) {
      e.constraints = corrected_constraints({names, raw->constraints}, correction).values;
      if (discrepancy && !discrepancy->empty()) {
        const std::vector<double> delta = discrepancy->at(normalised_design(config, x));
        for (std::size_t i = 0; i < e.constraints.size() && i < delta.size(); ++i) e.constraints[i] += delta[i];
      }
      for (double& g : e.constraints) g += config.search_margin;  // design margin for the re-check
    }
    return e;
  };
  // A design's evaluation depends on it alone (its FEM and rods hold no shared state; the
  // checkpoint locks), so a gradient's neighbours run side by side, one thread each.
  p.run_concurrently = [](int n, const std::function<void(int)>& task) { fem::parallel_tasks(n, task); };
  return p;
}

std::string describe(const DesignConfig& config, const std::vector<double>& x) {
  std::ostringstream s;
  for (std::size_t i = 0; i < config.variables.size(); ++i) {
    const auto& v = config.variables[i].variable;
    if (i) s << ", ";
    s << v.name << " = ";
    if (v.kind == optimise::VariableKind::categorical) s << v.choices.at(static_cast<std::size_t>(std::lround(x[i])));
    else if (v.kind == optimise::VariableKind::integer) s << std::lround(x[i]);
    else s << x[i] << (v.unit == "1" || v.unit.empty() ? "" : " " + v.unit);
  }
  return s.str();
}

}  // namespace softarm::engine

// Multi-start, integer neighbour search and categorical screening (see
// mixed_variable_search.hpp and the overview in optimiser.hpp).
#include "engine/optimiser/mixed_variable_search.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "engine/optimiser/relaxed_objective.hpp"
#include "engine/optimiser/start_points.hpp"

namespace softarm::optimise::detail {

MixedVariableSearch::MixedVariableSearch(const DesignSpace& space, EvaluationCache& cache,
                                         const Options& options)
    : space_(space), cache_(cache), options_(options), algorithm_(parse_algorithm(options.algorithm)) {}

DriverSettings MixedVariableSearch::settings(int budget, bool local_only) const {
  DriverSettings s;
  s.algorithm = local_only && is_global(algorithm_) ? Algorithm::cobyla : algorithm_;
  s.tolerance = options_.relative_tolerance;
  s.constraint_tolerance = options_.constraint_tolerance;
  s.finite_difference_step = options_.finite_difference_step;
  s.seed = options_.seed;
  s.budget = std::max(1, budget);
  return s;
}

std::string MixedVariableSearch::prefixed(const std::string& label, const std::string& phase) const {
  if (label.empty()) return phase;
  if (phase.empty()) return label;
  return label + ": " + phase;
}

void MixedVariableSearch::run(const std::vector<double>& start) {
  const std::vector<std::size_t> cats = space_.indices(VariableKind::categorical);
  const std::vector<std::vector<int>> combos = space_.categorical_combinations();
  if (combos.size() <= 1) {
    optimise_combination(start, cache_.remaining(), "");
    return;
  }
  const double tol = options_.constraint_tolerance;
  auto with_combo = [&](std::vector<double> x, const std::vector<int>& combo) {
    for (std::size_t j = 0; j < cats.size(); ++j) x[cats[j]] = combo[j];
    return x;
  };
  auto combo_of = [&](const std::vector<double>& x) {
    std::vector<int> combo(cats.size());
    for (std::size_t j = 0; j < cats.size(); ++j) combo[j] = static_cast<int>(std::llround(x[cats[j]]));
    return combo;
  };

  // 1. The first combination, with a share of the budget that leaves as much to each of the
  //    `categorical_keep` best of the screening (when the screening picks another combination, its
  //    continuous and integer variables are optimised for it, not left at the first one's optimum).
  const std::vector<int> first = combo_of(start);
  const int count = static_cast<int>(combos.size());
  const int keep = std::min(options_.categorical_keep, count);
  const int first_budget = std::max(1, (cache_.remaining() - (count - 1)) / (keep + 1));
  optimise_combination(start, first_budget, space_.categorical_label(start));
  const auto* best_first =
      cache_.best([&](const std::vector<double>& x) { return combo_of(x) == first; });
  if (!best_first) return;
  const std::vector<double> anchor = best_first->x;  // copy: entries move as the cache grows

  // 2. Screening: every other combination at the first one's optimum.
  struct Screened {
    std::vector<int> combo;
    std::vector<double> x;
    Evaluation value;
  };
  std::vector<Screened> screened{{first, anchor, best_first->value}};
  {
    EvaluationCache::Scope scope(cache_, "categorical screening", cache_.remaining());
    std::vector<std::vector<int>> others;
    std::vector<std::vector<double>> points;
    for (const auto& combo : combos)
      if (combo != first) {
        others.push_back(combo);
        points.push_back(with_combo(anchor, combo));
      }
    cache_.prefetch(points);
    for (std::size_t k = 0; k < others.size(); ++k) {
      try {
        screened.push_back({others[k], points[k], cache_.evaluate(points[k])});
      } catch (const BudgetExhausted&) {
        notes_.push_back("categorical screening: evaluation budget reached");
        break;
      }
    }
  }
  std::stable_sort(screened.begin(), screened.end(),
                   [&](const Screened& a, const Screened& b) { return better(a.value, b.value, tol); });

  // 3. The categorical_keep best, each from its screened point with an equal share of what is left
  //    (the first, if kept, continues from its optimum).
  const std::size_t top = std::min<std::size_t>(keep, screened.size());
  for (std::size_t k = 0; k < top && cache_.remaining() > 0; ++k)
    optimise_combination(screened[k].x, cache_.remaining() / static_cast<int>(top - k),
                         space_.categorical_label(screened[k].x));
}

void MixedVariableSearch::optimise_combination(const std::vector<double>& start, int budget,
                                               const std::string& label) {
  EvaluationCache::Scope scope(cache_, label, budget);
  const std::vector<std::size_t> searched = space_.searchable();
  if (searched.empty()) {
    try {
      cache_.evaluate(start);
    } catch (const BudgetExhausted&) {
    }
    return;
  }
  const bool has_integers = !space_.indices(VariableKind::integer).empty();
  const double tol = options_.constraint_tolerance;
  const int starts = options_.starts;
  const auto sample = latin_hypercube(static_cast<std::size_t>(starts - 1), searched.size(), options_.seed);

  bool have_best = false;
  std::vector<double> best_x;
  Evaluation best_value;
  {
    // The relaxed search leaves 40 % for the integer neighbours.
    const int relaxed_budget = has_integers ? std::max(1, cache_.remaining() * 3 / 5) : cache_.remaining();
    EvaluationCache::Scope relaxed(cache_, label, relaxed_budget);
    for (int k = 0; k < starts && cache_.remaining() > 0; ++k) {
      const std::string phase = prefixed(label, "start " + std::to_string(k + 1));
      const int share = std::max(1, cache_.remaining() / (starts - k));
      EvaluationCache::Scope one(cache_, phase, share);
      RelaxedObjective f(space_, cache_, start, searched);
      const std::vector<double> u0 =
          usable_start(f, k == 0 ? f.unit(start) : sample[static_cast<std::size_t>(k - 1)], k);
      const DriverOutcome out = run_driver(f, u0, settings(share, false));
      notes_.push_back(phase + ": " + out.stop_reason);
      if (f.has_best() && (!have_best || better(f.best_value(), best_value, tol))) {
        have_best = true;
        best_x = f.physical(f.best_u());
        best_value = f.best_value();
      }
    }
  }
  if (has_integers && have_best && cache_.remaining() > 0) integer_neighbours(best_x, label);
}

std::vector<double> MixedVariableSearch::usable_start(RelaxedObjective& f, const std::vector<double>& u0,
                                                      int start_index) {
  // A solver started on a failing design sees only penalties and stops there.
  // Try towards the centre of the box, then a small seeded sample.
  const std::size_t n = f.dimension();
  std::vector<std::vector<double>> candidates{u0};
  for (double t : {0.5, 0.75}) {
    std::vector<double> u = u0;
    for (double& v : u) v += t * (0.5 - v);
    candidates.push_back(u);
  }
  for (auto& u : latin_hypercube(2 * n + 2, n, options_.seed + 7919u * static_cast<unsigned>(start_index + 1)))
    candidates.push_back(std::move(u));
  try {
    for (const auto& u : candidates)
      if (f(u).ok) return u;
  } catch (const BudgetExhausted&) {
  }
  return u0;
}

void MixedVariableSearch::integer_neighbours(const std::vector<double>& relaxed, const std::string& label) {
  const std::vector<std::size_t> ints = space_.indices(VariableKind::integer);
  const double tol = options_.constraint_tolerance;
  // Candidate values per integer, nearest to the relaxed value first.
  std::vector<std::vector<double>> values(ints.size());
  std::size_t combinations = 1;
  for (std::size_t j = 0; j < ints.size(); ++j) {
    const Variable& v = space_.variable(ints[j]);
    // A relaxed value within the search's resolution of an integer is that
    // integer (the piecewise-linear relaxation often has its optimum on a vertex).
    const double snap = std::clamp(10 * options_.relative_tolerance * (v.upper - v.lower), 1e-9, 0.05);
    const double r = relaxed[ints[j]];
    const double lo = std::clamp(std::floor(r + snap), v.lower, v.upper);
    const double hi = std::clamp(std::ceil(r - snap), v.lower, v.upper);
    if (lo == hi) values[j] = {lo};
    else values[j] = r - lo <= hi - r ? std::vector<double>{lo, hi} : std::vector<double>{hi, lo};
    combinations *= values[j].size();
  }
  auto design = [&](const std::vector<std::size_t>& pick) {
    std::vector<double> x = relaxed;
    for (std::size_t j = 0; j < ints.size(); ++j) x[ints[j]] = values[j][pick[j]];
    return x;
  };
  auto name = [&](const std::vector<double>& x) {
    std::ostringstream s;
    s << "integer neighbours";
    for (std::size_t j = 0; j < ints.size(); ++j)
      s << (j ? ", " : " ") << space_.variable(ints[j]).name << "=" << x[ints[j]];
    return prefixed(label, s.str());
  };
  EvaluationCache::Scope scope(cache_, prefixed(label, "integer neighbours"), cache_.remaining());

  auto try_pick = [&](const std::vector<std::size_t>& pick, int candidates_left) -> std::optional<Evaluation> {
    const std::vector<double> x = design(pick);
    std::optional<Evaluation> best;
    const int share = std::max(1, cache_.remaining() / std::max(1, candidates_left));
    EvaluationCache::Scope one(cache_, name(x), share);
    const std::vector<std::size_t> cont = space_.indices(VariableKind::continuous);
    if (cont.empty()) {
      try {
        best = cache_.evaluate(x);
      } catch (const BudgetExhausted&) {
      }
      return best;
    }
    RelaxedObjective f(space_, cache_, x, cont);
    const DriverOutcome out = run_driver(f, f.unit(x), settings(share, true));
    notes_.push_back(name(x) + ": " + out.stop_reason);
    if (f.has_best()) best = f.best_value();
    return best;
  };

  if (combinations <= 8) {
    // Every floor/ceil combination, nearest to the relaxed optimum first.
    std::vector<std::vector<std::size_t>> picks{std::vector<std::size_t>(ints.size(), 0)};
    for (std::size_t j = 0; j < ints.size(); ++j) {
      std::vector<std::vector<std::size_t>> next;
      for (const auto& p : picks)
        for (std::size_t c = 0; c < values[j].size(); ++c) {
          next.push_back(p);
          next.back()[j] = c;
        }
      picks = std::move(next);
    }
    auto distance = [&](const std::vector<std::size_t>& p) {
      const std::vector<double> x = design(p);
      double d = 0;
      for (std::size_t i : ints) d += std::abs(x[i] - relaxed[i]);
      return d;
    };
    std::stable_sort(picks.begin(), picks.end(),
                     [&](const auto& a, const auto& b) { return distance(a) < distance(b); });
    for (std::size_t k = 0; k < picks.size() && cache_.remaining() > 0; ++k)
      try_pick(picks[k], static_cast<int>(picks.size() - k));
    return;
  }

  // Greedy: the nearest rounding, then each integer flipped in turn.
  std::vector<std::size_t> pick(ints.size(), 0);
  int candidates = 1;
  for (const auto& v : values) candidates += v.size() > 1;
  std::optional<Evaluation> current = try_pick(pick, candidates--);
  for (std::size_t j = 0; j < ints.size() && cache_.remaining() > 0; ++j) {
    if (values[j].size() < 2) continue;
    std::vector<std::size_t> flipped = pick;
    flipped[j] = 1;
    const std::optional<Evaluation> trial = try_pick(flipped, candidates--);
    if (trial && (!current || better(*trial, *current, tol))) {
      pick = flipped;
      current = trial;
    }
  }
}

}  // namespace softarm::optimise::detail

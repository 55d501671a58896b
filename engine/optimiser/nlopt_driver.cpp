// NLopt driver (C API, so no C++ exception can cross NLopt's C code).
//
// Objective and constraints are registered separately (nlopt_set_min_objective,
// nlopt_add_inequality_mconstraint); NLopt asks for them one after the other at
// the same point, and the second request is a cache hit. Failed points get a
// finite penalty (RelaxedObjective::penalty_*): the objective above the worst
// seen and every constraint violated, so the algorithms move away without ever
// seeing NaN. Budget exhaustion calls nlopt_force_stop (which also stops
// AUGLAG's subsidiary optimiser). nlopt:isres spends 80 % of its budget on the
// global search and then polishes from the best point with COBYLA.
#include <nlopt.h>

#include <algorithm>
#include <cmath>
#include <exception>

#include "engine/optimiser/driver.hpp"
#include "engine/optimiser/finite_difference.hpp"

namespace softarm::optimise::detail {

namespace {

struct Context {
  RelaxedObjective* f = nullptr;
  const DriverSettings* settings = nullptr;
  nlopt_opt opt = nullptr;
  bool gradients = false;
  bool budget_exhausted = false;
  std::exception_ptr error;
};

void stop(Context& c) {
  try {
    throw;
  } catch (const BudgetExhausted&) {
    c.budget_exhausted = true;
  } catch (...) {
    if (!c.error) c.error = std::current_exception();
  }
  nlopt_force_stop(c.opt);
}

double objective(unsigned n, const double* u, double* grad, void* data) {
  auto& c = *static_cast<Context*>(data);
  try {
    const std::vector<double> v(u, u + n);
    if (grad) {
      const Linearisation lin = linearise(*c.f, v, c.settings->finite_difference_step);
      std::copy(lin.objective_gradient.begin(), lin.objective_gradient.end(), grad);
      return lin.value.ok ? lin.value.objective : c.f->penalty_objective();
    }
    const Evaluation e = (*c.f)(v);
    return e.ok ? e.objective : c.f->penalty_objective();
  } catch (...) {
    stop(c);
  }
  if (grad) std::fill(grad, grad + n, 0.0);
  return c.f->penalty_objective();
}

void constraints(unsigned m, double* result, unsigned n, const double* u, double* grad, void* data) {
  auto& c = *static_cast<Context*>(data);
  try {
    const std::vector<double> v(u, u + n);
    Evaluation e;
    if (grad) {
      const Linearisation lin = linearise(*c.f, v, c.settings->finite_difference_step);
      std::copy(lin.constraint_jacobian.begin(), lin.constraint_jacobian.end(), grad);
      e = lin.value;
    } else {
      e = (*c.f)(v);
    }
    for (unsigned i = 0; i < m; ++i) result[i] = e.ok ? e.constraints[i] : c.f->penalty_constraint(i);
    return;
  } catch (...) {
    stop(c);
  }
  for (unsigned i = 0; i < m; ++i) result[i] = c.f->penalty_constraint(i);
  if (grad) std::fill(grad, grad + static_cast<std::size_t>(m) * n, 0.0);
}

std::string describe(nlopt_result r) {
  switch (r) {
    case NLOPT_SUCCESS: return "success";
    case NLOPT_STOPVAL_REACHED: return "stopval reached";
    case NLOPT_FTOL_REACHED: return "converged (f tolerance)";
    case NLOPT_XTOL_REACHED: return "converged (x tolerance)";
    case NLOPT_MAXEVAL_REACHED: return "NLopt call limit reached";
    case NLOPT_MAXTIME_REACHED: return "time limit reached";
    case NLOPT_FAILURE: return "NLopt failure";
    case NLOPT_INVALID_ARGS: return "NLopt invalid arguments";
    case NLOPT_OUT_OF_MEMORY: return "NLopt out of memory";
    case NLOPT_ROUNDOFF_LIMITED: return "round-off limited";
    case NLOPT_FORCED_STOP: return "stopped";
    default: return "NLopt result " + std::to_string(static_cast<int>(r));
  }
}

nlopt_algorithm nlopt_code(Algorithm a) {
  switch (a) {
    case Algorithm::cobyla: return NLOPT_LN_COBYLA;
    case Algorithm::auglag_bobyqa: return NLOPT_AUGLAG;
    case Algorithm::isres: return NLOPT_GN_ISRES;
    case Algorithm::slsqp: return NLOPT_LD_SLSQP;
    case Algorithm::ccsaq: return NLOPT_LD_CCSAQ;
    case Algorithm::ipopt: break;
  }
  return NLOPT_LN_COBYLA;
}

/// One NLopt run of `algorithm` (never isres's polish) from u0.
DriverOutcome run_one(RelaxedObjective& f, const std::vector<double>& u0, const DriverSettings& s,
                      Algorithm algorithm, int nlopt_calls) {
  const unsigned n = static_cast<unsigned>(f.dimension());
  const unsigned m = static_cast<unsigned>(f.constraint_count());
  nlopt_opt opt = nlopt_create(nlopt_code(algorithm), n);
  nlopt_opt local = nullptr;
  Context c;
  c.f = &f;
  c.settings = &s;
  c.opt = opt;
  c.gradients = uses_gradients(algorithm);

  const std::vector<double> lower(n, 0.0), upper(n, 1.0), tol(n, s.tolerance * 0.1);
  const std::vector<double> ctol(m, s.constraint_tolerance);
  nlopt_set_lower_bounds(opt, lower.data());
  nlopt_set_upper_bounds(opt, upper.data());
  nlopt_set_min_objective(opt, objective, &c);
  if (m > 0) nlopt_add_inequality_mconstraint(opt, m, constraints, &c, ctol.data());
  nlopt_set_xtol_abs(opt, tol.data());
  nlopt_set_ftol_rel(opt, s.tolerance);
  nlopt_set_maxeval(opt, std::max(nlopt_calls, 10));
  if (algorithm == Algorithm::cobyla) nlopt_set_initial_step1(opt, 0.1);
  if (algorithm == Algorithm::auglag_bobyqa) {
    local = nlopt_create(NLOPT_LN_BOBYQA, n);
    nlopt_set_xtol_abs(local, tol.data());
    nlopt_set_ftol_rel(local, s.tolerance);
    nlopt_set_initial_step1(local, 0.1);
    nlopt_set_local_optimizer(opt, local);
  }
  if (algorithm == Algorithm::isres) nlopt_srand(s.seed);

  std::vector<double> u = u0;
  for (double& v : u) v = std::clamp(std::isfinite(v) ? v : 0.5, 0.0, 1.0);
  double value = 0;
  const nlopt_result r = nlopt_optimize(opt, u.data(), &value);
  if (local) nlopt_destroy(local);
  nlopt_destroy(opt);
  if (c.error) std::rethrow_exception(c.error);

  DriverOutcome out;
  out.budget_exhausted = c.budget_exhausted;
  out.stop_reason = c.budget_exhausted ? "evaluation budget reached" : describe(r);
  return out;
}

}  // namespace

DriverOutcome run_nlopt(RelaxedObjective& f, const std::vector<double>& u0, const DriverSettings& s) {
  // NLopt's own call limit is only a backstop against a solver cycling on
  // cached points; the cache enforces the real budget.
  const int calls = 20 * std::max(1, s.budget) + 200;
  if (s.algorithm != Algorithm::isres) return run_one(f, u0, s, s.algorithm, calls);

  // ISRES has no convergence test of its own: it runs until its share of the
  // budget is spent (a phase-local BudgetExhausted), then COBYLA polishes.
  EvaluationCache& cache = f.cache();
  {
    EvaluationCache::Scope scope(cache, cache.phase(), std::max(1, s.budget * 4 / 5));
    run_one(f, u0, s, Algorithm::isres, calls);
  }
  if (cache.remaining() == 0 || !f.has_best()) {
    DriverOutcome out;
    out.budget_exhausted = true;
    out.stop_reason = "evaluation budget reached (ISRES)";
    return out;
  }
  DriverOutcome polish = run_one(f, f.best_u(), s, Algorithm::cobyla, calls);
  polish.stop_reason = "ISRES, then COBYLA polish: " + polish.stop_reason;
  return polish;
}

}  // namespace softarm::optimise::detail

// Ipopt driver through the C++ TNLP interface
// (https://coin-or.github.io/Ipopt/INTERFACES.html).
//
// Variables u in [0,1]^n, constraints g(u) <= 0 (g_l = -inf), dense Jacobian
// from finite differences (finite_difference.hpp), Hessian by the
// limited-memory quasi-Newton approximation (no second derivatives), no
// output (print_level 0, "sb" suppresses the banner). max_iter is derived from
// the evaluation budget (each iteration costs at least the n+1 evaluations of a
// gradient). A failed evaluation makes eval_* return false, which Ipopt treats
// as "cut the step"; on budget exhaustion eval_* returns false and
// intermediate_callback stops the run (it also stops on two consecutive steps
// below the tolerance, see record_iterate).
#include <IpIpoptApplication.hpp>
#include <IpTNLP.hpp>

#include <algorithm>
#include <cmath>
#include <exception>

#include "engine/optimiser/driver.hpp"
#include "engine/optimiser/finite_difference.hpp"

namespace softarm::optimise::detail {

namespace {

using Ipopt::Index;
using Ipopt::Number;

class Nlp : public Ipopt::TNLP {
 public:
  Nlp(RelaxedObjective& f, std::vector<double> u0, const DriverSettings& s)
      : f_(f), u0_(std::move(u0)), s_(s) {}

  bool budget_exhausted = false;
  std::exception_ptr error;
  Ipopt::SolverReturn status = Ipopt::UNASSIGNED;

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag,
                    IndexStyleEnum& index_style) override {
    n = static_cast<Index>(f_.dimension());
    m = static_cast<Index>(f_.constraint_count());
    nnz_jac_g = n * m;
    nnz_h_lag = 0;
    index_style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Index n, Number* x_l, Number* x_u, Index m, Number* g_l, Number* g_u) override {
    std::fill(x_l, x_l + n, 0.0);
    std::fill(x_u, x_u + n, 1.0);
    std::fill(g_l, g_l + m, -1e19);
    std::fill(g_u, g_u + m, 0.0);
    return true;
  }

  bool get_starting_point(Index n, bool init_x, Number* x, bool init_z, Number*, Number*, Index,
                          bool init_lambda, Number*) override {
    if (init_z || init_lambda) return false;
    if (init_x)
      for (Index j = 0; j < n; ++j) x[j] = std::clamp(u0_[j], 0.0, 1.0);
    return true;
  }

  bool eval_f(Index n, const Number* x, bool, Number& obj_value) override {
    return guarded([&] {
      const Evaluation e = f_(point(n, x));
      if (e.ok) obj_value = e.objective;
      return e.ok;
    });
  }

  bool eval_grad_f(Index n, const Number* x, bool, Number* grad_f) override {
    return guarded([&] {
      const std::vector<double> u = point(n, x);
      record_iterate(u);
      const Linearisation lin = linearise(f_, u, s_.finite_difference_step);
      if (!lin.value.ok || !lin.gradient_ok) return false;
      std::copy(lin.objective_gradient.begin(), lin.objective_gradient.end(), grad_f);
      return true;
    });
  }

  bool eval_g(Index n, const Number* x, bool, Index m, Number* g) override {
    return guarded([&] {
      const Evaluation e = f_(point(n, x));
      if (!e.ok) return false;
      std::copy(e.constraints.begin(), e.constraints.begin() + m, g);
      return true;
    });
  }

  bool eval_jac_g(Index n, const Number* x, bool, Index m, Index, Index* iRow, Index* jCol,
                  Number* values) override {
    if (!values) {  // structure: dense, row-major
      for (Index i = 0; i < m; ++i)
        for (Index j = 0; j < n; ++j) {
          iRow[i * n + j] = i;
          jCol[i * n + j] = j;
        }
      return true;
    }
    return guarded([&] {
      const Linearisation lin = linearise(f_, point(n, x), s_.finite_difference_step);
      if (!lin.value.ok || !lin.gradient_ok) return false;
      std::copy(lin.constraint_jacobian.begin(), lin.constraint_jacobian.end(), values);
      return true;
    });
  }

  void finalize_solution(Ipopt::SolverReturn st, Index, const Number*, const Number*, const Number*, Index,
                         const Number*, const Number*, Number, const Ipopt::IpoptData*,
                         Ipopt::IpoptCalculatedQuantities*) override {
    status = st;
  }

  bool intermediate_callback(Ipopt::AlgorithmMode, Index, Number, Number, Number, Number, Number, Number,
                             Number, Number, Index, const Ipopt::IpoptData*,
                             Ipopt::IpoptCalculatedQuantities*) override {
    if (small_steps >= 2) x_converged = true;
    return !budget_exhausted && !error && !x_converged;
  }

  /// Ipopt 3.11 has no step-size test; with finite-difference gradients the
  /// optimality error can stall at O(h) while the iterates creep by ever
  /// smaller steps. Gradients are requested at accepted iterates: two
  /// consecutive moves below the tolerance (max-norm in u) end the run.
  void record_iterate(const std::vector<double>& u) {
    if (!last_iterate_.empty()) {
      double step = 0;
      for (std::size_t j = 0; j < u.size(); ++j) step = std::max(step, std::abs(u[j] - last_iterate_[j]));
      if (step == 0) return;  // the same point asked again
      small_steps = step < s_.tolerance ? small_steps + 1 : 0;
    }
    last_iterate_ = u;
  }
  int small_steps = 0;
  bool x_converged = false;

 private:
  static std::vector<double> point(Index n, const Number* x) { return std::vector<double>(x, x + n); }

  template <class F>
  bool guarded(F&& body) {
    if (budget_exhausted || error) return false;
    try {
      return body();
    } catch (const BudgetExhausted&) {
      budget_exhausted = true;
    } catch (...) {
      error = std::current_exception();
    }
    return false;
  }

  RelaxedObjective& f_;
  std::vector<double> last_iterate_;
  std::vector<double> u0_;
  const DriverSettings& s_;
};

std::string describe(Ipopt::ApplicationReturnStatus r) {
  switch (r) {
    case Ipopt::Solve_Succeeded: return "converged";
    case Ipopt::Solved_To_Acceptable_Level: return "converged to the acceptable level";
    case Ipopt::Infeasible_Problem_Detected: return "Ipopt: locally infeasible";
    case Ipopt::Search_Direction_Becomes_Too_Small: return "Ipopt: search direction too small";
    case Ipopt::User_Requested_Stop: return "stopped";
    case Ipopt::Maximum_Iterations_Exceeded: return "Ipopt: iteration limit (from the evaluation budget)";
    case Ipopt::Restoration_Failed: return "Ipopt: restoration failed";
    case Ipopt::Error_In_Step_Computation: return "Ipopt: error in step computation";
    case Ipopt::Invalid_Number_Detected: return "Ipopt: invalid number";
    default: return "Ipopt status " + std::to_string(static_cast<int>(r));
  }
}

}  // namespace

DriverOutcome run_ipopt(RelaxedObjective& f, const std::vector<double>& u0, const DriverSettings& s) {
  Ipopt::SmartPtr<Nlp> nlp = new Nlp(f, u0, s);
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  auto options = app->Options();
  options->SetStringValue("sb", "yes");
  options->SetIntegerValue("print_level", 0);
  options->SetStringValue("hessian_approximation", "limited-memory");
  const int per_iteration = static_cast<int>(f.dimension()) + 1;
  options->SetIntegerValue("max_iter", std::max(3, s.budget / per_iteration));
  options->SetNumericValue("tol", s.tolerance);
  // Finite-difference gradients are biased by O(h): the optimality error may
  // stall above `tol`, so also accept a few consecutive iterations whose
  // objective change is below the tolerance (and whose error is moderate).
  options->SetNumericValue("acceptable_tol", 1e-2);
  options->SetNumericValue("acceptable_obj_change_tol", s.tolerance);
  options->SetNumericValue("acceptable_constr_viol_tol", std::max(s.constraint_tolerance, 1e-12));
  options->SetIntegerValue("acceptable_iter", 3);
  options->SetNumericValue("constr_viol_tol", std::max(s.constraint_tolerance, 1e-12));
  options->SetNumericValue("compl_inf_tol", s.tolerance);
  options->SetStringValue("mu_strategy", "adaptive");
  // "" : read no ipopt.opt from the working directory.
  Ipopt::ApplicationReturnStatus r = app->Initialize("");
  if (r == Ipopt::Solve_Succeeded) r = app->OptimizeTNLP(Ipopt::SmartPtr<Ipopt::TNLP>(GetRawPtr(nlp)));
  if (nlp->error) std::rethrow_exception(nlp->error);
  DriverOutcome out;
  out.budget_exhausted = nlp->budget_exhausted;
  out.stop_reason = nlp->budget_exhausted ? "evaluation budget reached"
                    : nlp->x_converged       ? "converged (x tolerance)"
                                             : describe(r);
  return out;
}

}  // namespace softarm::optimise::detail

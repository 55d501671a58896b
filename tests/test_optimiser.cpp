// The optimiser layer (engine/optimiser) on analytic problems with known
// optima: every algorithm on a constrained quadratic; integer relaxation and
// the neighbour search (including a rounded-nearest integer that is
// infeasible); categorical screening; failing regions (ok=false, exceptions,
// NaN); the cache; the evaluation budget; an infeasible problem; an unknown
// algorithm; multi-start on a function with two minima.
#include <catch2/catch.hpp>

#include <cmath>
#include <atomic>
#include <functional>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "engine/optimiser/optimiser.hpp"

using namespace softarm::optimise;
using Catch::Matchers::Contains;

namespace {

Variable continuous(const std::string& name, double lower, double upper) {
  Variable v;
  v.name = name;
  v.lower = lower;
  v.upper = upper;
  return v;
}

Variable integer(const std::string& name, double lower, double upper) {
  Variable v = continuous(name, lower, upper);
  v.kind = VariableKind::integer;
  return v;
}

/// min (x-2)^2 + (y-1)^2  s.t.  x + y <= 2  ->  (1.5, 0.5), f = 0.5.
Problem constrained_quadratic(int* counter = nullptr) {
  Problem p;
  p.variables = {continuous("x", 0, 3), continuous("y", 0, 3)};
  p.constraint_names = {"sum"};
  p.evaluate = [counter](const std::vector<double>& x) {
    if (counter) ++*counter;
    Evaluation e;
    e.objective = (x[0] - 2) * (x[0] - 2) + (x[1] - 1) * (x[1] - 1);
    e.constraints = {x[0] + x[1] - 2};
    return e;
  };
  return p;
}

Options with(const std::string& algorithm, int budget) {
  Options o;
  o.algorithm = algorithm;
  o.max_evaluations = budget;
  return o;
}

bool any_failure(const Result& r, const std::string& reason_part) {
  for (const auto& p : r.history)
    if (!p.value.ok && p.value.failure_reason.find(reason_part) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("optimiser: every algorithm finds the constrained optimum of a quadratic", "[optimiser]") {
  for (const std::string& name : algorithm_names()) {
    INFO(name);
    int counter = 0;
    const Result r = minimise(constrained_quadratic(&counter), with(name, name == "nlopt:isres" ? 1500 : 300));
    INFO(r.stop_reason);
    REQUIRE(r.feasible);
    CHECK(r.x[0] == Approx(1.5).margin(0.02));
    CHECK(r.x[1] == Approx(0.5).margin(0.02));
    CHECK(r.best.objective == Approx(0.5).margin(0.01));
    CHECK(r.best.constraints[0] <= 1e-6);
    CHECK(counter == r.evaluations);
    CHECK(static_cast<int>(r.history.size()) == r.evaluations);
  }
}

TEST_CASE("optimiser: integer relaxation and neighbour search find the integer optimum", "[optimiser]") {
  // min (n-2.6)^2 + (x-n/2)^2: relaxed optimum n = 2.6, x = 1.3; integer n = 3, x = 1.5.
  Problem p;
  p.variables = {integer("n", 0, 6), continuous("x", 0, 5)};
  p.evaluate = [](const std::vector<double>& x) {
    if (x[0] != std::round(x[0])) throw std::logic_error("fractional integer evaluated");
    Evaluation e;
    e.objective = (x[0] - 2.6) * (x[0] - 2.6) + (x[1] - x[0] / 2) * (x[1] - x[0] / 2);
    return e;
  };
  for (const std::string& name : algorithm_names()) {
    INFO(name);
    const Result r = minimise(p, with(name, name == "nlopt:isres" ? 800 : 200));
    INFO(r.stop_reason);
    REQUIRE(r.feasible);
    CHECK(r.x[0] == 3);
    CHECK(r.x[1] == Approx(1.5).margin(0.02));
    CHECK(r.best.objective == Approx(0.16).margin(1e-3));
    CHECK_FALSE(any_failure(r, "fractional"));
  }
}

TEST_CASE("optimiser: the neighbour search avoids an infeasible rounded-nearest integer", "[optimiser]") {
  // min (n-3)^2 + (x-1)^2 s.t. n - x <= 1.7, x in [0,1]: relaxed optimum
  // n = 2.7, x = 1; n = 3 needs x >= 1.3 (infeasible); the optimum is n = 2, x = 1, f = 1.
  Problem p;
  p.variables = {integer("n", 0, 6), continuous("x", 0, 1)};
  p.constraint_names = {"n_minus_x"};
  p.evaluate = [](const std::vector<double>& x) {
    Evaluation e;
    e.objective = (x[0] - 3) * (x[0] - 3) + (x[1] - 1) * (x[1] - 1);
    e.constraints = {x[0] - x[1] - 1.7};
    return e;
  };
  for (const std::string name : {"nlopt:cobyla", "nlopt:slsqp", "ipopt"}) {
    INFO(name);
    const Result r = minimise(p, with(name, 200));
    INFO(r.stop_reason);
    REQUIRE(r.feasible);
    CHECK(r.x[0] == 2);
    CHECK(r.x[1] == Approx(1).margin(0.01));
    CHECK(r.best.objective == Approx(1).margin(0.02));
    // n = 3, the rounded-nearest value, was tried by the neighbour search and is infeasible.
    CHECK_THAT(r.stop_reason, Contains("integer neighbours n=3"));
    bool ceil_infeasible = false;
    for (const auto& h : r.history)
      if (h.x[0] == 3 && h.value.constraints[0] > 0) ceil_infeasible = true;
    CHECK(ceil_infeasible);
  }
}

// min (x - c_k)^2 + b_k over x in [0, 1] and a categorical shape k in {low, middle, high}
// (c = 0.2, 0.5, 0.8; b = 1.0, 0.1, 0.5): choice 1 ("middle") at x = 0.5 gives 0.1, the best;
// `fixed_choice` holds the shape (-1: free).
namespace {
Problem three_shapes(int fixed_choice) {
  static const std::vector<double> c{0.2, 0.5, 0.8}, b{1.0, 0.1, 0.5};
  Problem p;
  Variable shape;
  shape.name = "shape";
  shape.kind = VariableKind::categorical;
  shape.choices = {"low", "middle", "high"};
  shape.fixed_choice = fixed_choice;
  p.variables = {continuous("x", 0, 1), shape};
  p.evaluate = [](const std::vector<double>& x) {
    const auto k = static_cast<std::size_t>(x[1]);
    Evaluation e;
    e.objective = (x[0] - c.at(k)) * (x[0] - c.at(k)) + b.at(k);
    return e;
  };
  return p;
}
}  // namespace

TEST_CASE("optimiser: categorical screening finds the optimum in a non-first choice", "[optimiser]") {
  const Problem p = three_shapes(-1);
  for (const std::string name : {"nlopt:cobyla", "nlopt:ccsaq", "ipopt"}) {
    INFO(name);
    Options o = with(name, 200);
    o.categorical_keep = 2;
    const Result r = minimise(p, o);
    INFO(r.stop_reason);
    REQUIRE(r.feasible);
    CHECK(r.x[1] == 1);
    CHECK(r.x[0] == Approx(0.5).margin(0.01));
    CHECK(r.best.objective == Approx(0.1).margin(1e-3));
    std::set<double> screened;
    for (const auto& h : r.history)
      if (h.phase == "categorical screening") screened.insert(h.x[1]);
    CHECK(screened == std::set<double>{1, 2});  // every other choice, once
  }
}

TEST_CASE("optimiser: a categorical variable held at one choice is neither screened nor changed", "[optimiser]") {
  // Choice 2 ("high") held: its own optimum x = 0.8, 0.5.
  Problem p = three_shapes(2);
  Options o = with("ipopt", 60);
  o.x0 = {0.5, 2};
  const Result r = minimise(p, o);
  REQUIRE(r.feasible);
  CHECK(r.x[1] == 2);
  CHECK(r.x[0] == Approx(0.8).margin(0.01));
  for (const auto& h : r.history) {
    CHECK(h.x[1] == 2);
    CHECK(h.phase != "categorical screening");
  }
  p.variables[1].fixed_choice = 3;  // no such choice
  CHECK_THROWS_WITH(minimise(p, o), Catch::Contains("held at choice 3 of 3"));
}

TEST_CASE("optimiser: a failing region is avoided without a crash", "[optimiser]") {
  // min (x-2)^2 + (y-0.5)^2 s.t. x <= 0.75; the evaluation fails for x > 0.8
  // (ok=false, an exception, or NaN): optimum (0.75, 0.5).
  enum class How { flag, exception, nan };
  for (How how : {How::flag, How::exception, How::nan}) {
    for (const std::string name : {"nlopt:cobyla", "nlopt:auglag_bobyqa", "nlopt:slsqp", "nlopt:ccsaq", "ipopt"}) {
      INFO(name << " failure mode " << static_cast<int>(how));
      Problem p;
      p.variables = {continuous("x", 0, 2), continuous("y", 0, 1)};
      p.constraint_names = {"x_limit"};
      p.evaluate = [how](const std::vector<double>& x) {
        Evaluation e;
        if (x[0] > 0.8) {
          if (how == How::exception) throw std::runtime_error("mesh inverted");
          if (how == How::flag) {
            e.ok = false;
            e.failure_reason = "solver stalled";
            return e;
          }
          e.objective = std::nan("");
        } else {
          e.objective = (x[0] - 2) * (x[0] - 2) + (x[1] - 0.5) * (x[1] - 0.5);
        }
        e.constraints = {x[0] - 0.75};
        return e;
      };
      Options o = with(name, 300);
      o.x0 = {0.95, 0.2};  // the start itself fails
      const Result r = minimise(p, o);
      INFO(r.stop_reason);
      REQUIRE(r.feasible);
      CHECK(r.x[0] == Approx(0.75).margin(0.01));
      CHECK(r.x[1] == Approx(0.5).margin(0.02));
      const std::string reason = how == How::flag ? "solver stalled"
                                 : how == How::exception ? "mesh inverted"
                                                         : "non-finite objective";
      CHECK(any_failure(r, reason));
    }
  }
}

TEST_CASE("optimiser: no design is evaluated twice and cache hits are counted", "[optimiser]") {
  // Integer-only problem: 7 distinct designs exist, so at most 7 real evaluations.
  Problem p;
  p.variables = {integer("n", 0, 6)};
  int counter = 0;
  p.evaluate = [&](const std::vector<double>& x) {
    ++counter;
    Evaluation e;
    e.objective = (x[0] - 4.4) * (x[0] - 4.4);
    return e;
  };
  int reported = 0;
  Options o = with("nlopt:cobyla", 100);
  o.on_evaluation = [&](const Progress& pr) {
    ++reported;
    CHECK_FALSE(pr.cached);
    CHECK(pr.evaluation == reported);
  };
  const Result r = minimise(p, o);
  CHECK(r.x[0] == 4);
  CHECK(counter == r.evaluations);
  CHECK(reported == r.evaluations);
  CHECK(r.evaluations <= 7);
  CHECK(r.cache_hits > 0);
  std::set<double> seen;
  for (const auto& h : r.history) CHECK(seen.insert(h.x[0]).second);

  // NLopt asks for the objective and the constraints of the same point
  // separately: the second request is served from the cache.
  int quadratic_counter = 0;
  const Result q = minimise(constrained_quadratic(&quadratic_counter), with("nlopt:cobyla", 300));
  CHECK(quadratic_counter == q.evaluations);
  CHECK(q.cache_hits >= q.evaluations - 1);
  std::set<std::vector<double>> points;
  for (const auto& h : q.history) CHECK(points.insert(h.x).second);
}

TEST_CASE("optimiser: the evaluation budget is never exceeded", "[optimiser]") {
  // Rosenbrock in 3-D with a constraint: no algorithm converges in 15 evaluations.
  Problem p;
  p.variables = {continuous("a", -2, 2), continuous("b", -2, 2), continuous("c", -2, 2)};
  p.constraint_names = {"disc"};
  int counter = 0;
  p.evaluate = [&](const std::vector<double>& x) {
    ++counter;
    Evaluation e;
    for (int i = 0; i < 2; ++i)
      e.objective += 100 * std::pow(x[i + 1] - x[i] * x[i], 2) + std::pow(1 - x[i], 2);
    e.constraints = {x[0] * x[0] + x[1] * x[1] - 1.5};
    return e;
  };
  for (const std::string& name : algorithm_names()) {
    INFO(name);
    counter = 0;
    const Result r = minimise(p, with(name, 15));
    INFO(r.stop_reason);
    CHECK(counter <= 15);
    CHECK(r.evaluations == counter);
    CHECK(r.evaluations == 15);
    CHECK_THAT(r.stop_reason, Contains("budget"));
  }
}

TEST_CASE("optimiser: an infeasible problem reports the least violation", "[optimiser]") {
  // g = 1 - x - y <= 0 with x, y <= 0.4: the least violation is 0.2 at (0.4, 0.4).
  Problem p;
  p.variables = {continuous("x", 0, 0.4), continuous("y", 0, 0.4)};
  p.constraint_names = {"reach"};
  p.evaluate = [](const std::vector<double>& x) {
    Evaluation e;
    e.objective = x[0] * x[0] + x[1] * x[1];
    e.constraints = {1 - x[0] - x[1]};
    return e;
  };
  for (const std::string name : {"nlopt:cobyla", "nlopt:slsqp", "ipopt"}) {
    INFO(name);
    const Result r = minimise(p, with(name, 200));
    INFO(r.stop_reason);
    CHECK_FALSE(r.feasible);
    REQUIRE(r.best.ok);
    CHECK(r.best.constraints[0] == Approx(0.2).margin(2e-3));
    CHECK_THAT(r.stop_reason, Contains("reach"));
  }
}

TEST_CASE("optimiser: an unknown algorithm is rejected with the valid names", "[optimiser]") {
  Options o;
  o.algorithm = "nlopt:nelder_mead_typo";
  CHECK_THROWS_AS(minimise(constrained_quadratic(), o), std::invalid_argument);
  CHECK_THROWS_WITH(minimise(constrained_quadratic(), o),
                    Contains("nelder_mead_typo") && Contains("nlopt:cobyla") && Contains("nlopt:slsqp") &&
                        Contains("ipopt"));
  Problem bad = constrained_quadratic();
  bad.variables[0].lower = 5;
  CHECK_THROWS_WITH(minimise(bad, Options{}), Contains("'x'"));
}

TEST_CASE("optimiser: multi-start finds the global of two minima", "[optimiser]") {
  // Local minimum at 0.2 (f = 0.5), global at 0.8 (f = 0); the first start is in the local basin.
  Problem p;
  p.variables = {continuous("x", 0, 1)};
  p.evaluate = [](const std::vector<double>& x) {
    Evaluation e;
    e.objective = 1 - std::exp(-std::pow((x[0] - 0.8) / 0.1, 2)) -
                  0.5 * std::exp(-std::pow((x[0] - 0.2) / 0.1, 2));
    return e;
  };
  Options o = with("nlopt:cobyla", 200);
  o.x0 = {0.15};
  const Result single = minimise(p, o);
  CHECK(single.x[0] == Approx(0.2).margin(0.01));  // one start: trapped, as expected

  o.starts = 4;
  for (const std::string name : {"nlopt:cobyla", "nlopt:slsqp"}) {
    INFO(name);
    o.algorithm = name;
    const Result r = minimise(p, o);
    INFO(r.stop_reason);
    CHECK(r.x[0] == Approx(0.8).margin(0.01));
    CHECK(r.best.objective == Approx(0).margin(1e-3));
    std::set<std::string> phases;
    for (const auto& h : r.history) phases.insert(h.phase);
    CHECK(phases.count("start 1") == 1);
    CHECK(phases.count("start 4") == 1);
  }
}

TEST_CASE("optimiser: malformed evaluations are failures and callback errors propagate", "[optimiser]") {
  // The wrong number of constraints is a failure with its reason, never a crash.
  Problem p = constrained_quadratic();
  p.evaluate = [](const std::vector<double>&) {
    Evaluation e;
    e.objective = 1;
    return e;  // no constraints, one expected
  };
  const Result r = minimise(p, with("nlopt:cobyla", 20));
  CHECK_FALSE(r.feasible);
  CHECK_FALSE(r.best.ok);
  CHECK(any_failure(r, "returned 0 constraints, expected 1"));
  CHECK_THAT(r.stop_reason, Contains("every evaluation failed"));

  // An exception from the progress callback stops the solver cleanly and reaches the caller.
  for (const std::string name : {"nlopt:cobyla", "nlopt:slsqp", "ipopt"}) {
    INFO(name);
    Options o = with(name, 100);
    int calls = 0;
    o.on_evaluation = [&](const Progress&) {
      if (++calls == 5) throw std::runtime_error("user abort");
    };
    CHECK_THROWS_WITH(minimise(constrained_quadratic(), o), "user abort");
    CHECK(calls == 5);
  }
}

TEST_CASE("optimiser: evaluations run side by side take the serial run's path", "[optimiser]") {
  // A mixed problem (continuous, integer, categorical) whose gradient neighbours and screening
  // can run concurrently. Each batch runs on its own threads, one per design; the result, the
  // history (designs, values, phases, order) and the count must equal the serial run's, and the
  // budget must hold, including when it runs out in the middle of a gradient.
  Problem p;
  Variable shape;
  shape.name = "shape";
  shape.kind = VariableKind::categorical;
  shape.choices = {"a", "b", "c"};
  p.variables = {continuous("x", 0, 3), continuous("y", 0, 3), integer("n", 0, 8), shape};
  p.constraint_names = {"sum", "n"};
  std::atomic<int> calls{0};
  p.evaluate = [&calls](const std::vector<double>& x) {
    ++calls;
    const double k = 0.3 * x[3];
    Evaluation e;
    e.objective = (x[0] - 2 - k) * (x[0] - 2 - k) + (x[1] - 1) * (x[1] - 1) + 0.1 * (x[2] - 5.3) * (x[2] - 5.3);
    e.constraints = {x[0] + x[1] - 2 - k, 3.5 - x[2]};
    return e;
  };
  Problem side_by_side = p;
  int batches = 0;
  side_by_side.run_concurrently = [&batches](int n, const std::function<void(int)>& task) {
    ++batches;
    std::vector<std::thread> threads;
    for (int i = 0; i < n; ++i) threads.emplace_back(task, i);
    for (auto& t : threads) t.join();
  };
  for (const std::string name : {"ipopt", "nlopt:slsqp", "nlopt:ccsaq"})
    for (int budget : {17, 120}) {
      INFO(name << ", budget " << budget);
      Options o = with(name, budget);
      o.categorical_keep = 2;
      calls = 0;
      const Result serial = minimise(p, o);
      const int serial_calls = calls;
      batches = 0;
      calls = 0;
      const Result concurrent = minimise(side_by_side, o);
      CHECK(batches > 0);
      CHECK(serial_calls == serial.evaluations);
      CHECK(calls >= concurrent.evaluations);  // a prefetched design the budget then refused is extra
      // The held results are the ones used: with budget to spare, nothing is computed twice.
      if (budget == 120) CHECK(calls == concurrent.evaluations);
      if (budget == 17) CHECK_THAT(concurrent.stop_reason, Contains("budget"));
      CHECK(concurrent.evaluations <= budget);
      CHECK(concurrent.x == serial.x);
      CHECK(concurrent.feasible == serial.feasible);
      CHECK(concurrent.evaluations == serial.evaluations);
      CHECK(concurrent.cache_hits == serial.cache_hits);
      CHECK(concurrent.stop_reason == serial.stop_reason);
      REQUIRE(concurrent.history.size() == serial.history.size());
      for (std::size_t i = 0; i < serial.history.size(); ++i) {
        INFO("evaluation " << i + 1);
        CHECK(concurrent.history[i].x == serial.history[i].x);
        CHECK(concurrent.history[i].phase == serial.history[i].phase);
        CHECK(concurrent.history[i].value.objective == serial.history[i].value.objective);
        CHECK(concurrent.history[i].value.constraints == serial.history[i].value.constraints);
      }
    }
}

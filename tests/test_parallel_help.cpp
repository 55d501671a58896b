// Idle task threads lending to a running task (visit_in_order_with_help, fem/core/parallel.hpp):
// the visit's results are the bits of a visit alone, whoever computed what.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "fem/assembly/energy_problem.hpp"
#include "fem/core/parallel.hpp"
#include "fem/forms/make_elastic_form.hpp"
#include "fem/mesh/quadratic_mesh.hpp"
#include "fem/mesh/serendipity_mesh.hpp"
#include "fem/mesh/structured_mesh.hpp"
#include "support/test_problems.hpp"

using namespace softarm::fem;

namespace {

/// Some microseconds of arithmetic whose result depends on i alone.
double work_on(int i) {
  double x = 0.1 * i;
  for (int k = 0; k < 300; ++k) x = std::sin(x + 1e-3 * k) + 1e-4 * i;
  return x;
}

/// Runs `body` as the first of two tasks on two threads, the second ending at once: from then on
/// the second task's thread waits to lend. The thread count is restored after.
template <class Body>
void beside_an_idle_thread(Body body) {
  const int saved = thread_count();
  set_thread_count(2);
  parallel_tasks(2, [&](int task) {
    if (task == 0) body();
  });
  set_thread_count(saved);
}

}  // namespace

TEST_CASE("a visit takes what an idle task thread lent, in order, and gives the bits of a visit alone", "[solver]") {
  constexpr int n = 3000;
  // Alone: each item once, in order, combined in an order-sensitive sum.
  double alone = 0;
  for (int i = 0; i < n; ++i) alone = 0.999 * alone + work_on(i);

  std::vector<double> slot(n);
  long taken = 0;
  int visits = 0;
  beside_an_idle_thread([&] {
    for (; visits < 2000 && taken == 0; ++visits) {
      std::vector<int> order;
      double sum = 0;
      visit_in_order_with_help(
          n,
          [&](int i) {
            order.push_back(i);
            sum = 0.999 * sum + work_on(i);
            return true;
          },
          [&](int i) { slot[i] = work_on(i); },
          [&](int i) {
            order.push_back(i);
            sum = 0.999 * sum + slot[i];
            ++taken;
            return true;
          });
      REQUIRE(order.size() == static_cast<std::size_t>(n));
      for (int i = 0; i < n; ++i) REQUIRE(order[i] == i);
      REQUIRE(std::memcmp(&sum, &alone, sizeof sum) == 0);
    }
  });
  INFO(visits << " visits");
  CHECK(taken > 0);  // the idle thread lent: what was compared is the lent path
}

TEST_CASE("a visit stops where it is told to, and hands back what a lender threw", "[solver]") {
  std::vector<double> slot(2000);
  double sink = 0;  // keeps the visitor's own work from being optimised away
  beside_an_idle_thread([&] {
    // Stopped by own at item 100: nothing after it is visited, and the visit returns.
    int last = -1;
    visit_in_order_with_help(
        2000,
        [&](int i) {
          last = i;
          sink += work_on(i);
          return i < 100;
        },
        [&](int i) { slot[i] = work_on(i); },
        [&](int i) {
          last = i;
          return i < 100;
        });
    CHECK(last == 100);
    // A lender that throws: the visit throws it (tried until the idle thread lends).
    bool thrown = false;
    for (int tries = 0; tries < 2000 && !thrown; ++tries) {
      try {
        visit_in_order_with_help(
            2000,
            [&](int i) {
              sink += work_on(i);
              return true;
            },
            [](int) { throw std::runtime_error("lent item failed"); }, [](int) { return true; });
      } catch (const std::runtime_error& e) {
        CHECK(std::string(e.what()) == "lent item failed");
        thrown = true;
      }
    }
    CHECK(thrown);
    // A visit that stops before the item that threw returns, as a visit alone would.
    for (int tries = 0; tries < 20; ++tries)
      CHECK_NOTHROW(visit_in_order_with_help(
          2000,
          [&](int i) {
            sink += work_on(i);
            return i < 5;
          },
          [](int) { throw std::runtime_error("lent item failed"); }, [](int i) { return i < 5; }));
  });
  CHECK(std::isfinite(sink));
}

TEST_CASE("an elastic body's energy, gradient and tangent are the same bits when an idle thread computes part of it",
          "[solver]") {
  const Mesh mesh = serendipity_from_triquadratic(
      to_quadratic_3d(box_mesh(Eigen::Vector3d::Zero(), Eigen::Vector3d(4, 4, 12), 3, 3, 9)));
  EnergyProblem problem(flattened_positions(mesh), DirichletConstraints{});
  problem.add_form(make_elastic_form(mesh, {softarm::test::dragon_skin_30_ogden(2.0 / 0.7029)}));
  problem.finalize();
  // Two deformed states, evaluated in turn: the elements' lent storage is reused with other values.
  std::vector<Vector> x(2, problem.reference_positions());
  for (int i = 0; i < x[0].size(); ++i) {
    x[0][i] *= 1.0 + 0.02 * std::sin(0.7 * i);
    x[1][i] *= 1.0 - 0.015 * std::cos(0.3 * i);
  }
  const int saved = thread_count();
  set_thread_count(1);  // the elements in their order, as inside a task
  const std::vector<Evaluation> alone = {problem.evaluate(x[0], true, true), problem.evaluate(x[1], true, true)};
  set_thread_count(saved);
  REQUIRE(alone[0].status.ok);
  REQUIRE(alone[1].status.ok);

  int visits = 0, helped = 0;
  beside_an_idle_thread([&] {
    for (; visits < 2000 && helped < 4; ++visits) {
      const long lent = lent_items();
      const Evaluation& want = alone[visits % 2];
      const Evaluation got = problem.evaluate(x[visits % 2], true, true);
      if (lent_items() > lent) ++helped;
      REQUIRE(got.status.ok);
      REQUIRE(std::memcmp(&got.energy, &want.energy, sizeof(double)) == 0);
      REQUIRE(got.gradient.size() == want.gradient.size());
      REQUIRE(std::memcmp(got.gradient.data(), want.gradient.data(), sizeof(double) * want.gradient.size()) == 0);
      REQUIRE(got.hessian.nonZeros() == want.hessian.nonZeros());
      REQUIRE(std::memcmp(got.hessian.valuePtr(), want.hessian.valuePtr(), sizeof(double) * want.hessian.nonZeros()) == 0);
    }
  });
  INFO(visits << " evaluations, " << helped << " of them helped");
  CHECK(helped >= 4);  // the lent path, with storage reused across states
}

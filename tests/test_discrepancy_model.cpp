// The model management of `softarm design` (engine/design/discrepancy_model.hpp): the discrepancy
// g_accurate − g_search between verified designs, as an additive correction whose linear term
// interpolates every verified design. Checked on discrepancies that are exactly linear (which it
// must then reproduce everywhere once the verified designs span the space), against the
// interpolation property, and the trust region's box.
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "engine/design/design_problem.hpp"
#include "engine/design/discrepancy_model.hpp"
#include "fem/core/json_reader.hpp"

using namespace softarm;

namespace {
// A linear discrepancy in 3 variables for 2 constraints: δ(u) = a + B u.
std::vector<double> linear_delta(const std::vector<double>& u) {
  return {0.2 + 0.5 * u[0] - 0.3 * u[1] + 0.1 * u[2], -0.1 - 0.2 * u[0] + 0.05 * u[2]};
}

// The accurate g as the search g plus the discrepancy.
void add_point(engine::DiscrepancyModel& m, const std::vector<double>& u, const std::vector<double>& delta) {
  const std::vector<double> g_search = {0.3 * u[0] - 1, 0.7 * u[1]};  // anything: only the difference counts
  std::vector<double> g_accurate = g_search;
  for (std::size_t i = 0; i < g_accurate.size(); ++i) g_accurate[i] += delta[i];
  m.add(u, g_accurate, g_search);
}
}  // namespace

TEST_CASE("The discrepancy model corrects nothing before a verified design and shifts by it after one",
          "[design][discrepancy]") {
  engine::DiscrepancyModel m;
  CHECK(m.empty());
  CHECK(m.at({0.5, 0.5, 0.5}).empty());
  CHECK(m.describe({"a", "b"}) == "none");
  const std::vector<double> u0 = {0.2, 0.4, 0.6};
  add_point(m, u0, linear_delta(u0));
  // One design: zeroth order, the same shift everywhere.
  for (const auto& u : {u0, std::vector<double>{0.9, 0.1, 0.3}}) {
    const auto d = m.at(u);
    REQUIRE(d.size() == 2);
    CHECK(d[0] == Approx(linear_delta(u0)[0]));
    CHECK(d[1] == Approx(linear_delta(u0)[1]));
  }
}

TEST_CASE("The discrepancy model interpolates every verified design and is exact for a linear discrepancy once "
          "they span the space", "[design][discrepancy]") {
  engine::DiscrepancyModel m;
  const std::vector<std::vector<double>> points = {{0.2, 0.4, 0.6}, {0.5, 0.4, 0.6}, {0.3, 0.9, 0.1}, {0.7, 0.2, 0.5}};
  for (std::size_t k = 0; k < points.size(); ++k) {
    add_point(m, points[k], linear_delta(points[k]));
    // Every design verified so far is reproduced exactly.
    for (std::size_t j = 0; j <= k; ++j) {
      const auto d = m.at(points[j]);
      CHECK(d[0] == Approx(linear_delta(points[j])[0]).margin(1e-8));
      CHECK(d[1] == Approx(linear_delta(points[j])[1]).margin(1e-8));
    }
  }
  // Two designs differing in u[0] alone: exact along that line, beyond the two as well.
  engine::DiscrepancyModel line;
  add_point(line, points[0], linear_delta(points[0]));
  add_point(line, points[1], linear_delta(points[1]));
  const std::vector<double> on_line = {0.95, 0.4, 0.6};
  CHECK(line.at(on_line)[0] == Approx(linear_delta(on_line)[0]));
  // Four affinely independent designs in three variables: exact everywhere.
  for (const auto& u : {std::vector<double>{0, 0, 0}, std::vector<double>{1, 1, 1}, std::vector<double>{0.1, 0.8, 0.4}}) {
    CHECK(m.at(u)[0] == Approx(linear_delta(u)[0]).margin(1e-8));
    CHECK(m.at(u)[1] == Approx(linear_delta(u)[1]).margin(1e-8));
  }
  CHECK(m.points() == 4);
  CHECK(m.centre() == points.back());
}

TEST_CASE("The corrected search stays in a box about the last verified design", "[design][discrepancy]") {
  const engine::DesignConfig config =
      engine::read_design_config(fem::load_json_file(std::string(SOFTARM_SOURCE_DIR) + "/configs/thesis_requirements.json"));
  const std::vector<double> x = engine::baseline_values(config);
  const std::vector<double> u = engine::normalised_design(config, x);
  const std::vector<optimise::Variable> box = engine::trust_region(config, x, 0.25);
  REQUIRE(box.size() == config.variables.size());
  for (std::size_t i = 0; i < box.size(); ++i) {
    const optimise::Variable& v = config.variables[i].variable;
    INFO(v.name);
    CHECK(u[i] >= 0);
    CHECK(u[i] <= 1);
    if (v.kind == optimise::VariableKind::categorical) {
      CHECK(box[i].choices == v.choices);
      continue;
    }
    CHECK(box[i].lower >= v.lower);
    CHECK(box[i].upper <= v.upper);
    CHECK(box[i].lower <= x[i]);
    CHECK(box[i].upper >= x[i]);
    if (v.kind == optimise::VariableKind::continuous)
      CHECK(box[i].upper - box[i].lower <= 0.5 * (v.upper - v.lower) + 1e-12);
    else
      CHECK(box[i].upper > box[i].lower);
  }
  // The thesis' wall (0.466 in 0.3-0.6) is 0.553 of its range; its box is 0.391-0.541.
  CHECK(box[0].name == "wall_thickness_normalised");
  CHECK(box[0].lower == Approx(0.466 - 0.075));
  CHECK(box[0].upper == Approx(0.466 + 0.075));
}

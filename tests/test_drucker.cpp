// Drucker stability and the nominal stress along the standard test paths,
// checked against hand-derived closed forms, plus the `softarm material`
// command.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>

#include "engine/material_command.hpp"
#include "fem/core/input_error.hpp"
#include "fem/forms/make_elastic_form.hpp"
#include "fem/materials/drucker_stability.hpp"
#include "fem/materials/isochoric_law.hpp"
#include "fem/materials/material.hpp"
#include "fem/materials/mooney_rivlin.hpp"
#include "fem/materials/neo_hookean.hpp"
#include "fem/materials/ogden.hpp"
#include "fem/mesh/quadratic_mesh.hpp"
#include "fem/mesh/structured_mesh.hpp"
#include "support/test_problems.hpp"

using namespace softarm::fem;

namespace {

/// For an Ogden law in log strains, w = Σ 2μ_i/α_i² Σ_k e^{α_i ε_k}: with
/// a_k = Σ_i 2μ_i e^{α_i ε_k} the Drucker matrix is [[a1 + a3, a3], [a3, a2 + a3]]
/// (ε3 = −ε1 − ε2). Positive definite ⇔ a1 + a3 > 0 and a1 a2 + a2 a3 + a3 a1 > 0.
double ogden_a(const Ogden& law, double eps) {
  double a = 0;
  for (std::size_t i = 0; i < law.mu().size(); ++i) a += 2 * law.mu()[i] * std::exp(law.alpha()[i] * eps);
  return a;
}

/// Root of f on [lo, hi] (sign change assumed), by plain bisection.
double bisect(const std::function<double(double)>& f, double lo, double hi) {
  const bool lo_positive = f(lo) > 0;
  for (int k = 0; k < 200 && hi - lo > 1e-15; ++k) {
    const double mid = 0.5 * (lo + hi);
    ((f(mid) > 0) == lo_positive ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

const ModeStability& mode(const std::vector<ModeStability>& all, const std::string& name) {
  for (const auto& m : all)
    if (m.mode == name) return m;
  FAIL("no mode " << name);
  return all.front();
}

/// Boundaries are bisected to 1e-7 in ln λ; the closed forms are exact.
constexpr double boundary_tolerance = 1e-6;

}  // namespace

TEST_CASE("Drucker matrix from Jet<3> equals the Ogden closed form", "[drucker]") {
  for (const std::string name : {"dragon_skin_10", "dragon_skin_20", "dragon_skin_30"}) {
    const auto& law = dynamic_cast<const Ogden&>(*builtin_material(name, "m").law);
    for (const auto& [e1, e2] : std::vector<std::pair<double, double>>{{0, 0}, {0.7, -0.35}, {-1.2, 0.4}, {1.5, 1.5}}) {
      INFO(name << " at eps = (" << e1 << ", " << e2 << ")");
      const double a1 = ogden_a(law, e1), a2 = ogden_a(law, e2), a3 = ogden_a(law, -e1 - e2);
      const Eigen::Matrix2d H = drucker_matrix(law, e1, e2);
      const double scale = std::abs(a1) + std::abs(a2) + std::abs(a3);
      CHECK(std::abs(H(0, 0) - (a1 + a3)) <= 1e-12 * scale);
      CHECK(std::abs(H(1, 1) - (a2 + a3)) <= 1e-12 * scale);
      CHECK(std::abs(H(0, 1) - a3) <= 1e-12 * scale);
      CHECK(std::abs(H(1, 0) - a3) <= 1e-12 * scale);
    }
  }
}

TEST_CASE("nominal stress: incompressible Ogden closed forms on the three paths", "[drucker]") {
  // τ1 − τ3 = Σ 2μ/α (λ1^α − λ3^α) and P = (τ1 − τ3)/λ:
  //   uniaxial    λ3 = λ^-1/2: P = Σ 2μ/α (λ^(α−1) − λ^(−α/2−1))
  //   equibiaxial λ3 = λ^-2:   P = Σ 2μ/α (λ^(α−1) − λ^(−2α−1))
  //   planar      λ3 = 1/λ:    P = Σ 2μ/α (λ^(α−1) − λ^(−α−1))
  std::vector<std::pair<std::string, std::shared_ptr<const Ogden>>> laws;
  for (const std::string name : {"dragon_skin_10", "dragon_skin_20", "dragon_skin_30"})
    laws.push_back({name, std::dynamic_pointer_cast<const Ogden>(builtin_material(name, "m").law)});
  laws.push_back({"ogden_N1", std::make_shared<Ogden>(std::vector{0.6}, std::vector{5.0}, VolumetricPolynomial())});
  laws.push_back({"ogden_N2", std::make_shared<Ogden>(std::vector{0.5, -0.1}, std::vector{2.5, -1.5},
                                                      VolumetricPolynomial())});
  for (const auto& [name, law] : laws) {
    for (double lambda : {0.3, 0.8, 1.0, 1.5, 3.0, 4.64}) {
      double uni = 0, eb = 0, pl = 0;
      for (std::size_t i = 0; i < law->mu().size(); ++i) {
        const double m = law->mu()[i], a = law->alpha()[i];
        uni += 2 * m / a * (std::pow(lambda, a - 1) - std::pow(lambda, -a / 2 - 1));
        eb += 2 * m / a * (std::pow(lambda, a - 1) - std::pow(lambda, -2 * a - 1));
        pl += 2 * m / a * (std::pow(lambda, a - 1) - std::pow(lambda, -a - 1));
      }
      INFO(name << " at lambda = " << lambda);
      CHECK(nominal_stress(*law, LoadingMode::uniaxial, lambda) == Approx(uni).margin(1e-13));
      CHECK(nominal_stress(*law, LoadingMode::equibiaxial, lambda) == Approx(eb).margin(1e-13));
      CHECK(nominal_stress(*law, LoadingMode::planar, lambda) == Approx(pl).margin(1e-13));
    }
    // Small-strain limit: uniaxial dP/dλ at λ = 1 is Young's modulus 3 μ0.
    const double h = 1e-5;
    CHECK((nominal_stress(*law, LoadingMode::uniaxial, 1 + h) - nominal_stress(*law, LoadingMode::uniaxial, 1 - h)) /
              (2 * h) ==
          Approx(3 * law->initial_shear_modulus()).epsilon(1e-6));
  }
}

TEST_CASE("neo-Hookean is Drucker stable on the whole scanned range", "[drucker]") {
  const NeoHookean nh(0.5, VolumetricPolynomial({0.1}));
  for (const auto& s : drucker_stability(nh, 0.1, 10.0)) {
    INFO(s.mode);
    CHECK(s.stable_at_rest);
    CHECK_FALSE(s.bounded_below);
    CHECK_FALSE(s.bounded_above);
    CHECK(s.lambda_min == 0.1);
    CHECK(s.lambda_max == 10.0);
  }
}

TEST_CASE("Mooney-Rivlin with C01 < 0 loses stability where the closed form says", "[drucker]") {
  // C10 = 0.5, C01 = −0.3 is Ogden μ = [1, −0.6], α = [2, −2], so with c = λ²
  //   a(c) = 2c − 1.2/c   (a_k = a(c_k)).
  // uniaxial c = (λ², 1/λ, 1/λ): det = a2 (2 a1 + a2); tension fails where
  //   a2 = 2/λ − 1.2 λ = 0  →  λ_max = √(5/3);
  //   compression where 2 a1 + a2 = 0  ⇔  4λ⁴ − 1.2λ³ + 2λ − 2.4 = 0.
  // equibiaxial c = (λ², λ², λ⁻⁴): det = a1 (a1 + 2 a3); compression fails where
  //   a1 = 0  →  λ_min = 0.6^(1/4);  tension where 2λ² − 1.2λ⁻² + 4λ⁻⁴ − 2.4λ⁴ = 0.
  // planar c = (λ², 1, λ⁻²), s = λ² + λ⁻²: det = −2.4 s² + 0.64 s + 10.24, so
  //   s* = (0.64 + √(0.64² + 4·2.4·10.24)) / 4.8 and λ_max² = (s* + √(s*² − 4))/2, λ_min = 1/λ_max.
  const MooneyRivlin mr(0.5, -0.3, VolumetricPolynomial({0.1}));
  const auto result = drucker_stability(mr);

  const double uni_max = std::sqrt(5.0 / 3.0);
  const double uni_min = bisect([](double l) { return 4 * std::pow(l, 4) - 1.2 * std::pow(l, 3) + 2 * l - 2.4; }, 0.5, 1.0);
  const double eb_min = std::pow(0.6, 0.25);
  const double eb_max = bisect(
      [](double l) { return 2 * l * l - 1.2 / (l * l) + 4 / std::pow(l, 4) - 2.4 * std::pow(l, 4); }, 1.0, 1.5);
  const double s_star = (0.64 + std::sqrt(0.64 * 0.64 + 4 * 2.4 * 10.24)) / 4.8;
  const double pl_max = std::sqrt((s_star + std::sqrt(s_star * s_star - 4)) / 2);

  const auto& uni = mode(result, "uniaxial");
  const auto& eb = mode(result, "equibiaxial");
  const auto& pl = mode(result, "planar");
  for (const auto* s : {&uni, &eb, &pl}) {
    CHECK(s->stable_at_rest);
    CHECK(s->bounded_below);
    CHECK(s->bounded_above);
  }
  CHECK(uni.lambda_max == Approx(uni_max).epsilon(boundary_tolerance));
  CHECK(uni.lambda_min == Approx(uni_min).epsilon(boundary_tolerance));
  CHECK(eb.lambda_min == Approx(eb_min).epsilon(boundary_tolerance));
  CHECK(eb.lambda_max == Approx(eb_max).epsilon(boundary_tolerance));
  CHECK(pl.lambda_max == Approx(pl_max).epsilon(boundary_tolerance));
  CHECK(pl.lambda_min == Approx(1 / pl_max).epsilon(boundary_tolerance));
  // Stability depends on the stretch set only: uniaxial compression at λ is
  // equibiaxial tension at λ^(-1/2).
  CHECK(uni.lambda_min == Approx(std::pow(eb.lambda_max, -2)).epsilon(boundary_tolerance));
  CHECK(eb.lambda_min == Approx(std::pow(uni.lambda_max, -0.5)).epsilon(boundary_tolerance));
  WARN("MR C10 = 0.5, C01 = -0.3: uniaxial [" << uni.lambda_min << ", " << uni.lambda_max << "], equibiaxial ["
                                               << eb.lambda_min << ", " << eb.lambda_max << "], planar ["
                                               << pl.lambda_min << ", " << pl.lambda_max << "]");
  // The equivalent Ogden law reports the same boundaries.
  const Ogden ogden({1.0, -0.6}, {2.0, -2.0}, VolumetricPolynomial({0.1}));
  const auto same = drucker_stability(ogden);
  for (std::size_t k = 0; k < 3; ++k) {
    CHECK(same[k].lambda_min == Approx(result[k].lambda_min).epsilon(1e-9));
    CHECK(same[k].lambda_max == Approx(result[k].lambda_max).epsilon(1e-9));
  }
}

TEST_CASE("the elastic form finds the Gauss points where its law is not Drucker stable", "[drucker][forms]") {
  // A distorted axisymmetric Q2 patch in the same Mooney-Rivlin law, stretched uniaxially along z
  // without volume change, x = (λ^(-1/2) r, λ z): every point sees (λ, λ^(-1/2), λ^(-1/2)), unstable
  // exactly beyond λ_max = √(5/3). A uniform dilatation s on top changes J, not the isochoric state.
  const auto mr = std::make_shared<MooneyRivlin>(0.5, -0.3, VolumetricPolynomial({0.1}));
  const Mesh mesh = to_quadratic(rectangle_mesh(2.0, 5.0, 0.0, 3.0, 3, 3, 0.2));
  const auto form = make_elastic_form(mesh, {softarm::test::material(mr)}, VolumetricTreatment::projected_dilatation);
  const Vector X = flattened_positions(mesh);
  const auto stretched = [&](double lambda, double s) {
    Vector x = X;
    for (int n = 0; n < mesh.num_nodes(); ++n) {
      x[2 * n] = s * X[2 * n] / std::sqrt(lambda);
      x[2 * n + 1] = s * X[2 * n + 1] * lambda;
    }
    return x;
  };
  const double lambda_max = std::sqrt(5.0 / 3.0);
  const int points = mesh.num_elements() * 9;  // 3×3 Gauss points per Q2 element
  for (const double s : {1.0, 1.05}) {
    INFO("dilatation " << s);
    CHECK_FALSE(form->material_instability(X).found());
    CHECK_FALSE(form->material_instability(stretched(lambda_max * (1 - 1e-4), s)).found());
    const MaterialInstability beyond = form->material_instability(stretched(lambda_max * (1 + 1e-4), s));
    CHECK(beyond.unstable_points == points);
    CHECK(beyond.checked_points == points);
    CHECK(beyond.max_stretch == Approx(lambda_max * (1 + 1e-4)).epsilon(1e-10));
    CHECK(beyond.min_stretch == Approx(std::pow(lambda_max * (1 + 1e-4), -0.5)).epsilon(1e-10));
    CHECK(beyond.element >= 0);
    CHECK(form->element_corner_node(beyond.element) == mesh.element(beyond.element)[0]);
    // Uniaxial compression is stable down to the closed form's λ_min (0.82 here): 0.9 is inside.
    CHECK_FALSE(form->material_instability(stretched(0.9, s)).found());
  }
}

namespace {
/// A law that is unstable at rest (negative shear modulus); not constructible
/// through the validated laws, so written here.
class NegativeShear final : public IsochoricVolumetricLaw {
 public:
  NegativeShear() : IsochoricVolumetricLaw(VolumetricPolynomial()) {}
  std::string kind() const override { return "negative_shear"; }
  double initial_shear_modulus() const override { return -0.2; }

 protected:
  Jet3 isochoric_energy(const IsochoricStretches& s) const override { return -0.1 * (s.first_invariant() - 3.0); }
  nlohmann::json coefficients_json() const override { return nlohmann::json::object(); }
};
}  // namespace

TEST_CASE("a law unstable at rest is reported as such", "[drucker]") {
  for (const auto& s : drucker_stability(NegativeShear())) {
    CHECK_FALSE(s.stable_at_rest);
    CHECK(std::isnan(s.lambda_min));
    CHECK(std::isnan(s.lambda_max));
  }
  CHECK_THROWS_AS(drucker_stability(NeoHookean(0.5, VolumetricPolynomial()), 1.2, 10), InputError);
  CHECK_THROWS_AS(drucker_stability(NeoHookean(0.5, VolumetricPolynomial()), 0.1, 0.9), InputError);
}

TEST_CASE("Dragon Skin fits: Drucker-stable ranges", "[drucker]") {
  // Despite negative μ_i, a(λ) = Σ 2μ_i λ^α_i stays positive for all λ > 0 for
  // the three fits (the extreme-α terms have μ_i > 0 and the minimum in between
  // is positive), so a_k > 0 for every k and the Drucker matrix is positive
  // definite everywhere: the scan must find no boundary. Checked here on a
  // grid over 1e-3 … 1e3 independently of the scan.
  for (const std::string name : {"dragon_skin_10", "dragon_skin_20", "dragon_skin_30"}) {
    const Material& m = builtin_material(name, "m");
    const auto& law = dynamic_cast<const Ogden&>(*m.law);
    double a_min = 1e300, at = 0;
    for (int k = 0; k <= 6000; ++k) {
      const double eps = std::log(1e-3) + k * (std::log(1e6) / 6000);
      if (ogden_a(law, eps) < a_min) {
        a_min = ogden_a(law, eps);
        at = std::exp(eps);
      }
    }
    const double hi = std::max(10.0, 1.1 * (1 + m.elongation_at_break));
    const auto result = drucker_stability(law, 0.1, hi);
    std::ostringstream report;
    report << name << " (mu0 = " << law.initial_shear_modulus() << " MPa): min_lambda a(lambda) = " << a_min
           << " at lambda = " << at << "; Drucker-stable:";
    for (const auto& s : result) {
      report << "  " << s.mode << " [" << (s.bounded_below ? "" : "<=") << s.lambda_min << ", "
             << (s.bounded_above ? "" : ">=") << s.lambda_max << "]";
      CHECK(s.stable_at_rest);
      CHECK(s.bounded_below == (a_min <= 0));
      CHECK(s.bounded_above == (a_min <= 0));
      // The range must reach the stretch at break for the fit to be usable up to failure.
      CHECK(s.lambda_max >= 1 + m.elongation_at_break);
    }
    WARN(report.str());
    CHECK(a_min > 0);
  }
}

namespace {
/// Runs `softarm <args>` through add_material_command, capturing stdout.
std::string run_material_command(const std::vector<std::string>& args) {
  CLI::App app("softarm");
  softarm::engine::add_material_command(app);
  std::vector<std::string> argv_strings{"softarm"};
  argv_strings.insert(argv_strings.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& s : argv_strings) argv.push_back(s.data());
  std::ostringstream captured;
  auto* old = std::cout.rdbuf(captured.rdbuf());
  try {
    app.parse(static_cast<int>(argv.size()), argv.data());
  } catch (...) {
    std::cout.rdbuf(old);
    throw;
  }
  std::cout.rdbuf(old);
  return captured.str();
}
}  // namespace

TEST_CASE("softarm material list / check", "[drucker][cli]") {
  const std::string list = run_material_command({"material", "list"});
  for (const auto& name : builtin_material_names()) CHECK(list.find(name) != std::string::npos);
  const auto list_json = nlohmann::json::parse(run_material_command({"material", "list", "--json"}));
  REQUIRE(list_json.size() == builtin_material_names().size());
  CHECK(list_json[2]["mu0_MPa"].get<double>() == Approx(0.1153));

  const auto check = nlohmann::json::parse(run_material_command({"material", "check", "dragon_skin_30", "--json"}));
  CHECK(check["name"] == "dragon_skin_30");
  REQUIRE(check["drucker_stability"].size() == 3);
  CHECK(check["drucker_stability"][0]["mode"] == "uniaxial");
  CHECK(check["warnings"].empty());

  // A custom unstable law in a file: the text report warns that the stable
  // range ends before the stretch at break.
  const auto file = std::filesystem::temp_directory_path() / "softarm_test_unstable_material.json";
  {
    std::ofstream out(file);
    out << R"({"name": "bad_fit", "law": "mooney_rivlin", "C10_MPa": 0.5, "C01_MPa": -0.3, "D_per_MPa": [0.1],
              "density_g_cm3": 1.1, "elongation_at_break_percent": 300})";
  }
  const std::string text = run_material_command({"material", "check", file.string()});
  std::filesystem::remove(file);
  INFO(text);
  CHECK(text.find("uniaxial") != std::string::npos);
  CHECK(text.find("1.29099") != std::string::npos);  // √(5/3)
  CHECK(text.find("WARNING: uniaxial") != std::string::npos);

  CHECK_THROWS_AS(run_material_command({"material", "check", "no_such_material"}), InputError);
}

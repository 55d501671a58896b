// Benchmark (not a test): what a law's closed-form derivatives save over the jets.
//
// Every Gauss point asks its law for W(c1, c2, c3) with the gradient and Hessian in the eigenvalues
// of C (HyperelasticLaw::principal_energy_at). Ogden and Saint Venant-Kirchhoff give them in closed
// form; the jets (fem/core/jet.hpp) are the reference every law has. This benchmark times both ways,
// interleaved, in one run:
//  1. per Gauss point: evaluate_principal with its tangent, for each built-in material, over a set
//     of deformation gradients (stretches 0.5 to 3, shear, rotation), ns per point: once with C
//     block-diagonal in (x, y) and z, as axisymmetric kinematics give it (one Jacobi rotation finds
//     its eigenvalues), once with C full, as the 3D scenes give it (symmetric_eigen3's closed form
//     or iterative solver). Saint Venant-Kirchhoff's closed form is its tensor form (no eigenvalues);
//     through the jets it goes through the eigenvalues as every other law. With C block-diagonal, the
//     closed form also with its tangent on the axisymmetric Q9's five components of F alone
//     (closed_5_ns: what that element asks for);
//  2. a whole rra scene (default: the thesis RRA) with its tube and ring laws wrapped so that they
//     answer through the jets: time, Newton iterations and the last extension, which must agree.
//
// Usage: bench_material_law [config] [--points N] [--repeat N] [--threads T]
#include <Eigen/Geometry>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "benchmarks/bench_options.hpp"
#include "benchmarks/bench_scene.hpp"
#include "benchmarks/bench_stats.hpp"
#include "fem/core/input_error.hpp"
#include "fem/core/parallel.hpp"
#include "fem/elements/axisymmetric_quad.hpp"
#include "fem/materials/material.hpp"
#include "fem/materials/principal_stress.hpp"
#include "fem/scenes/rra_scene.hpp"

using namespace softarm;

namespace {

/// A law that answers every question as `law` does, but principal_energy_at through the jets.
class ThroughJets final : public fem::HyperelasticLaw {
 public:
  explicit ThroughJets(std::shared_ptr<const fem::HyperelasticLaw> law) : law_(std::move(law)) {}
  std::string kind() const override { return law_->kind(); }
  fem::Jet3 principal_energy(const fem::Jet3& c1, const fem::Jet3& c2, const fem::Jet3& c3) const override {
    return law_->principal_energy(c1, c2, c3);
  }
  fem::VolumetricResponse volumetric(double J) const override { return law_->volumetric(J); }
  bool has_volumetric_split() const override { return law_->has_volumetric_split(); }
  double initial_shear_modulus() const override { return law_->initial_shear_modulus(); }
  double initial_bulk_modulus() const override { return law_->initial_bulk_modulus(); }
  nlohmann::json to_json() const override { return law_->to_json(); }

 private:
  std::shared_ptr<const fem::HyperelasticLaw> law_;
};

/// Deformation gradients over the range the scenes meet: stretch, shear and a rotation each; the
/// shear in the (x, y) plane only where `full` is false (C block-diagonal), out of it too where true.
std::vector<fem::Mat3> deformations(int count, bool full) {
  std::vector<fem::Mat3> F;
  for (int k = 0; k < count; ++k) {
    const double t = (k + 0.5) / count;
    fem::Mat3 stretch = fem::Mat3::Identity();
    stretch(0, 0) = 0.5 + 2.5 * t;
    stretch(1, 1) = 1.0 / std::sqrt(stretch(0, 0)) * (1.0 + 0.1 * std::sin(7.0 * t));
    stretch(2, 2) = 1.0 / (stretch(0, 0) * stretch(1, 1)) * (1.0 + 0.02 * std::cos(5.0 * t));
    stretch(0, 1) = 0.3 * std::sin(11.0 * t);
    if (full) stretch(0, 2) = 0.2 * std::cos(13.0 * t), stretch(1, 2) = 0.15 * std::sin(17.0 * t);
    F.push_back(Eigen::AngleAxisd(3.0 * t, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix() * stretch);
  }
  return F;
}

/// ns per evaluate_principal (with tangent) of `law` over F, the tangent on the components `active`
/// of F; `sink` keeps the work from being elided.
template <std::size_t N>
double ns_per_point(const fem::HyperelasticLaw& law, const std::vector<fem::Mat3>& F, double& sink,
                    const std::array<int, N>& active) {
  const auto start = std::chrono::steady_clock::now();
  for (const auto& f : F)
    if (const auto s = fem::evaluate_principal<static_cast<int>(N)>(law, f, true, active)) sink += s->A(0, 0) + s->W;
  return 1e9 * bench::seconds_since(start) / static_cast<double>(F.size());
}

void time_points(int points, int repeat, bool full) {
  const auto F = deformations(points, full);
  double sink = 0;
  std::printf("evaluate_principal with its tangent, %d deformation gradients, C %s, median of %d\n", points,
              full ? "full (3D)" : "block-diagonal (axisymmetric)", repeat);
  // Block-diagonal C: also the closed form with the tangent on the axisymmetric Q9's five components.
  std::printf("%-24s %-24s %12s %12s %7s%s\n", "material", "law", "closed_ns", "jets_ns", "ratio",
              full ? "" : "   closed_5_ns");
  for (const auto& name : fem::builtin_material_names()) {
    const auto law = fem::builtin_material(name, "bench").law;
    const ThroughJets jets(law);
    std::vector<double> closed_ns, jets_ns, five_ns;
    for (int k = 0; k < repeat; ++k) {
      closed_ns.push_back(ns_per_point(*law, F, sink, fem::kAllComponents));
      jets_ns.push_back(ns_per_point(jets, F, sink, fem::kAllComponents));
      if (!full) five_ns.push_back(ns_per_point(*law, F, sink, fem::axisym::kActiveComponents));
    }
    const double c = bench::median(closed_ns), j = bench::median(jets_ns);
    std::printf("%-24s %-24s %12.1f %12.1f %6.2fx", name.c_str(), law->kind().c_str(), c, j, j / c);
    if (!full) std::printf(" %14.1f", bench::median(five_ns));
    std::printf("\n");
  }
  std::printf("(checksum %.6g)\n\n", sink);
}

void time_scene(const fem::RraSceneSpec& closed, int repeat) {
  fem::RraSceneSpec jets = closed;
  jets.tube_material.law = std::make_shared<ThroughJets>(closed.tube_material.law);
  jets.ring_material.law = std::make_shared<ThroughJets>(closed.ring_material.law);
  std::vector<double> times[2];
  fem::RraResult last[2];
  for (int k = 0; k < repeat; ++k)
    for (int way = 0; way < 2; ++way) {
      const auto start = std::chrono::steady_clock::now();
      last[way] = fem::run_rra_scene(way == 0 ? closed : jets);
      times[way].push_back(bench::seconds_since(start));
    }
  std::printf("the rra scene's whole curve, %d thread(s), median of %d, interleaved\n", fem::thread_count(), repeat);
  std::printf("%-12s %8s %7s %7s %18s\n", "derivatives", "time_s", "steps", "newton", "last_extension_mm");
  for (int way = 0; way < 2; ++way) {
    const auto& r = last[way];
    std::printf("%-12s %8.3f %7d %7d %18.12f\n", way == 0 ? "closed form" : "jets", bench::median(times[way]),
                r.path.path.stats.steps, r.path.path.stats.newton_iterations,
                r.curve.empty() ? 0.0 : r.curve.back().extension_mm);
  }
  std::printf("ratio jets / closed form: %.3f\n", bench::median(times[1]) / bench::median(times[0]));
}

}  // namespace

int main(int argc, char** argv) try {
  std::string config = "configs/rra_thesis.json";
  int points = 200000, repeat = 5, threads = 1;
  CLI::App app{"a law's closed-form derivatives against the jets: per Gauss point and on an rra scene"};
  app.add_option("config", config, "an rra scene config");
  app.add_option("--points", points, "deformation gradients timed per material")->check(CLI::Range(1, 100000000));
  app.add_option("--repeat", repeat, "runs of each (the median is printed)")->check(CLI::Range(1, 1000));
  app.add_option("--threads", threads, "threads of the scene's runs")->check(CLI::Range(1, 256));
  if (const auto code = bench::parse_or_exit(app, argc, argv)) return *code;
  fem::set_thread_count(threads);
  const auto scene = bench::scene_of_kind(config, "rra", "bench_material_law");
  if (!scene) return 2;
  time_points(points, repeat, false);
  time_points(points, repeat, true);
  time_scene(scene->rra, repeat);
  return 0;
} catch (const fem::InputError& e) {
  std::fprintf(stderr, "%s\n", e.what());
  return 2;
}

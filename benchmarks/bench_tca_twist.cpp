// A 3CA's torsion at rest, bonded at both ends (fem/scenes/twist_compliance.hpp): the whole 3D
// model's twist per unit torque against the spatial cell rod's, on its cells' GJ alone and with
// bonded end cells through N rings in place of the cells' GJ there.
//
//   bench_tca_twist [tca or spl config] [--segment N] [--end-rings 1,2,3] [--no-3d] [--axial-level N]
//   --segment N: an SPL config's segment N (1–3) as its cell rod sees it (spl_segment_cell_scene)
//   --no-3d: skip the whole 3D model (a thesis segment at the cells' layers is large)
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "benchmarks/bench_options.hpp"
#include "benchmarks/bench_scene.hpp"
#include "benchmarks/bench_stats.hpp"
#include "fem/core/input_error.hpp"
#include "fem/scenes/scene_config.hpp"
#include "fem/scenes/spl_cell_rod.hpp"
#include "fem/scenes/tca_cell_rod.hpp"
#include "fem/scenes/twist_compliance.hpp"

using namespace softarm;


int main(int argc, char** argv) try {
  std::string config = "configs/tca_thesis.json";
  std::vector<int> end_rings_asked{1, 2, 3};
  int segment = 0, axial_level = 0;
  bool no_3d = false;
  CLI::App app{"a 3CA's torsion at rest, bonded at both ends: the whole 3D model against the spatial cell rod"};
  app.add_option("config", config, "a tca config, or an spl config with --segment");
  app.add_option("--segment", segment, "an spl config's segment N as its cell rod sees it")
      ->check(CLI::Range(1, 3))
      ->default_str("none (a tca config)");
  app.add_option("--end-rings", end_rings_asked, "the rod also with bonded end cells through each of these ring counts")
      ->delimiter(',')
      ->check(CLI::Range(1, 100));
  app.add_option("--axial-level", axial_level, "element layers along the axis as at mesh level N")
      ->check(CLI::Range(1, 8))
      ->default_str("the config's");
  app.add_flag("--no-3d", no_3d, "skip the whole 3D model");
  if (const auto code = bench::parse_or_exit(app, argc, argv)) return *code;
  const bool whole = !no_3d;
  const fem::SceneConfig scene = fem::load_scene_config(config);
  fem::TcaSceneSpec spec;
  if (scene.scene == "spl") {
    if (segment < 1 || segment > 3) {
      std::fprintf(stderr, "bench_tca_twist: an spl config needs --segment 1, 2 or 3\n");
      return 2;
    }
    spec = fem::spl_segment_cell_scene(scene.spl, segment - 1, 1);
  } else if (scene.scene == "tca") {
    spec = scene.tca;
  } else {
    std::fprintf(stderr, "bench_tca_twist: %s is a \"%s\" scene, not tca or spl\n", config.c_str(), scene.scene.c_str());
    return 2;
  }
  if (axial_level > 0) spec.axial_level = axial_level;
  const int n = spec.design.actuator.ring_count;
  std::printf("%s%s: %d rings, length %.2f mm, cap %.2f mm, pitch %.4f mm\n", config.c_str(),
              segment ? (" segment " + std::to_string(segment)).c_str() : "", n, spec.design.actuator.length_mm,
              spec.design.actuator.end_cap_thickness_mm, spec.design.actuator.pitch());
  std::vector<int> end_rings = {0};
  for (const int rings : end_rings_asked) {
    if (fem::end_cell_rings(rings, n) > 0) end_rings.push_back(rings);
    else std::printf("ends through %d rings: %s\n", rings, fem::no_end_cells_note(rings, n).c_str());
  }
  double solid = 0;
  if (whole) {
    const auto t0 = std::chrono::steady_clock::now();
    solid = fem::tca_twist_compliance(spec);
    std::printf("3D, bonded at both ends (its antisymmetric half, or the full model with symmetry off): %.6e rad/(N·mm), GJ_eff = L/C = %.1f N·mm² (%.1f s)\n", solid,
                spec.design.actuator.length_mm / solid, bench::seconds_since(t0));
  }
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<double> rod = fem::tca_rod_twist_compliances(spec, end_rings);
  std::printf("the rod's cells and end cells at rest: %.1f s\n%-28s %14s %12s %10s\n", bench::seconds_since(t0), "rod",
              "C_rad_per_Nmm", "GJ_eff_Nmm2", "vs_3D_pct");
  for (std::size_t i = 0; i < rod.size(); ++i) {
    const std::string name = end_rings[i] == 0 ? "cells' GJ alone" : "ends through " + std::to_string(end_rings[i]) + " rings";
    std::printf("%-28s %14.6e %12.1f", name.c_str(), rod[i], spec.design.actuator.length_mm / rod[i]);
    if (solid > 0) std::printf(" %10.3f", 100 * (rod[i] / solid - 1));
    std::printf("\n");
  }
  return 0;
} catch (const fem::InputError& e) {
  std::fprintf(stderr, "%s\n", e.what());
  return 2;
}

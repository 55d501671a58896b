// A 3CA's torsion at rest, bonded at both ends (fem/scenes/twist_compliance.hpp): the whole 3D
// model's twist per unit torque against the spatial cell rod's, on its cells' GJ alone and with
// bonded end cells through N rings in place of the cells' GJ there.
//
//   bench_tca_twist [tca or spl config] [--segment N] [--end-rings 1,2,3] [--no-3d] [--axial-level N]
//   --segment N: an SPL config's segment N (1–3) as its cell rod sees it (spl_segment_cell_scene)
//   --no-3d: skip the whole 3D model (a thesis segment's full model at the cells' layers is large)
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "benchmarks/bench_scene.hpp"
#include "fem/reduced/spatial_cell_rod.hpp"
#include "fem/scenes/scene_config.hpp"
#include "fem/scenes/spl_cell_rod.hpp"
#include "fem/scenes/tca_cell.hpp"
#include "fem/scenes/twist_compliance.hpp"

using namespace softarm;

namespace {
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

int main(int argc, char** argv) {
  std::string config = "configs/tca_thesis.json", rings_arg = "1,2,3";
  int segment = 0, axial_level = 0;
  bool whole = true;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--segment" && i + 1 < argc) segment = std::atoi(argv[++i]);
    else if (a == "--end-rings" && i + 1 < argc) rings_arg = argv[++i];
    else if (a == "--axial-level" && i + 1 < argc) axial_level = std::atoi(argv[++i]);
    else if (a == "--no-3d") whole = false;
    else config = a;
  }
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
  // The cells at rest: their GJ (the rod's tables need a rest state only).
  fem::SpatialCellPiece piece;
  piece.length_mm = spec.design.actuator.length_mm;
  piece.cap_mm = spec.design.actuator.end_cap_thickness_mm;
  fem::TcaSceneSpec rest = spec;
  rest.chamber_pressure_kPa = {0, 0, 0};
  rest.output_pressures_kPa.clear();
  for (int ring : fem::cell_rod_rings(n)) {
    auto t0 = std::chrono::steady_clock::now();
    const fem::TcaCellResult cell = fem::run_tca_cell(rest, ring);
    piece.cells.push_back(fem::spatial_cell_table(cell, 0));
    const double gj = fem::cell_torsion_stiffness(rest, ring);
    piece.cells.back().torsion_compliance_per_Nmm2 = 1 / gj;
    std::printf("cell about ring %d (z = %.2f mm): GJ %.1f N·mm² (%.1f s)\n", ring, cell.ring_centre_z_mm, gj,
                seconds_since(t0));
  }
  fem::SpatialCellRodSpec rod;
  rod.pieces = {piece};
  const double cells_only = fem::spatial_cell_rod_twist_compliance(rod, 0);
  double solid = 0;
  if (whole) {
    auto t0 = std::chrono::steady_clock::now();
    solid = fem::tca_twist_compliance(spec);
    std::printf("3D, bonded at both ends (full model): %.6e rad/(N·mm), GJ_eff = L/C = %.1f N·mm² (%.1f s)\n", solid,
                piece.length_mm / solid, seconds_since(t0));
  }
  std::printf("%-28s %14s %12s %10s\n", "rod", "C_rad_per_Nmm", "GJ_eff_Nmm2", "vs_3D");
  const auto row = [&](const std::string& name, double c) {
    std::printf("%-28s %14.6e %12.1f %10s\n", name.c_str(), c, piece.length_mm / c,
                solid > 0 ? (std::to_string(100 * (c / solid - 1)).substr(0, 6) + " %").c_str() : "-");
  };
  row("cells' GJ alone", cells_only);
  std::stringstream list(rings_arg);
  for (std::string item; std::getline(list, item, ',');) {
    const int rings = std::atoi(item.c_str());
    if (fem::end_cell_rings(rings, n) == 0) {
      std::printf("ends through %d rings: %s\n", rings, fem::no_end_cells_note(rings, n).c_str());
      continue;
    }
    fem::SpatialCellRodSpec with = rod;
    auto t0 = std::chrono::steady_clock::now();
    for (const fem::TcaEnd end : {fem::TcaEnd::bottom, fem::TcaEnd::top}) {
      fem::SpatialEndTable t;
      t.at_top = end == fem::TcaEnd::top;
      t.length_mm = rings * spec.design.actuator.pitch();
      t.level = {0, 1};
      t.rotation_rad = {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
      t.elongation_mm = {0, 0};
      t.twist_compliance_per_Nmm = fem::end_cell_twist_compliance(spec, end, rings);
      std::printf("  %s end through %d rings (%.2f mm): %.6e rad/(N·mm), cells over the same length %.6e\n",
                  t.at_top ? "top" : "bottom", rings, t.length_mm, t.twist_compliance_per_Nmm,
                  t.length_mm / (1 / piece.cells[t.at_top ? piece.cells.size() - 1 : 0].torsion_compliance_per_Nmm2));
      with.pieces[0].ends.push_back(t);
    }
    row("ends through " + std::to_string(rings) + " rings (" + std::to_string(seconds_since(t0)).substr(0, 5) + " s)",
        fem::spatial_cell_rod_twist_compliance(with, 0));
  }
  return 0;
}

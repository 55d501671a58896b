// The ring-pitch cell of a 3CA config (fem/scenes/tca_cell.hpp): its free stretch and
// curvature along the pressure ramp at chosen rings, and the bending angle they add up to
// over the ringed length, for comparison with the whole 3CA's curve (gravity off).
//
//   bench_tca_cell [config] [--rings 1,15,30] [--axial-level N] [--threads N]
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "fem/core/parallel.hpp"
#include "fem/scenes/scene_config.hpp"
#include "fem/scenes/tca_cell.hpp"

using namespace softarm;

int main(int argc, char** argv) {
  std::string config = "configs/tca_thesis.json", rings_arg;
  int axial_level = -1;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--rings" && i + 1 < argc) rings_arg = argv[++i];
    else if (a == "--axial-level" && i + 1 < argc) axial_level = std::atoi(argv[++i]);
    else if (a == "--threads" && i + 1 < argc) fem::set_thread_count(std::atoi(argv[++i]));
    else config = a;
  }
  auto scene = fem::load_scene_config(config);
  if (scene.scene != "tca") {
    std::fprintf(stderr, "bench_tca_cell: %s is not a tca scene\n", config.c_str());
    return 2;
  }
  fem::TcaSceneSpec spec = scene.tca;
  if (axial_level >= 0) spec.axial_level = axial_level;
  const int n = spec.design.actuator.ring_count;
  std::vector<int> rings;
  if (rings_arg.empty()) rings = {1, (n + 1) / 2, n};
  std::stringstream list(rings_arg);
  for (std::string item; std::getline(list, item, ',');) rings.push_back(std::atoi(item.c_str()));
  std::printf("%s: %d rings, pitch %.4f mm, threads %d\n", config.c_str(), n, spec.design.actuator.pitch(),
              fem::thread_count());
  for (int ring : rings) {
    const auto r = fem::run_tca_cell(spec, ring);
    std::printf("\nring %d at z = %.3f mm: %s, %s, %d dofs, %d steps, %d Newton, %.1f s; %s%s\n", ring,
                r.ring_centre_z_mm, r.model.name.c_str(), r.element_name.c_str(), r.dofs, r.path.path.stats.steps,
                r.path.path.stats.newton_iterations, r.seconds, fem::to_string(r.path.outcome),
                r.path.diagnosis.empty() ? "" : (": " + r.path.diagnosis).c_str());
    std::printf("%12s %10s %14s %14s %12s %10s %14s %12s\n", "pressure_kPa", "stretch", "curv_deg_mm", "deg_per_pitch",
                "volume_mm3", "gap_mm", "EI_Nmm2", "EA_N");
    for (const auto& s : r.states) {
      std::printf("%12.2f %10.5f %14.6f %14.4f %12.1f %10.2e", s.pressure_kPa, s.stretch,
                  s.curvature_per_mm * 180 / 3.14159265358979, s.curvature_per_mm * r.pitch_mm * 180 / 3.14159265358979,
                  s.chamber_volume_mm3, s.plane_gap_mm);
      if (s.bending_compliance_per_Nmm2 > 0)
        std::printf(" %14.1f %12.2f\n", 1 / s.bending_compliance_per_Nmm2, 1 / s.axial_compliance_per_N);
      else
        std::printf(" %14s %12s\n", s.is_output ? "-" : "", s.is_output ? "-" : "");
    }
  }
  return 0;
}

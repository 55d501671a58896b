#include "fem/scenes/tube_peaks.hpp"

#include <chrono>

#include "fem/core/parallel.hpp"

namespace softarm::fem {

TubePeak TubePeakMaps::at(const std::array<double, 3>& chamber_stretch) const {
  TubePeak out;
  for (int n = 0; n < 3; ++n) {
    const RraCalibration::Peaks peaks = segment[n].peaks_at(chamber_stretch[n]);
    if (out.segment == 0 || peaks.stretch > out.stretch) out = {peaks.stretch, n + 1, peaks.extrapolated};
  }
  return out;
}

TubePeakMaps tube_peak_maps(const SplSceneSpec& arm, const std::array<double, 3>& largest_chamber_stretch,
                            double max_pressure_kPa, int rra_mesh_level, double averaging_radius_mm) {
  const auto t0 = std::chrono::steady_clock::now();
  TubePeakMaps maps;
  parallel_tasks(3, [&](int n) {
    RraSceneSpec rra;
    rra.design = arm.design.segments[n].actuator;
    rra.tube_material = arm.tube_material;
    rra.ring_material = arm.ring_material;
    rra.mesh_level = rra_mesh_level;
    rra.peak_averaging_radius_mm = averaging_radius_mm;
    maps.segment[n] = calibrate_rra_to_stretch(rra, largest_chamber_stretch[n], max_pressure_kPa);
  });
  maps.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return maps;
}

}  // namespace softarm::fem

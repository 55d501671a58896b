#pragma once
// The tube's local peaks in any pose of an arm: each segment's chamber-axis stretch
// (chamber_stretch.hpp) read through that segment's lone-RRA FEM map from an actuator's mean axial
// stretch to the tube's peaks averaged over the criteria's ball (rra_calibration.hpp), as the
// design's check reads them along its bending path. The quantity burst criterion (b) and the
// durability strain judge (spec §4).
#include <array>

#include "fem/materials/burst_criteria.hpp"
#include "fem/scenes/rra_calibration.hpp"
#include "fem/scenes/spl_scene.hpp"

namespace softarm::fem {

struct TubePeak {
  double stretch = 1;        // the tube's peak principal stretch, the largest over the segments
  int segment = 0;           // 1–3: where it is (0: none judged)
  bool extrapolated = false; // read beyond that segment's lone-RRA FEM path
};

struct TubePeakMaps {
  std::array<RraCalibration, 3> segment;  // per segment, its lone RRA's map
  double seconds = 0;

  /// The peak at chamber-axis stretches `chamber_stretch` (per segment).
  TubePeak at(const std::array<double, 3>& chamber_stretch) const;
};

/// Each segment's map of `arm` (its design and materials), its lone RRA's FEM path covering
/// `largest_chamber_stretch` of that segment (calibrate_rra_to_stretch, at most `max_pressure_kPa`),
/// on RRA mesh level `rra_mesh_level`, the peaks averaged over `averaging_radius_mm`; the three side
/// by side.
TubePeakMaps tube_peak_maps(const SplSceneSpec& arm, const std::array<double, 3>& largest_chamber_stretch,
                            double max_pressure_kPa, int rra_mesh_level = 1,
                            double averaging_radius_mm = kDefaultPeakAveragingRadius_mm);

}  // namespace softarm::fem

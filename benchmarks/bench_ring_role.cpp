// What the ABS rings do in the 3D 3CA, and what the rod sees of it (docs/reduced-model.md,
// Where the rod's error comes from; What the rings do). The thesis 3CA (TcaDesign defaults,
// Dragon Skin 30 throughout), 3D Hex20/P1 at 2x2x2 points, level 1, under
//   - its own weight across the axis, unpressurised: the sag (deg),
//   - ten times its weight along the axis: the tip's stretch (mm),
//   - chambers 2 and 3 at 50 kPa, no gravity: the bending (deg),
// with three kinds of ring: ABS (the thesis), ABS half as thick, and rings of
// the tube's own silicone (a plain, ungrooved tube). Beside them the planar rod,
// free (its default) and with ring-confined walls (model.ring_confinement).
// Nine 3D runs, about 15 minutes on one core; --rod-only prints the rods alone.
//
//   build/benchmarks/bench_ring_role [--rod-only]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "benchmarks/bench_options.hpp"
#include "benchmarks/bench_stats.hpp"
#include "fem/core/input_error.hpp"
#include "fem/materials/material.hpp"
#include "fem/reduced/arm_rod.hpp"
#include "fem/scenes/tca_scene.hpp"
#include "fem/core/angles.hpp"

using namespace softarm::fem;
namespace bench = softarm::bench;

namespace {
constexpr double kG = 9.80665, kDeg = softarm::fem::kDeg;

struct Load {
  const char* name;
  double pressure_kPa;   // chambers 2 and 3
  double gravity_x, gravity_axial;  // m/s²: across the axis (against the bend), along it (away from the clamp)
  bool stretch;          // report the tip's axial displacement (mm), else the bending (deg)
};

struct Rings {
  const char* name;
  std::string material;
  double thickness_normalised;
};

double solid(const Rings& r, const Load& l, double& seconds) {
  TcaSceneSpec spec;
  spec.design.actuator.ring_diameter_mm = r.thickness_normalised * spec.design.actuator.pitch();
  spec.tube_material = spec.sheath_material = builtin_material("dragon_skin_30", "tube");
  spec.ring_material = builtin_material(r.material, "rings");
  spec.mesh_level = 1;
  spec.element_order = 2;
  spec.serendipity = true;
  spec.integration = ElementIntegration::reduced;
  const double p = std::max(l.pressure_kPa, 1e-3);  // a path needs a pressure to ramp: 1 Pa is nothing here
  spec.chamber_pressure_kPa = {0.0, p, p};
  spec.gravity_m_s2 = Eigen::Vector3d(-l.gravity_x, 0.0, -l.gravity_axial);
  spec.output_pressures_kPa = {p};
  const auto t0 = std::chrono::steady_clock::now();
  const TcaResult res = run_tca_scene(spec);
  seconds = bench::seconds_since(t0);
  const TcaState& s = res.states.back();
  return l.stretch ? -s.tip_displacement_mm.z() : s.bending_angle_deg;
}

double rod(const Rings& r, const Load& l, bool confined) {
  ArmRodSpec spec;
  RodPiece piece;
  piece.kind = RodPiece::Kind::tca;
  piece.design.actuator.ring_diameter_mm = r.thickness_normalised * piece.design.actuator.pitch();
  spec.pieces = {piece};
  spec.tube = spec.sheath = builtin_material("dragon_skin_30", "tube");
  spec.rings = builtin_material(r.material, "rings");
  spec.nodes_per_segment = 17;
  spec.ring_confinement = confined;
  const ArmRod a(spec);
  RodLoad load;
  load.chamber_pressure_kPa = {{0.0, l.pressure_kPa, l.pressure_kPa}};
  load.gravity_m_s2 = {-l.gravity_x, -l.gravity_axial};
  load.clamp_angle_rad = -90 / kDeg;  // hanging: the axis points down
  const RodState st = a.follow(load, 12);
  return l.stretch ? -(st.z.back() + a.length_mm()) : a.tip_rotation(st, load) * kDeg;
}
}  // namespace

int main(int argc, char** argv) try {
  bool rod_only = false;
  CLI::App app{"what the ABS rings do in the thesis 3CA, 3D against the planar rods (about 15 minutes on one core)"};
  app.add_flag("--rod-only", rod_only, "the rods alone, no 3D runs");
  if (const auto code = bench::parse_or_exit(app, argc, argv)) return *code;
  const Load loads[] = {{"sag under its weight (deg)", 0, kG, 0, false},
                        {"stretch under 10x its weight (mm)", 0, 0, 10 * kG, true},
                        {"bending at 50 kPa (deg)", 50, 0, 0, false}};
  const Rings rings[] = {{"ABS rings (thesis)", "digital_abs", 0.4},
                         {"ABS rings, half as thick", "digital_abs", 0.2},
                         {"rings of tube silicone", "dragon_skin_30", 0.4}};
  std::printf("%-36s %-26s %9s %9s %14s %8s\n", "load", "rings", "3D", "rod", "confined rod", "3D s");
  for (const Load& l : loads)
    for (const Rings& r : rings) {
      double seconds = 0;
      const double s = rod_only ? std::nan("") : solid(r, l, seconds);
      std::printf("%-36s %-26s %9.3f %9.3f %14.3f %8.1f\n", l.name, r.name, s, rod(r, l, false), rod(r, l, true),
                  seconds);
      std::fflush(stdout);
    }
  return 0;
} catch (const InputError& e) {
  std::fprintf(stderr, "%s\n", e.what());
  return 2;
}

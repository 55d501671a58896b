#include "fem/reduced/reduced_scenes.hpp"

#include <algorithm>
#include <chrono>

#include "fem/core/input_error.hpp"
#include "fem/reduced/fibre_law.hpp"
#include "fem/reduced/rra_calibration.hpp"

namespace softarm::fem {
namespace {
constexpr double kDeg = 57.295779513082320876;
double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

ReducedRraResult run_reduced_rra(const RraSceneSpec& spec) {
  const auto t0 = std::chrono::steady_clock::now();
  const FibreLaw law(*spec.tube_material.law);
  ReducedRraResult out;
  for (double p : spec.path.output_pressures_kPa) {
    out.pressure_kPa.push_back(p);
    out.extension_mm.push_back(rod_rra_extension_mm(spec.design, law, p, 1.0));
  }
  out.seconds = since(t0);
  return out;
}

namespace {
ArmRod reduced_tca_rod(const TcaSceneSpec& spec, int nodes) {
  ArmRodSpec rod;
  RodPiece piece;
  piece.design = spec.design;
  rod.pieces = {piece};
  rod.tube = spec.tube_material;
  rod.sheath = spec.sheath_material;
  rod.rings = spec.ring_material;
  rod.nodes_per_segment = nodes;
  return ArmRod(rod);
}
}  // namespace

ReducedTcaResult run_reduced_tca(const TcaSceneSpec& spec, int nodes) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto& pc = spec.chamber_pressure_kPa;
  if (pc[1] != pc[2] || spec.gravity_m_s2.y() != 0)
    throw InputError("load", "the reduced (rod) model is planar: it needs chambers 2 and 3 at equal pressure and "
                             "gravity in the x–z plane; ask for a higher fidelity for this scene");
  const ArmRod rod = reduced_tca_rod(spec, nodes);
  RodLoad load;
  load.chamber_pressure_kPa = {pc};
  load.gravity_m_s2 = {spec.gravity_m_s2.x(), spec.gravity_m_s2.z()};
  const double p_max = std::max({pc[0], pc[1], pc[2]});
  // Every step is a converged equilibrium, so the count only sets where the curve is sampled:
  // at the scene's (evenly spaced) output pressures, or at least every 1/8 of the load.
  const int steps = std::max<int>(8, static_cast<int>(spec.output_pressures_kPa.size()));
  ReducedTcaResult out;
  out.final_state = rod.follow(load, steps, [&](double f, const RodState& s) {
    const double p = f * p_max, angle = rod.tip_rotation(s, load) * kDeg;
    if (!out.target_pressure_kPa && !out.bending_deg.empty() && out.bending_deg.back() < spec.target_bending_deg &&
        angle >= spec.target_bending_deg)
      out.target_pressure_kPa = out.pressure_kPa.back() + (spec.target_bending_deg - out.bending_deg.back()) *
                                                              (p - out.pressure_kPa.back()) / (angle - out.bending_deg.back());
    out.pressure_kPa.push_back(p);
    out.bending_deg.push_back(angle);
  });
  out.extremes = rod.extremes(out.final_state, load, 0);
  out.mass_kg = rod.mass_kg();
  out.nodes = rod.node_count();
  out.arc_length_mm = rod.arc_length();
  out.seconds = since(t0);
  return out;
}

}  // namespace softarm::fem

#include "fem/scenes/reduced_scenes.hpp"

#include <algorithm>
#include <chrono>

#include "fem/reduced/fibre_law.hpp"
#include "fem/scenes/rra_calibration.hpp"
#include "fem/core/angles.hpp"

namespace softarm::fem {
namespace {
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
ArmRodSpec reduced_tca_rod(const TcaSceneSpec& spec, int nodes) {
  ArmRodSpec rod;
  RodPiece piece;
  piece.design = spec.design;
  rod.pieces = {piece};
  rod.tube = spec.tube_material;
  rod.sheath = spec.sheath_material;
  rod.rings = spec.ring_material;
  rod.nodes_per_segment = nodes;
  return rod;
}
}  // namespace

ReducedTcaResult run_reduced_tca(const TcaSceneSpec& spec, int nodes) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto& pc = spec.chamber_pressure_kPa;
  const double p_max = std::max({pc[0], pc[1], pc[2]});
  // Every step is a converged equilibrium, so the count only sets where the curve is sampled:
  // at the scene's (evenly spaced) output pressures, or at least every 1/8 of the load.
  const int steps = std::max<int>(8, static_cast<int>(spec.output_pressures_kPa.size()));
  ReducedTcaResult out;
  const auto record = [&](double fraction, double angle) {
    const double p = fraction * p_max;
    if (!out.target_pressure_kPa && !out.bending_deg.empty() && out.bending_deg.back() < spec.target_bending_deg &&
        angle >= spec.target_bending_deg)
      out.target_pressure_kPa = out.pressure_kPa.back() + (spec.target_bending_deg - out.bending_deg.back()) *
                                                              (p - out.pressure_kPa.back()) / (angle - out.bending_deg.back());
    out.pressure_kPa.push_back(p);
    out.bending_deg.push_back(angle);
  };
  const ArmRodSpec rod_spec = reduced_tca_rod(spec, nodes);
  out.spatial = pc[1] != pc[2] || spec.gravity_m_s2.y() != 0;
  if (!out.spatial) {
    const ArmRod rod(rod_spec);
    RodLoad load;
    load.chamber_pressure_kPa = {pc};
    load.gravity_m_s2 = {spec.gravity_m_s2.x(), spec.gravity_m_s2.z()};
    const RodState st =
        rod.follow(load, steps, [&](double f, const RodState& s) { record(f, rod.tip_rotation(s, load) * kDeg); });
    out.converged = st.converged;
    out.diagnosis = st.diagnosis;
    for (std::size_t j = 0; j < st.x.size(); ++j) out.centreline_mm.emplace_back(st.x[j], 0.0, st.z[j]);
    out.extremes = rod.extremes(st, load, 0);
    out.mass_kg = rod.mass_kg();
    out.arc_length_mm = rod.arc_length();
  } else {
    const SpatialRod rod(rod_spec);
    SpatialRodLoad load;
    load.chamber_pressure_kPa = {pc};
    load.gravity_m_s2 = spec.gravity_m_s2;
    const int tip = rod.node_count() - 1;
    const SpatialRodState st =
        rod.follow(load, steps, [&](double f, const SpatialRodState& s) { record(f, rod.tilt_deg(s, load, tip)); });
    out.converged = st.converged;
    out.diagnosis = st.diagnosis;
    out.centreline_mm = st.position;
    out.extremes = rod.extremes(st, load, 0);
    out.mass_kg = rod.mass_kg();
    out.arc_length_mm = rod.layout().s;
  }
  out.nodes = static_cast<int>(out.arc_length_mm.size());
  out.seconds = since(t0);
  return out;
}

}  // namespace softarm::fem

namespace softarm::fem {

ReducedSplResult run_reduced_spl(const SplSceneSpec& spec, int nodes_per_segment, int cells) {
  const auto t0 = std::chrono::steady_clock::now();
  ArmRodSpec arm;
  arm.pieces = spl_rod_pieces(spec.design, spec.connector_material);
  arm.tube = spec.tube_material;
  arm.sheath = spec.sheath_material;
  arm.rings = spec.ring_material;
  arm.nodes_per_segment = nodes_per_segment;
  const SpatialRod rod(arm, cells);
  // Scene frame (spl_scene.hpp): z along the arm, the tip at z = 0 at rest, the shoulder at z = L.
  SpatialRodLoad load;
  load.clamp_position_mm = {0, 0, rod.layout().s.back()};
  load.gravity_m_s2 = spec.gravity_m_s2;
  load.tip_mass_kg = spec.tip_mass_kg;
  for (const RodPiece& piece : arm.pieces) {
    const int segment = static_cast<int>(load.chamber_pressure_kPa.size()) / 2;  // pieces alternate connector, segment
    if (piece.kind == RodPiece::Kind::connector) load.chamber_pressure_kPa.push_back({0, 0, 0});
    else load.chamber_pressure_kPa.push_back({spec.chamber_pressure_kPa[3 * segment], spec.chamber_pressure_kPa[3 * segment + 1],
                                              spec.chamber_pressure_kPa[3 * segment + 2]});
  }
  const int tip = rod.node_count() - 1;
  ReducedSplResult out;
  const int steps = std::max<int>(8, static_cast<int>(spec.output_levels.size()));
  out.final_state = rod.follow(load, steps, [&](double f, const SpatialRodState& s) {
    out.curve.push_back({f, s.position.back(), rod.tilt_deg(s, load, tip), s.newton_iterations,
                         s.position});
  });
  const SpatialRodState& s = out.final_state;
  if (!s.position.empty()) {
    // Pose of node j relative to rest (every node's rest frame is the clamp's).
    const auto pose = [&](int j) {
      return FacePose{s.position[j], s.frame[j] * load.clamp_frame.transpose(), rod.tilt_deg(s, load, j)};
    };
    for (int n = 1; n <= 3; ++n) {
      const int piece = 2 * n - 1;
      int first = -1, last = -1;
      for (int j = 0; j <= tip; ++j)
        if (rod.layout().nodes[j].piece == piece) {
          if (first < 0) first = j;
          last = j;
        }
      const std::string segment = "segment " + std::to_string(n);
      out.joints.push_back({segment + " top" + (n == 1 ? " (shoulder connector)" : ""), pose(first)});
      out.joints.push_back({segment + " bottom" + (n == 3 ? " (tip)" : ""), pose(last)});
      out.segment_extremes[n - 1] = rod.extremes(s, load, piece);
    }
  }
  out.part_masses = rod.layout().masses;
  out.mass_kg = rod.mass_kg();
  out.nodes = rod.node_count();
  out.seconds = since(t0);
  return out;
}

}  // namespace softarm::fem

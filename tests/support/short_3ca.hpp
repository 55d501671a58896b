#pragma once
// A short 3CA for the 3D scene tests: four rings over 24 mm with the thesis distal section
// (r = 9 mm), its taper slope and its normalised sizes, Dragon Skin 30 with ABS rings, whose 3D
// models take seconds; as a scene, chambers 2 and 3 ramped together under gravity along −x.
#include <vector>

#include "fem/scenes/tca_scene.hpp"

namespace softarm::test {

inline fem::TcaDesign short_3ca() {
  fem::TcaDesign d;
  fem::RraDesign& a = d.actuator;
  a.length_mm = 24;
  a.bottom_radius_mm = 9;
  a.top_radius_mm = 9.45;  // the thesis taper slope
  a.wall_thickness_mm = 0.466 * 9;
  a.end_cap_thickness_mm = 0.25 * 9;
  a.ring_count = 4;
  a.ring_diameter_mm = 0.4 * 24 / 4;
  return d;
}

inline fem::TcaSceneSpec short_3ca_scene(double pressure_kPa, std::vector<double> output_pressures_kPa) {
  fem::TcaSceneSpec s;
  s.design = short_3ca();
  s.tube_material = s.sheath_material = fem::builtin_material("dragon_skin_30", "test");
  s.ring_material = fem::builtin_material("digital_abs", "test");
  s.chamber_pressure_kPa = {0, pressure_kPa, pressure_kPa};
  s.gravity_m_s2 = Eigen::Vector3d(-9.80665, 0, 0);
  s.output_pressures_kPa = std::move(output_pressures_kPa);
  return s;
}

}  // namespace softarm::test

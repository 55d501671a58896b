#include "fem/scenes/rra_calibration.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace softarm::fem {

double rod_rra_extension_mm(const RraDesign& design, const FibreLaw& tube, double pressure_kPa, double factor,
                            int nodes) {
  // A lone RRA carries no moment: each section's axis stretch balances c·p·A_c (section_equilibrium.hpp).
  double sum = 0, previous = 0;
  SectionState st;
  for (int i = 0; i < nodes; ++i) {
    const double z = design.length_mm * i / (nodes - 1);
    const RodSection s = rra_section(design, z);
    st = solve_section(s, {&tube, nullptr}, {factor * pressure_kPa * 1e-3 * s.chamber_force_area[0]}, 0.0, 0.0, st);
    if (!st.ok) return std::nan("");
    const double e = st.stretch - 1;
    if (i > 0) sum += 0.5 * (e + previous) * design.length_mm / (nodes - 1);
    previous = e;
  }
  return sum;
}

RraCalibration calibrate_rra(const RraSceneSpec& spec) {
  RraCalibration c;
  const auto t0 = std::chrono::steady_clock::now();
  const RraResult fem = run_rra_scene(spec);
  c.fem_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  c.dofs = fem.dofs;
  c.limit_point = fem.path.outcome == PathOutcome::limit_point;
  c.outcome = to_string(fem.path.outcome);
  const FibreLaw tube(*spec.tube_material.law);
  for (const RraCurvePoint& p : fem.curve) {
    if (!(p.pressure_kPa > 0)) continue;
    c.last_pressure_kPa = std::max(c.last_pressure_kPa, p.pressure_kPa);
    const double target = p.extension_mm;
    const auto ext = [&](double f) { return rod_rra_extension_mm(spec.design, tube, p.pressure_kPa, f); };
    // Secant on c: the extension grows monotonically with the force.
    double f0 = 1.0, e0 = ext(f0), f1 = 1.2, e1 = ext(f1);
    const double rod = e0;
    for (int it = 0; it < 30 && std::isfinite(e1) && std::abs(e1 - target) > 1e-7 * std::abs(target); ++it) {
      const double f2 = std::clamp(f1 + (target - e1) * (f1 - f0) / (e1 - e0), 0.5 * f1, 2.0 * f1);
      f0 = f1, e0 = e1, f1 = f2, e1 = ext(f2);
    }
    if (!std::isfinite(e1) || !std::isfinite(rod)) continue;  // the rod's fibres left their table: keep the last fit
    c.pressure_kPa.push_back(p.pressure_kPa);
    c.fem_extension_mm.push_back(p.extension_mm);
    c.rod_extension_mm.push_back(rod);
    c.force_factor.pressure_kPa.push_back(p.pressure_kPa);
    c.force_factor.factor.push_back(f1);
    c.mean_stretch.push_back(1 + p.extension_mm / spec.design.length_mm);
    c.peak_stretch.push_back(p.averaged.stretch);
    c.peak_log_strain.push_back(p.averaged.log_strain);
    c.peak_stress_MPa.push_back(p.averaged.stress_MPa);
    c.point_stretch.push_back(p.tube_max_stretch);
  }
  return c;
}

RraCalibration::Peaks RraCalibration::peaks_at(double l) const {
  Peaks out;
  if (mean_stretch.empty()) return out;
  // Rest state (λ̄ = 1, no peaks) prepended, then piecewise linear in λ̄.
  std::vector<double> x{1.0}, a{1.0}, b{0.0}, s{0.0}, q{1.0};
  for (std::size_t i = 0; i < mean_stretch.size(); ++i)
    if (mean_stretch[i] > x.back()) {
      x.push_back(mean_stretch[i]);
      a.push_back(peak_stretch[i]);
      b.push_back(peak_log_strain[i]);
      s.push_back(peak_stress_MPa[i]);
      q.push_back(point_stretch[i]);
    }
  if (x.size() < 2) return out;
  std::size_t i = 1;
  while (i + 1 < x.size() && l > x[i]) ++i;
  const double t = (l - x[i - 1]) / (x[i] - x[i - 1]);
  out.stretch = a[i - 1] + t * (a[i] - a[i - 1]);
  out.log_strain = b[i - 1] + t * (b[i] - b[i - 1]);
  out.stress_MPa = s[i - 1] + t * (s[i] - s[i - 1]);
  out.point_stretch = q[i - 1] + t * (q[i] - q[i - 1]);
  out.extrapolated = l > x.back();
  if (l < 1.0) out = {1.0, 0.0, 0.0, 1.0, false};  // a compressed actuator: no tensile peak from pressure
  return out;
}

RraCalibration calibrate_rra_to_stretch(RraSceneSpec spec, double stretch, double max_pressure_kPa) {
  const FibreLaw law(*spec.tube_material.law);
  const double target_mm = 1.25 * (stretch - 1) * spec.design.length_mm;
  double lo = 0, hi = max_pressure_kPa;
  const double at_max = rod_rra_extension_mm(spec.design, law, hi, 1.0);
  if (std::isfinite(at_max) && at_max > target_mm) {
    for (int it = 0; it < 40; ++it) {  // bisection: the extension grows with the pressure
      const double mid = 0.5 * (lo + hi), e = rod_rra_extension_mm(spec.design, law, mid, 1.0);
      (std::isfinite(e) && e < target_mm ? lo : hi) = mid;
    }
  }
  spec.path = PressurePathSpec{};
  spec.path.max_pressure_kPa = std::max(hi, 0.05 * max_pressure_kPa);
  for (int k = 1; k <= 8; ++k) spec.path.output_pressures_kPa.push_back(spec.path.max_pressure_kPa * k / 8);
  return calibrate_rra(spec);
}

}  // namespace softarm::fem

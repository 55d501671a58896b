#include "fem/reduced/rod_layout.hpp"

#include <algorithm>
#include <cmath>

#include "fem/reduced/rod_section.hpp"
#include "fem/core/angles.hpp"

namespace softarm::fem {
namespace {
constexpr double kMm3ToKgPerGcm3 = 1e-6;  // mm³ × g/cm³ → kg

// Trapezoid integral of f over the nodes [a, b].
template <class F>
double trapezoid(const std::vector<double>& s, int a, int b, F f) {
  double sum = 0;
  for (int j = a; j < b; ++j) sum += 0.5 * (s[j + 1] - s[j]) * (f(j) + f(j + 1));
  return sum;
}
}  // namespace

double ForceFactor::at(double p) const {
  if (pressure_kPa.empty()) return 1.0;
  if (p <= pressure_kPa.front()) return factor.front();
  for (std::size_t i = 1; i < pressure_kPa.size(); ++i)
    if (p <= pressure_kPa[i]) {
      const double t = (p - pressure_kPa[i - 1]) / (pressure_kPa[i] - pressure_kPa[i - 1]);
      return (1 - t) * factor[i - 1] + t * factor[i];
    }
  return factor.back();
}

void PieceExtremes::widen(const FibreExtremes& f, bool first) {
  tube_max_stretch = first ? f.tube_max : std::max(tube_max_stretch, f.tube_max);
  tube_min_stretch = first ? f.tube_min : std::min(tube_min_stretch, f.tube_min);
  sheath_max_stretch = first ? f.sheath_max : std::max(sheath_max_stretch, f.sheath_max);
  sheath_min_stretch = first ? f.sheath_min : std::min(sheath_min_stretch, f.sheath_min);
}

std::vector<double> chamber_forces_N(const RodPiece& piece, const std::array<double, 3>& pressure_kPa,
                                     const std::vector<double>& area) {
  std::vector<double> f(area.size(), 0.0);
  for (std::size_t k = 0; k < f.size(); ++k)
    f[k] = piece.force_factor.at(pressure_kPa[k]) * pressure_kPa[k] * 1e-3 * area[k];  // kPa → MPa; MPa·mm² = N
  return f;
}

RodLayout rod_nodes(const ArmRodSpec& spec) {
  RodLayout out;
  double s0 = 0;
  for (int p = 0; p < static_cast<int>(spec.pieces.size()); ++p) {
    const RodPiece& piece = spec.pieces[p];
    if (piece.kind == RodPiece::Kind::connector) {
      for (double s : {s0, s0 + piece.length_mm}) {
        out.nodes.push_back({p, true, 0.0});
        out.s.push_back(s);
      }
      s0 += piece.length_mm;
      continue;
    }
    const RraDesign& a = piece.design.actuator;
    // The trapezoid rule keeps its second order only on smooth zones.
    const double l = a.length_mm, tc = a.end_cap_thickness_mm;
    const int n = std::max(5, spec.nodes_per_segment);
    const int cap_nodes = std::max(2, static_cast<int>(std::lround(n * tc / l)) + 1);
    const std::array<std::array<double, 2>, 3> zones{{{0.0, tc}, {tc, l - tc}, {l - tc, l}}};  // in local s = l − z
    for (int k = 0; k < 3; ++k) {
      const int count = k == 1 ? std::max(3, n - 2 * cap_nodes) : cap_nodes;
      const double eps = 1e-9 * l;  // evaluate the section just inside the zone
      for (int i = 0; i < count; ++i) {
        const double local = zones[k][0] + (zones[k][1] - zones[k][0]) * i / (count - 1);
        out.nodes.push_back({p, false, std::clamp(l - local, l - zones[k][1] + eps, l - zones[k][0] - eps)});
        out.s.push_back(s0 + local);
      }
    }
    s0 += a.length_mm;
  }
  return out;
}

void distribute_masses(RodLayout& layout, const ArmRodSpec& spec, const std::vector<double>& tube_area,
                       const std::vector<double>& sheath_area) {
  const int n = static_cast<int>(layout.nodes.size());
  layout.interval_mass.assign(std::max(1, n) - 1, 0.0);
  layout.masses = {};
  for (int first = 0; first < n;) {
    int last = first;
    while (last + 1 < n && layout.nodes[last + 1].piece == layout.nodes[first].piece) ++last;
    const RodPiece& piece = spec.pieces[layout.nodes[first].piece];
    if (piece.kind == RodPiece::Kind::connector) {
      layout.interval_mass[first] = piece.mass_kg;
      layout.masses.connectors += piece.mass_kg;
      first = last + 1;
      continue;
    }
    const RraDesign& a = piece.design.actuator;
    const double count = piece.kind == RodPiece::Kind::tca ? 3.0 : 1.0;
    const double tube = count * tube_volume_mm3(a) * spec.tube.density_g_cm3 * kMm3ToKgPerGcm3;
    const double rings = count * ring_volume_mm3(a) * spec.rings.density_g_cm3 * kMm3ToKgPerGcm3;
    const auto tube_at = [&](int j) { return tube_area[j]; };
    const auto sheath_at = [&](int j) { return sheath_area[j]; };
    // The rings sit half in the tube's grooves, half in the core: the core loses that half.
    const double sheath_volume =
        std::max(0.0, trapezoid(layout.s, first, last, sheath_at) - 0.5 * count * ring_volume_mm3(a));
    const double sheath = sheath_volume * spec.sheath.density_g_cm3 * kMm3ToKgPerGcm3;
    const double tube_total = trapezoid(layout.s, first, last, tube_at);
    const double sheath_total = trapezoid(layout.s, first, last, sheath_at);
    for (int j = first; j < last; ++j) {
      const double ds = layout.s[j + 1] - layout.s[j];
      double m = tube * 0.5 * ds * (tube_at(j) + tube_at(j + 1)) / tube_total + rings * ds / a.length_mm;
      if (sheath_total > 0) m += sheath * 0.5 * ds * (sheath_at(j) + sheath_at(j + 1)) / sheath_total;
      layout.interval_mass[j] = m;
    }
    layout.masses.tube += tube;
    layout.masses.rings += rings;
    layout.masses.sheath += sheath;
    first = last + 1;
  }
}

std::vector<RodPiece> spl_rod_pieces(const SplDesign& d, const Material& connector) {
  // Connector c (0: shoulder, on segment 1's top; 1: between 1 and 2; 2: between 2 and 3).
  const auto connector_piece = [&](int c) {
    const TcaDesign& seg = d.segments[c == 0 ? 0 : c - 1];
    const RodSection s = tca_section(seg, c == 0 ? seg.actuator.length_mm : 0.0, 0.0);
    const double hole = kPi * std::pow(seg.centre_hole_diameter_mm / 2, 2);
    RodPiece p;
    p.kind = RodPiece::Kind::connector;
    p.length_mm = d.connector_thickness_mm;
    p.mass_kg = d.connector_mass_g ? *d.connector_mass_g * 1e-3
                                   : (s.tube_area + s.sheath_area + hole) * d.connector_thickness_mm *
                                         connector.density_g_cm3 * kMm3ToKgPerGcm3;
    return p;
  };
  // No calibration factor inside a 3CA: the core stops the chamber bulging between the
  // rings, which is what the lone RRA's factor measures (docs/reduced-model.md, Calibration on the
  // lone RRA).
  const auto segment_piece = [&](int n) {
    RodPiece p;
    p.kind = RodPiece::Kind::tca;
    p.design = d.segments[n];
    return p;
  };
  return {connector_piece(0), segment_piece(0), connector_piece(1), segment_piece(1), connector_piece(2),
          segment_piece(2)};
}

}  // namespace softarm::fem

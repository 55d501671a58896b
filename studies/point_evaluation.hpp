#pragma once
// One study point: its scene solved by the study's model, reduced to the
// outputs the rules and reports use (names carry their units).
//
//   rra (extension, spec §4): extension_mm at the peak pressure, mass_g, the
//     tube's peaks (stretch, principal Cauchy stress, log strain), the
//     pressure reached, limit_pressure_kPa when the pressure–volume curve
//     turns over (ballooning), and burst_utilisation: the largest of
//     stress / (strength / SF), stretch / ((1 + elongation) / SF) and, past a
//     limit point, p_max / p_limit (≥ 1 means burst by spec §4 (a), (b) or (c)).
//   tca (bending, spec §4): bending_deg at the peak pressure and its share of
//     90° (normalised_bending, thesis §6.1), pressure_for_target_kPa, mass_g,
//     the tip position; model "rod" adds the fibre extremes of the section
//     (tube, sheath) and burst_utilisation from criterion (b) on them.
//
// A point whose path stops at a limit point is a result (status "ok", the
// pressure reached, the diagnosis, burst by criterion (c)); one whose solver
// stalled before the peak pressure is "incomplete" (its outputs hold at the
// pressure reached); a design that cannot be built is "invalid" (the scene
// reader's message); anything else "failed".
#include <nlohmann/json.hpp>

#include "studies/study_points.hpp"
#include "studies/study_spec.hpp"

namespace softarm::studies {

/// {"status", "diagnosis", outputs…, "curve": {"pressure_kPa": […], "<y>": […]},
///  "shape": {…} (deformed outline for the report), "model", "dofs", "seconds"}.
nlohmann::json evaluate_point(const StudySpec& spec, const StudyPoint& point);

}  // namespace softarm::studies

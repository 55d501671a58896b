#pragma once
// The ladder's "check and correct" (issue 6): a 3D check of one segment of an
// optimum (objectives/solid_segment_check.hpp) becomes a correction of the
// search model, and the search runs again with it.
//
// The correction is multiplicative and of zeroth order, the simplest model
// management of multifidelity optimisation (Alexandrov & Lewis 2001; Eldred,
// Giunta & Collis 2004): at the checked design the corrected search model
// equals the 3D one, β·f_search = f_3D, and β is held constant elsewhere.
// Two measures get one:
//   bending   β_θ = θ_3D(p) / θ_search(p) on the checked segment at the
//             pressure the 3D path reached (the working pressure, or its
//             limit point), applied to every segment's bending at the working
//             pressure (one segment is checked; the others share its section
//             law, so its error is taken for theirs);
//   burst     β_u = u_3D / u_search on the checked segment when the 3D path
//             meets a ballooning limit point p_lim below the working pressure
//             p_w, with u_3D = p_w / p_lim (the search model's own utilisation
//             of a limit point, objectives/arm_evaluation.cpp). A 3D path that
//             holds p_w says nothing about how far away its limit point is, so
//             β_u only grows: the largest of all checks is kept, and the search
//             cannot walk back into a design the 3D model saw balloon.
// Not corrected: mass (exact in both models), payload (the 3D model of the
// whole hanging arm is not run), durability (the 3D check has no groove-lip
// strain at the RRA mesh level that defines it).
#include <string>

#include "objectives/arm_evaluation.hpp"
#include "objectives/solid_segment_check.hpp"

namespace softarm::engine {

struct SolidCorrection {
  double bending_factor = 1;  // β_θ
  double burst_factor = 1;    // β_u
  int checks = 0;             // the 3D checks it comes from
  /// "none", or "bending ×0.690 (…), burst ×1.181 (…)".
  std::string describe() const;
};

/// The correction after one more 3D check: `check` of segment check.segment, `searched` the
/// search model's measures of the same design (its segment check.segment − 1 is compared).
/// A check whose 3D path stalled (neither the working pressure nor a limit point) leaves it as it was.
SolidCorrection updated_correction(const SolidCorrection& previous, const objectives::SolidSegmentCheck& check,
                                   const objectives::ArmMeasures& searched, double working_pressure_kPa);

/// The search model's measures with the correction applied (bending at the working pressure,
/// burst utilisation; everything else as it was).
objectives::ArmMeasures corrected(const objectives::ArmMeasures& m, const SolidCorrection& c);

}  // namespace softarm::engine

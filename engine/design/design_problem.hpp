#pragma once
// The bridge between the requirements and the optimiser: a design vector x
// (design_config.hpp's variables, physical units) becomes an SPL candidate,
// the candidate's measures (objectives/arm_evaluation.hpp) become the
// objective and the dimensionless constraints g ≤ 0:
//   mass        m / m_max − 1
//   payload     1 − payload / payload_min
//   bending     1 − min_n θ_n(p_w) / θ_target
//   burst       max_n utilisation_n − 1   (criteria (a), (b), (c), spec §4)
//   durability  ε_peak / (ε_ref·r) − 1    (ε_ref: thesis RRA at its cycling pressure; r the allowed
//                                          ratio for the required life, 1 without a strain–life curve)
// plus any extra bounds on named measures (design_measures.hpp), relative to |limit|.
#include <string>
#include <vector>

#include "engine/design/design_checkpoint.hpp"
#include "engine/design/design_config.hpp"
#include "engine/design/discrepancy_model.hpp"
#include "engine/design/solid_correction.hpp"
#include "engine/optimiser/optimiser.hpp"
#include "objectives/arm_evaluation.hpp"

namespace softarm::engine {

class MeasuresMemo;  // measures_memo.hpp

/// A candidate from the variables' values (others from the baseline). Throws
/// fem::InputError when the geometry cannot be built (touching rings, ...).
objectives::ArmCandidate make_candidate(const DesignConfig& config, const std::vector<double>& x);
/// The baseline (thesis) design's values of the variables.
std::vector<double> baseline_values(const DesignConfig& config);

struct ConstraintValues {
  std::vector<std::string> names;
  std::vector<double> values;  // g_i, feasible when ≤ 0
};
ConstraintValues constraints_of(const DesignConfig& config, const objectives::ArmMeasures& m, double reference_strain);
/// The value the optimiser minimises (a maximised measure negated).
/// Whether every constraint of the measures holds (g ≤ 0, to round-off): the verdict of "meets every
/// requirement", wherever it is given.
bool meets_every_requirement(const DesignConfig& config, const objectives::ArmMeasures& m, double reference_strain);

double objective_of(const DesignConfig& config, const objectives::ArmMeasures& m, double reference_strain);

/// The constraints with the correction applied (bending and burst; solid_correction.hpp):
/// the same values as constraints_of(corrected(m)), from constraints_of(m).
ConstraintValues corrected_constraints(ConstraintValues raw, const SolidCorrection& correction);

/// The optimiser's problem: the objective and constraints g + config.search_margin ≤ 0 of the
/// search model's measures, constraints corrected by `correction` and then shifted by the
/// discrepancy model's δ(u) (optional; discrepancy_model.hpp). `checkpoint` (optional) is looked up
/// before a design is measured and keeps every new measurement, uncorrected. `memo` (optional) measures
/// each design once per run (measures_memo.hpp).
optimise::Problem design_problem(const DesignConfig& config, double reference_strain,
                                 const SolidCorrection& correction, DesignCheckpoint* checkpoint,
                                 const DiscrepancyModel* discrepancy = nullptr, MeasuresMemo* memo = nullptr);

/// The design in the normalised space of the discrepancy model: each variable mapped to [0, 1] over
/// its bounds; a categorical choice to 0 (the correction is of zeroth order across materials: a
/// material the verified designs did not use gets no extrapolated slope).
std::vector<double> normalised_design(const DesignConfig& config, const std::vector<double>& x);

/// The constraints of the search model's measures `m` at x, corrected as design_problem corrects them
/// (without the search margin).
ConstraintValues corrected_constraints_at(const DesignConfig& config, const objectives::ArmMeasures& m,
                                          double reference_strain, const SolidCorrection& correction,
                                          const DiscrepancyModel* discrepancy, const std::vector<double>& x);

/// The variables' bounds narrowed to a box of half-width `radius` (a fraction of each range) about x
/// (continuous and integer variables; an integer box spans at least its two nearest integers;
/// categorical choices stay free unless `keep_choices` holds them at x's): the trust region of a
/// corrected search.
std::vector<optimise::Variable> trust_region(const DesignConfig& config, const std::vector<double>& x, double radius,
                                             bool keep_choices = false);

/// "ring_count = 30, taper_ratio = 0.5, ..., tube_material = dragon_skin_30".
std::string describe(const DesignConfig& config, const std::vector<double>& x);

}  // namespace softarm::engine

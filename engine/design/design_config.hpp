#pragma once
// The requirements config of `softarm design` (configs/thesis_requirements.json):
// what the arm must do (spec §3), which design parameters the optimiser may
// change and within which bounds, the model settings and the optimiser's.
// Read with fem::JsonReader: unknown keys, missing keys and out-of-range values
// are rejected naming the field; `softarm schema --design` lists every key.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "fem/core/thesis_values.hpp"
#include "engine/optimiser/optimiser.hpp"
#include "fem/mesh/spl_design.hpp"
#include "objectives/solid_segment_check.hpp"
#include "objectives/arm_evaluation.hpp"

namespace softarm::engine {

struct Requirements {
  double max_mass_kg = 2.0;
  double length_m = 0.6;
  double min_payload_kg = 0.5;
  double bending_per_segment_deg = 90;
  double max_pressure_kPa = fem::thesis::kWorkingPressure_kPa;  // supply: every chamber's working pressure
  double durability_reference_pressure_kPa = fem::thesis::kRraTestPressure_kPa;  // the thesis RRA's cycling test
  double durability_reference_cycles = 1.1e6;
  double durability_cycles = 1e6;           // required; met when ε ≤ ε_ref (the only measured point)
  /// Optional strain–life curve through the measured point, N = N_ref·(ε_ref/ε)^b (Basquin form
  /// in strain): with it, the life required sets the allowed strain ratio (N_ref/N_req)^(1/b).
  double strain_life_exponent = 0;          // b; 0: no curve (then N_req ≤ N_ref and ε ≤ ε_ref)
  /// Allowed ε/ε_ref for the required life.
  double allowed_strain_ratio() const;
};

/// One design variable: the name of a geometry key (or "tube_material" /
/// "sheath_material"), its bounds or choices, and the baseline (thesis) value.
struct DesignVariable {
  optimise::Variable variable;
  double baseline = 0;  // physical units; categorical: index of the baseline choice
};

/// An extra constraint on a named measure (design_measures.hpp): value ≥ min or value ≤ max.
struct MeasureBound {
  std::string measure;
  bool is_min = true;
  double limit = 0;
};

struct DesignConfig {
  Requirements requirements;
  std::string objective = "minimise_mass";  // "minimise_<measure>" or "maximise_<measure>" (design_measures.hpp)
  std::string objective_measure = "mass_kg";
  bool maximise = false;
  std::vector<MeasureBound> extra_constraints;
  std::vector<DesignVariable> variables;    // in a fixed order (design_variable_names())
  fem::SplParameters baseline_geometry;     // the SPL geometry as given (segment length from the arm's): the
                                            // keys not optimised, and the variables' starts
  std::string baseline_tube = "dragon_skin_30", baseline_sheath = "dragon_skin_30";
  objectives::EvaluationSettings model;     // search fidelity
  objectives::EvaluationSettings check;     // the final design's re-check (higher fidelity)
  int solid_check_segment = 0;              // 1–3: that segment of the optimum also by the 3D FEM; 0: none
  int solid_corrections = 0;                // searches again with the search model corrected by the 3D check
  objectives::SolidCheckModel solid_check_model = objectives::SolidCheckModel::cell_rod;  // check.solid_model
                                            // (solid_correction.hpp), at most this many times
  /// check.verification: every requirement of each optimum verified on the cell rod of the whole arm
  /// (objectives/cell_rod_evaluation.hpp), which decides feasibility and corrects the search model
  /// (check.corrections); false: the search model's verdict stands (a first look).
  bool verify_on_cells = true;
  int cell_levels = 16;                     // check.cell_levels: outputs along the cells' pressure ramp
  bool mesh_sensitivity = true;             // check.mesh_sensitivity: the optimum's peaks one RRA level finer
  int cell_layers_level = 0;                // check.cell_layers_level: the cells' layers along the axis (0: the rung's)
  double trust_radius = 0.25;               // check.trust_radius: the first corrected search's box, fraction of each range
  int improvement_rounds = 0;               // check.improvement_rounds: searches again about a verified design that
                                            // meets every requirement, corrected by it (trust-region model management)
  double improvement_tolerance = 0.005;     // check.improvement_tolerance_percent: a round predicting less stops
  int improvement_evaluations = 0;          // check.improvement_evaluations: an improvement round's budget (0: optimiser's)
  double search_margin = 0.01;              // constraints on the search model: g + margin ≤ 0
  optimise::Options optimiser;
  std::string output_directory = "out/design";
};

/// The variables softarm knows, in order.
const std::vector<std::string>& design_variable_names();

DesignConfig read_design_config(const nlohmann::json& document);

}  // namespace softarm::engine

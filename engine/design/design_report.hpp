#pragma once
#include <nlohmann/json.hpp>
// What `softarm design` writes: report.html (self-contained, SVG plots: the
// pressure–bending curves of the optimum and of the thesis design, the
// constraint margins, the convergence history, the payload pose), summary.json
// and the optimum's payload pose as a VTU polyline for ParaView.
#include <optional>
#include <string>
#include <vector>

#include "engine/design/design_config.hpp"
#include "engine/design/solid_correction.hpp"
#include "engine/optimiser/optimiser.hpp"
#include "objectives/arm_evaluation.hpp"
#include "objectives/cell_rod_evaluation.hpp"
#include "objectives/solid_segment_check.hpp"

namespace softarm::engine {

struct HistoryPoint {
  int evaluation = 0;
  double objective = 0;  // NaN for a failed evaluation
  bool feasible = false;
  std::string phase;
};

/// Why a search round ran: the first search; a correction (the last verified design missed a
/// requirement: check.corrections); an improvement (it met every one: check.improvement_rounds).
enum class RoundPurpose { first_search, correction, improvement };
/// "first search", "correction", "improvement": the words of the console, summary.json and the report.
const char* purpose_name(RoundPurpose purpose);

/// One search of a check-and-correct run and the 3D check of its optimum.
struct SearchRound {
  RoundPurpose purpose = RoundPurpose::first_search;
  SolidCorrection correction;         // the search model's, during this search
  std::vector<double> optimum_x;
  objectives::ArmMeasures optimum;    // search model, corrected
  bool feasible = false;
  std::optional<objectives::SolidSegmentCheck> solid_check;
  std::optional<objectives::CellRodEvaluation> verification;  // the optimum on the cell rod (check.verification)
  objectives::ArmMeasures optimum_uncorrected;                  // search model
};

struct DesignRun {
  const DesignConfig* config = nullptr;
  double reference_strain = 0, check_reference_strain = 0;
  std::vector<double> thesis_x, optimum_x;
  objectives::ArmMeasures thesis, optimum, check;  // optimum, check: corrected by the last round's correction
  std::optional<objectives::ArmMeasures> finer_peaks;  // the optimum with the RRA FEM one level finer (peak
                                                        // sensitivity); none where check.mesh_sensitivity is false
  double finer_reference_strain = 0;
  std::vector<SearchRound> rounds;  // the first search, then each correction round (check.corrections)
  std::size_t answer_round = 0;     // the round whose optimum is the answer (the best verified; else the last)
  std::string rounds_stop_reason;   // why no further round ran (words)
  /// The final optimum's segment by the 3D FEM (check.solid_segment): the last round's check.
  const std::optional<objectives::SolidSegmentCheck>& solid_check() const;
  /// The final optimum on the cell rod (check.verification): the last round's.
  const std::optional<objectives::CellRodEvaluation>& verification() const;
  /// The search model's measures of the final optimum, uncorrected (its error against the verification).
  objectives::ArmMeasures optimum_uncorrected;
  /// The start design (the baseline) on the cell rod, when the first search is corrected by it.
  std::optional<objectives::CellRodEvaluation> thesis_verification;
  optimise::Result result;
  std::vector<HistoryPoint> history;
  double seconds = 0;
};

void write_design_outputs(const DesignRun& run);

/// Whether the final optimum's verification on the cell rod meets every requirement (false without one).
bool verified_all_met(const DesignRun& run);

/// The measured errors of the models the search used (the fidelity ladder, fem/scenes/fidelity.hpp):
/// the 3CA bending by the rod, and the RRA's FEM level that supplies the local peaks.
nlohmann::json model_errors_json(int rra_mesh_level);

}  // namespace softarm::engine

#include "engine/design/design_command.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <optional>

#include "engine/design/cell_cluster.hpp"
#include "engine/design/design_problem.hpp"
#include "engine/design/design_report.hpp"
#include "engine/design/measures_memo.hpp"
#include "engine/design/search_log.hpp"
#include "engine/report/output_files.hpp"
#include "fem/core/json_reader.hpp"
#include "objectives/cell_rod_evaluation.hpp"
#include "objectives/fit_range.hpp"
#include "studies/progress_bar.hpp"

namespace softarm::engine {
namespace {
using Clock = std::chrono::steady_clock;

std::string fixed(double v, int digits) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}

// The 3D check of one segment of the optimum: the rod's error on it and the 3D model's verdict.
void print_solid_check(const objectives::SolidSegmentCheck& sc, double target_deg) {
  const auto kPa_or = [](const std::optional<double>& p, const char* none) {
    return p ? fixed(*p, 1) + " kPa" : std::string(none);
  };
  std::cout << "3D check of segment " << sc.segment << " (" << sc.element << ", " << sc.dofs << " dofs, "
            << fixed(sc.seconds, 0) << " s): at " << fixed(sc.reached_pressure_kPa, 1) << " kPa it bends "
            << fixed(sc.bending_deg, 2) << " deg, the rod " << fixed(sc.rod_bending_deg, 2) << " deg (rod error "
            << fixed(sc.bending_error_percent(), 1) << " %); " << target_deg << " deg at "
            << kPa_or(sc.pressure_for_target_kPa, "no pressure reached") << " (rod: "
            << kPa_or(sc.rod_pressure_for_target_kPa, "not reached") << "); path: " << sc.outcome << "\n";
  std::cout << "3D verdict on segment " << sc.segment << ": bending " << (sc.meets_bending() ? "met" : "NOT met")
            << ", working pressure " << sc.working_pressure_verdict() << "\n";
}

void print_measures(const std::string& title, const objectives::ArmMeasures& m) {
  std::cout << title << ": mass " << fixed(m.mass_kg, 3) << " kg, payload " << fixed(m.payload_kg, 3)
            << " kg, bending per segment " << fixed(m.segments[0].bending_deg_at_working, 1) << " / "
            << fixed(m.segments[1].bending_deg_at_working, 1) << " / " << fixed(m.segments[2].bending_deg_at_working, 1)
            << " deg, burst utilisation " << fixed(m.burst_utilisation, 3) << " (" << m.burst_governing
            << "), peak log strain " << fixed(m.durability_log_strain, 3) << " (" << fixed(m.seconds, 2) << " s)\n";
}

void print_constraints(const ConstraintValues& c) {
  for (std::size_t i = 0; i < c.names.size(); ++i)
    std::cout << "  " << std::left << std::setw(11) << c.names[i] << std::right << " margin " << std::setw(8)
              << fixed(-100 * c.values[i], 1) << " %" << (c.values[i] > 1e-6 ? "  VIOLATED" : "") << "\n";
}

// One search of the search model (corrected by `correction` and the discrepancy model) from x0,
// within the trust region of half-width `radius` about x0 when the discrepancy model has a centre,
// the materials held at x0's in an improvement round (`keep_materials`).
// Every 10 evaluations it prints an ETA: the rest of the budget at the mean cost of an evaluation so
// far, plus `after_s` (the verification that follows, at the last one's cost).
optimise::Result search(const DesignConfig& config, double ref_strain, const SolidCorrection& correction,
                        const DiscrepancyModel& discrepancy, double radius, const std::vector<double>& x0,
                        int max_evaluations, bool keep_materials, DesignCheckpoint& checkpoint, SearchLog& log,
                        double after_s, MeasuresMemo& memo) {
  optimise::Problem problem = design_problem(config, ref_strain, correction, &checkpoint, &discrepancy, &memo);
  if (!discrepancy.empty() && (radius < 1 || keep_materials)) {
    problem.variables = trust_region(config, x0, radius, keep_materials);
    std::cout << "search within the trust region: each variable within " << fixed(100 * radius, 1)
              << " % of its range of the best verified design"
              << (keep_materials ? ", its materials kept (a trust region is local; the first search screened them)" : "")
              << "\n";
  }
  optimise::Options options = config.optimiser;
  options.max_evaluations = max_evaluations;
  options.x0 = x0;
  const auto started = Clock::now();
  options.on_evaluation = [&](const optimise::Progress& p) {
    log.record(p, problem.constraint_names, options.constraint_tolerance);
    if (p.evaluation % 10 == 0 && p.evaluation < options.max_evaluations) {
      const double spent = std::chrono::duration<double>(Clock::now() - started).count();
      const double left = spent / p.evaluation * (options.max_evaluations - p.evaluation) + after_s;
      std::cout << "progress: " << p.evaluation << " of at most " << options.max_evaluations
                << " evaluations in this search; ETA of this round ~" << fixed(left / 60, 1) << " min"
                << (after_s > 0 ? " (with its verification)" : "") << "\n";
    }
  };
  const optimise::Result result = optimise::minimise(problem, options);
  std::cout << "\noptimiser: " << result.evaluations << " evaluations (" << result.cache_hits << " cache hits), "
            << fixed(result.seconds, 1) << " s; " << result.stop_reason << "\n";
  return result;
}

void print_optimum(const DesignConfig& config, const optimise::Result& result, const objectives::ArmMeasures& m,
                   double ref_strain, const SolidCorrection& correction, const DiscrepancyModel& discrepancy) {
  std::cout << (result.feasible ? "optimal design: " : "no design meets every requirement; the closest: ")
            << describe(config, result.x) << "\n";
  print_measures(correction.checks ? "optimum (search model, corrected: " + correction.describe() + ")"
                                   : std::string("optimum (search model)"),
                 m);
  const ConstraintValues margins = corrected_constraints_at(config, m, ref_strain, {}, &discrepancy, result.x);
  if (!discrepancy.empty())
    std::cout << "  margins of the search model corrected by the verified designs ("
              << discrepancy.describe(margins.names) << "):\n";
  print_constraints(margins);
  if (!result.feasible) {
    std::size_t worst = 0;
    for (std::size_t i = 1; i < margins.values.size(); ++i)
      if (margins.values[i] > margins.values[worst]) worst = i;
    if (margins.values[worst] > 0)
      std::cout << "binding constraint: " << margins.names[worst] << ", violated by " << fixed(100 * margins.values[worst], 1)
                << " % of its limit at the best design found within the bounds\n";
    else  // met, but within the search margin the optimiser asks for
      std::cout << "binding constraint: " << margins.names[worst] << ", met with " << fixed(-100 * margins.values[worst], 1)
                << " % to spare, less than the search margin of " << fixed(100 * config.search_margin, 1) << " %\n";
  }
}

// The ladder's accurate rung on an optimum: one segment by the 3D FEM against the rod (none if it
// cannot run), or the check the checkpoint holds from an earlier run.
std::optional<objectives::SolidSegmentCheck> check_in_3d(const DesignConfig& config, const std::vector<double>& x,
                                                         const objectives::ArmMeasures& rod_check,
                                                         DesignCheckpoint& checkpoint) {
  const int n = config.solid_check_segment;
  std::optional<objectives::SolidSegmentCheck> sc = checkpoint.solid_check(x);
  if (sc) {
    std::cout << "3D check of segment " << n << ": read from " << checkpoint.file().string() << "\n";
  } else {
    std::cout << "3D check of segment " << n << " (minutes) ...\n" << std::flush;
    try {
      sc = objectives::check_segment_in_3d(
          make_candidate(config, x), config.check, n, rod_check.segments[static_cast<std::size_t>(n - 1)], 1,
          [](double p, double deg) { std::cout << "  3D: " << fixed(p, 1) << " kPa, " << fixed(deg, 2) << " deg\n" << std::flush; },
          config.solid_check_model);
      checkpoint.add(x, *sc);
    } catch (const std::exception& e) {  // the search's results stand; the check reports why it could not run
      std::cout << "3D check of segment " << n << " could not run: " << e.what() << "\n";
      return std::nullopt;
    }
  }
  print_solid_check(*sc, config.requirements.bending_per_segment_deg);
  return sc;
}

// The accurate model's verdict on an optimum: every requirement on the cell rod of the whole arm
// (objectives/cell_rod_evaluation.hpp), or the verification the checkpoint holds from an earlier run.
std::optional<objectives::CellRodEvaluation> verify_on_cells(const DesignConfig& config, const std::vector<double>& x,
                                                            const objectives::ArmMeasures& searched, double ref_strain,
                                                            DesignCheckpoint& checkpoint, const CellCluster& cells,
                                                            Clock::time_point t0) {
  std::optional<objectives::CellRodEvaluation> v = checkpoint.verification(x);
  if (v) {
    std::cout << "verification on the cell rod: read from " << checkpoint.file().string() << "\n";
  } else {
    std::cout << "verification on the cell rod: each segment's ring-pitch cells and end cells along its ramp to "
              << fixed(config.check.working_pressure_kPa, 1) << " kPa (minutes; "
              << fixed(std::chrono::duration<double>(Clock::now() - t0).count(), 0) << " s into the run) ...\n"
              << std::flush;
    try {
      v = cells.evaluate(config, x, studies::task_progress(std::cout, "  cells"));
    } catch (const std::exception& e) {
      std::cout << "verification could not run: " << e.what() << "\n";
      return std::nullopt;
    }
    checkpoint.add(x, *v);
  }
  std::cout << "verification (" << v->model << "; cells " << fixed(v->cell_seconds, 0) << " s ("
            << fem::solver_work_text(v->cell_work) << "), " << v->poses
            << " rod poses " << fixed(v->pose_seconds, 1) << " s)";
  if (!v->ok()) {
    std::cout << ": no cells: " << v->failure << "\n";
    return v;
  }
  std::cout << "\n";
  print_measures("  accurate model", v->measures);
  const objectives::ArmMeasures& m = v->measures;
  for (int n = 0; n < 3; ++n) {
    const auto& seg = m.segments[static_cast<std::size_t>(n)];
    std::cout << "  segment " << n + 1 << ": " << fixed(seg.bending_deg_at_working, 1) << " deg at "
              << fixed(seg.pressure_kPa.empty() ? 0.0 : seg.pressure_kPa.back(), 1) << " kPa (search model "
              << fixed(searched.segments[static_cast<std::size_t>(n)].bending_deg_at_working, 1) << "), cells "
              << fem::to_string(v->segment_outcome[static_cast<std::size_t>(n)]) << " at "
              << fixed(v->segment_reached_kPa[static_cast<std::size_t>(n)], 1) << " kPa; burst utilisation "
              << fixed(seg.burst_utilisation, 3) << (seg.governing.empty() ? "" : " (" + seg.governing + ")") << "\n";
  }
  std::cout << "  payload " << fixed(m.payload_kg, 3) << " kg (search model " << fixed(searched.payload_kg, 3)
            << " kg), lifted at " << fixed(m.payload_lift_pressure_kPa, 1) << " kPa; heavier: " << m.payload_note << "\n";
  print_constraints(constraints_of(config, m, ref_strain));
  std::cout << "  " << objectives::check_fit_range(m, make_candidate(config, x).tube).words << "\n";
  std::cout << "  verdict on the accurate model: " << (meets_every_requirement(config, m, ref_strain) ? "every requirement met" : "NOT every requirement met") << "\n";
  return v;
}

// A verified design's rank: those that meet every requirement first, by objective; then by their
// largest violation.
std::pair<double, double> verified_rank(const DesignConfig& config, const objectives::ArmMeasures& m, double ref_strain) {
  double worst = -1e300;
  for (double g : constraints_of(config, m, ref_strain).values) worst = std::max(worst, g);
  return worst <= 1e-9 ? std::pair{0.0, objective_of(config, m, ref_strain)} : std::pair{1.0, worst};
}

std::size_t best_round(const DesignConfig& config, const DesignRun& run, double ref_strain) {
  std::size_t best = run.rounds.size() - 1;
  std::optional<std::pair<double, double>> best_rank;
  for (std::size_t k = 0; k < run.rounds.size(); ++k) {
    const auto& v = run.rounds[k].verification;
    if (!v || !v->ok()) continue;
    const auto rank = verified_rank(config, v->measures, ref_strain);
    if (!best_rank || rank < *best_rank) best = k, best_rank = rank;
  }
  return best;
}

// The centre of the next trust region: the best verified design so far (the start design included).
std::vector<double> best_verified(const DesignConfig& config, const DesignRun& run, double ref_strain,
                                  const std::vector<double>& fallback) {
  std::vector<double> x = fallback;
  std::optional<std::pair<double, double>> best_rank;
  if (run.thesis_verification && run.thesis_verification->ok())
    x = run.thesis_x, best_rank = verified_rank(config, run.thesis_verification->measures, ref_strain);
  for (const SearchRound& r : run.rounds) {
    if (!r.verification || !r.verification->ok()) continue;
    const auto rank = verified_rank(config, r.verification->measures, ref_strain);
    if (!best_rank || rank < *best_rank) x = r.optimum_x, best_rank = rank;
  }
  return x;
}

// Why an improvement round stops here, if it does: its search predicts an objective no better than
// the best verified design's by more than check.improvement_tolerance_percent (the search model's
// objective is the accurate one's where it is the mass; the corrected constraints are consistent at
// the centre). Then the round stops without a verification: within the trust region the corrected
// model knows no better design, the trust-region method's stopping test.
std::optional<std::string> improvement_stop(const DesignConfig& config, const DesignRun& run, double ref_strain) {
  const std::size_t best = best_round(config, run, ref_strain);
  const objectives::ArmMeasures& centre = run.rounds[best].verification->measures;
  const double now = objective_of(config, centre, ref_strain), predicted = run.result.best.objective;
  const double gain = (now - predicted) / std::max(std::abs(now), 1e-12);
  if (run.result.feasible && gain > config.improvement_tolerance) return std::nullopt;
  std::ostringstream why;
  why << "the improvement round's search predicts " << (run.result.feasible ? "" : "no feasible design, ")
      << "an objective " << fixed(100 * gain, 2) << " % better than the best verified design's (round " << best
      << "), within check.improvement_tolerance_percent (" << fixed(100 * config.improvement_tolerance, 2)
      << " %): no better design within the trust region by the corrected model";
  return why.str();
}

// A rank other than 0 under mpirun: the same config, silently, and its share of every verification's cells.
int serve_design(const std::string& file, CellCluster& cells) {
  try {
    const DesignConfig config = read_design_config(fem::load_json_file(file));
    cells.serve(config);
  } catch (const std::exception&) {
    return 2;  // rank 0 reads the same file and says why
  }
  return 0;
}
/// The run's first lines: the config's objective, requirements, search model, optimiser, the
/// verification and rounds it asks for, and what a checkpoint gives back.
void print_run_header(const std::string& file, const DesignConfig& config, int ranks, const DesignCheckpoint& checkpoint) {
  std::cout << "softarm design: " << file << "\nobjective: " << config.objective << "; requirements: mass <= "
            << config.requirements.max_mass_kg << " kg, payload >= " << config.requirements.min_payload_kg
            << " kg, bending >= " << config.requirements.bending_per_segment_deg << " deg per segment at "
            << config.requirements.max_pressure_kPa << " kPa, length " << config.requirements.length_m << " m\n"
            << "search model: reduced rod + axisymmetric RRA FEM level " << config.model.rra_mesh_level << "; optimiser "
            << config.optimiser.algorithm << ", budget " << config.optimiser.max_evaluations << " evaluations, "
            << config.optimiser.starts << " start(s)";
  if (config.verify_on_cells)
    std::cout << "; every optimum verified on the cell rod of the whole arm, which decides feasibility"
              << (ranks > 1 ? " (its cells spread over " + std::to_string(ranks) + " MPI ranks)" : "");
  else
    std::cout << "; no verification: the search model's verdict (fast fidelity)";
  if (config.solid_check_segment > 0) std::cout << "; 3D check of segment " << config.solid_check_segment;
  if (config.solid_corrections > 0) std::cout << "; up to " << config.solid_corrections << " correction round(s)";
  if (config.improvement_rounds > 0) std::cout << " and " << config.improvement_rounds << " improvement round(s)";
  std::cout << "\n";
  if (checkpoint.resumed_evaluations() + checkpoint.resumed_solid_checks() + checkpoint.resumed_verifications() > 0)
    std::cout << "resuming: " << checkpoint.resumed_evaluations() << " evaluations, " << checkpoint.resumed_solid_checks()
              << " 3D check(s) and " << checkpoint.resumed_verifications() << " verification(s) of an earlier run are "
              << "read from " << checkpoint.file().string() << " instead of computed (--fresh discards them)\n";
}

/// The answer's local peaks one RRA mesh level finer (run.finer_peaks): they come from a stress
/// singularity (the groove lip), averaged over a ball so that they converge; this shows how far.
void peaks_one_level_finer(const DesignConfig& config, DesignRun& run, double ref_strain) {
  if (config.mesh_sensitivity) {
    objectives::EvaluationSettings finer = config.check;
    finer.rra_mesh_level = config.check.rra_mesh_level + 1;
    run.finer_peaks = objectives::evaluate_arm(make_candidate(config, run.optimum_x), finer);
    run.finer_reference_strain = objectives::durability_reference_log_strain(
        config.requirements.durability_reference_pressure_kPa, finer.rra_mesh_level, finer.peak_averaging_radius_mm);
    std::cout << "local peaks one RRA mesh level finer (level " << finer.rra_mesh_level << "): burst utilisation "
              << fixed(run.finer_peaks->burst_utilisation, 3) << " (" << run.finer_peaks->burst_governing << ") vs "
              << fixed(run.check.burst_utilisation, 3) << "; durability strain ratio "
              << fixed(run.finer_peaks->durability_log_strain / run.finer_reference_strain, 3) << " vs "
              << fixed(run.check.durability_log_strain / ref_strain, 3)
              << " (peaks averaged over a ball of " << fixed(config.check.peak_averaging_radius_mm, 2)
              << " mm, which converge under refinement where the groove lip's point value does not; durability is a "
                 "ratio to the thesis RRA at the same level)\n";
  } else {
    std::cout << "local peaks one RRA mesh level finer: not computed (check.mesh_sensitivity is false)\n";
  }
}

/// Check and correct, round by round, when there was more than one.
void print_rounds(const DesignConfig& config, const DesignRun& run, double ref_strain) {
  if (run.rounds.size() > 1) {
    std::cout << "check and correct, round by round:\n";
    for (std::size_t k = 0; k < run.rounds.size(); ++k) {
      const auto& r = run.rounds[k];
      std::cout << "  round " << k << " (" << purpose_name(r.purpose) << "): ";
      if (r.verification && r.verification->ok())
        std::cout << "verified mass " << fixed(r.verification->measures.mass_kg, 3) << " kg, "
                  << (meets_every_requirement(config, r.verification->measures, ref_strain) ? "every requirement met"
                                                                            : "NOT every requirement met");
      else
        std::cout << "correction " << r.correction.describe() << "; mass " << fixed(r.optimum.mass_kg, 3) << " kg"
                  << (r.feasible ? "" : " (infeasible)");
      if (r.solid_check)
        std::cout << "; 3D: bending " << (r.solid_check->meets_bending() ? "met" : "NOT met") << ", working pressure "
                  << r.solid_check->working_pressure_verdict() << ", rod error " << fixed(r.solid_check->bending_error_percent(), 1)
                  << " %";
      std::cout << "\n";
    }
    if (!run.rounds_stop_reason.empty()) std::cout << "  no further round: " << run.rounds_stop_reason << "\n";
  }

}

/// The models' measured errors, then the answer as the cell rod verified it: every requirement met
/// or the binding one, and the search model's error at the answer.
void print_answer(const DesignConfig& config, const DesignRun& run, double ref_strain) {
  std::cout << "model errors (fidelity ladder, softarm fidelity):";
  for (const auto& e : model_errors_json(config.check.rra_mesh_level))
    std::cout << " " << e["what"].get<std::string>() << " by the " << e["model"].get<std::string>() << ": "
              << e["error_percent"].get<double>() << " % (" << e["measured_on"].get<std::string>() << ");";
  std::cout << "\n";

  if (const auto& v = run.verification(); v && v->ok()) {
    const ConstraintValues g = constraints_of(config, v->measures, ref_strain);
    std::cout << "\nanswer, verified on the cell rod: "
              << (verified_all_met(run) ? "the design meets every requirement: " : "NOT every requirement met by: ")
              << describe(config, run.optimum_x) << "\n";
    print_measures("accurate model", v->measures);
    print_constraints(g);
    if (!verified_all_met(run)) {
      std::size_t worst = 0;
      for (std::size_t i = 1; i < g.values.size(); ++i)
        if (g.values[i] > g.values[worst]) worst = i;
      std::cout << "binding constraint on the accurate model: " << g.names[worst] << ", violated by "
                << fixed(100 * g.values[worst], 1) << " % of its limit (after " << run.rounds.size() << " round(s))\n";
    }
    const objectives::ArmMeasures& raw = run.optimum_uncorrected;
    const auto percent = [](double search, double accurate) {
      return std::abs(accurate) > 1e-12 ? fixed(100 * (search - accurate) / std::abs(accurate), 1) + " %" : std::string("n/a");
    };
    std::cout << "search model's error at this design (uncorrected fibre rod against the cell rod): payload "
              << percent(raw.payload_kg, v->measures.payload_kg) << ", bending per segment "
              << percent(raw.segments[0].bending_deg_at_working, v->measures.segments[0].bending_deg_at_working) << " / "
              << percent(raw.segments[1].bending_deg_at_working, v->measures.segments[1].bending_deg_at_working) << " / "
              << percent(raw.segments[2].bending_deg_at_working, v->measures.segments[2].bending_deg_at_working)
              << ", burst utilisation " << percent(raw.burst_utilisation, v->measures.burst_utilisation) << "\n";
  } else if (config.verify_on_cells) {
    std::cout << "\nanswer NOT verified: the cell rod could not measure the final design (above)\n";
  }
}

/// What the rounds of search and verification carry from one round to the next.
struct RoundState {
  SolidCorrection correction;    // the 3D check's correction of the search model (solid_correction.hpp)
  DiscrepancyModel discrepancy;  // the verified designs' g_cells − g_search (discrepancy_model.hpp)
  double radius = 0;             // the trust region's half-width about the best verified design
  std::vector<double> x0;        // where the next search starts
  std::optional<objectives::ArmMeasures> rod_check;  // the last optimum at the check fidelity, uncorrected
  int corrections = 0, improvements = 0;              // rounds of each kind run so far
  RoundPurpose purpose = RoundPurpose::first_search;
};

/// A verified design teaches the discrepancy model its g_cells − g_search.
void learn(const DesignConfig& config, double ref_strain, RoundState& state, const std::vector<double>& x,
           const objectives::ArmMeasures& accurate, const objectives::ArmMeasures& searched) {
  state.discrepancy.add(normalised_design(config, x), constraints_of(config, accurate, ref_strain).values,
                        constraints_of(config, searched, ref_strain).values);
}

/// A round after the first: what it searches for and with which correction, in the log and the console.
void announce_round(const DesignConfig& config, const RoundState& state, const DesignRun& run, double ref_strain,
                    SearchLog& log) {
  const bool improving = state.purpose == RoundPurpose::improvement;
  const int count = improving ? state.improvements : state.corrections;
  log.next_round(run.result.evaluations, purpose_name(state.purpose) + (" " + std::to_string(count) + ": "));
  std::cout << "\n" << purpose_name(state.purpose) << " round " << count << " of at most "
            << (improving ? config.improvement_rounds : config.solid_corrections) << ": search again "
            << (improving ? "about the best verified design" : "from the last optimum")
            << " with the search model corrected by the " << (config.verify_on_cells ? "verified designs" : "3D check")
            << " ("
            << (config.verify_on_cells ? state.discrepancy.describe(constraints_of(config, {}, ref_strain).names)
                                       : state.correction.describe())
            << ")\n";
}

/// After a round verified on the cell rod: true, with the next round's purpose set, where another
/// round is due; false, with the reason in the run, where the rounds end.
bool another_round_after_verification(const DesignConfig& config, DesignRun& run, RoundState& state,
                                      const std::optional<objectives::CellRodEvaluation>& verification,
                                      const objectives::ArmMeasures& raw, double ref_strain) {
  if (!verification || !verification->ok()) {
    run.rounds_stop_reason = "the verification could not measure the last design";
    std::cout << "no further round: " << run.rounds_stop_reason << "\n";
    return false;
  }
  learn(config, ref_strain, state, run.optimum_x, verification->measures, raw);
  state.x0 = best_verified(config, run, ref_strain, state.x0);
  if (meets_every_requirement(config, verification->measures, ref_strain)) {
    // Trust-region model management past feasibility: the model is now corrected at this design
    // too, and the next search looks for a better one about the best verified design.
    if (state.improvements == config.improvement_rounds) {
      run.rounds_stop_reason = config.improvement_rounds == 0
                                   ? "the verification meets every requirement (check.improvement_rounds is 0)"
                                   : "the verification meets every requirement; every improvement round has run";
      std::cout << "the verification on the cell rod meets every requirement: no further round ("
                << run.rounds_stop_reason << ")\n";
      return false;
    }
    state.purpose = RoundPurpose::improvement;
    ++state.improvements;
    return true;
  }
  if (state.corrections == config.solid_corrections) {
    run.rounds_stop_reason = "the last verified design misses a requirement; every correction round has run";
    return false;
  }
  // The next search is corrected by every verified design, within a trust region half as wide
  // (the linear discrepancy was not enough to hold this one), about the best verified design.
  state.radius *= 0.5;
  state.purpose = RoundPurpose::correction;
  ++state.corrections;
  return true;
}

/// Without the cell rod's verification: true where the 3D check of one segment asks for a
/// correction round (set in the state), false where the rounds end.
bool another_round_after_3d_check(const DesignConfig& config, const DesignRun& run, RoundState& state,
                                  const std::optional<objectives::SolidSegmentCheck>& check,
                                  const objectives::ArmMeasures& raw) {
  if (state.corrections == config.solid_corrections || !check) return false;
  if (check->meets_bending() && check->holds_working_pressure()) {
    std::cout << "the 3D check meets bending and holds the working pressure: no correction needed\n";
    return false;
  }
  if (!run.result.feasible) {
    std::cout << "no correction round: the search found no design that meets every requirement of its own model\n";
    return false;
  }
  const SolidCorrection next = updated_correction(state.correction, *check, raw, config.check.working_pressure_kPa);
  if (next.checks == state.correction.checks) {
    std::cout << "no correction round: the 3D path stalled, so it measured neither bending at the working pressure "
                 "nor a limit point\n";
    return false;
  }
  state.correction = next;
  state.x0 = run.optimum_x;
  state.purpose = RoundPurpose::correction;
  ++state.corrections;
  return true;
}

/// Search, verify the optimum on the cell rod (and, if asked, one segment in 3D), and while the
/// verification finds a requirement not met, correct the search model by it and search again from
/// the last optimum (solid_correction.hpp); past feasibility, improvement rounds. The verification
/// decides feasibility.
void run_rounds(const DesignConfig& config, DesignRun& run, RoundState& state, double ref_strain, SearchLog& log,
                DesignCheckpoint& checkpoint, CellCluster& cells, Clock::time_point t0, MeasuresMemo& memo) {
  for (int round = 0;; ++round) {
    if (round > 0) announce_round(config, state, run, ref_strain, log);
    const double verification_s = !config.verify_on_cells ? 0.0
                                  : run.thesis_verification ? run.thesis_verification->measures.seconds
                                  : 240.0;  // a verification's cells on 2 cores, before one has been timed
    const bool improving = state.purpose == RoundPurpose::improvement;
    const int budget = improving && config.improvement_evaluations > 0
                           ? std::min(config.improvement_evaluations, config.optimiser.max_evaluations)
                           : config.optimiser.max_evaluations;
    const double after_s = run.rounds.empty() || !run.rounds.back().verification
                               ? verification_s
                               : run.rounds.back().verification->measures.seconds;
    run.result = search(config, ref_strain, state.correction, state.discrepancy, state.radius, state.x0, budget,
                        improving, checkpoint, log, after_s, memo);
    run.optimum_x = run.result.x;
    if (improving) {
      if (const auto stop = improvement_stop(config, run, ref_strain)) {
        run.rounds_stop_reason = *stop;
        std::cout << run.rounds_stop_reason << "\n";
        run.optimum_x = run.rounds.back().optimum_x;  // the answer stays a verified design (chosen after)
        return;
      }
    }
    const objectives::ArmMeasures raw =
        memo.measures(run.optimum_x, make_candidate(config, run.optimum_x), config.model);
    run.optimum = corrected(raw, state.correction);
    run.optimum_uncorrected = raw;
    print_optimum(config, run.result, run.optimum, ref_strain, state.correction, state.discrepancy);
    state.rod_check = memo.measures(run.optimum_x, make_candidate(config, run.optimum_x), config.check);
    std::optional<objectives::SolidSegmentCheck> check;
    if (config.solid_check_segment > 0) check = check_in_3d(config, run.optimum_x, *state.rod_check, checkpoint);
    std::optional<objectives::CellRodEvaluation> verification;
    if (config.verify_on_cells) verification = verify_on_cells(config, run.optimum_x, raw, ref_strain, checkpoint, cells, t0);
    run.rounds.push_back({state.purpose, state.correction, run.optimum_x, run.optimum, run.result.feasible, check,
                          verification, raw});
    run.answer_round = run.rounds.size() - 1;
    const bool another = config.verify_on_cells
                             ? another_round_after_verification(config, run, state, verification, raw, ref_strain)
                             : another_round_after_3d_check(config, run, state, check, raw);
    if (!another) return;
  }
}

/// The answer is the best verified design (the first that meets every requirement ends the rounds;
/// with none, the least violating), not merely the last.
void choose_answer(const DesignConfig& config, DesignRun& run, RoundState& state, double ref_strain,
                   MeasuresMemo& memo) {
  if (!config.verify_on_cells || run.rounds.empty()) return;
  run.answer_round = best_round(config, run, ref_strain);
  if (run.answer_round + 1 == run.rounds.size()) return;
  const SearchRound& a = run.rounds[run.answer_round];
  std::cout << "the answer is round " << run.answer_round << "'s design, the best verified one (every requirement "
               "met first, then the objective; else the least violation)\n";
  run.optimum_x = a.optimum_x;
  run.optimum = a.optimum;
  run.optimum_uncorrected = a.optimum_uncorrected;
  state.rod_check = memo.measures(run.optimum_x, make_candidate(config, run.optimum_x), config.check);
}

/// The answer re-checked by the search model at the check fidelity, and the difference it makes.
void recheck_answer(const DesignConfig& config, DesignRun& run, const RoundState& state, double ref_strain) {
  run.check_reference_strain = ref_strain;
  run.check = corrected(*state.rod_check, state.correction);
  print_measures("optimum re-checked by the search model (" + std::to_string(config.check.rod_nodes_per_segment) +
                     " rod nodes per segment, " + std::to_string(config.check.pressure_steps) + " pressure steps" +
                     (state.correction.checks ? ", corrected" : "") +
                     (config.verify_on_cells ? "; uncorrected: the rod's discretisation, not the verdict" : "") + ")",
                 run.check);
  print_constraints(constraints_of(config, run.check, run.check_reference_strain));
  std::cout << "fidelity difference: mass " << fixed(100 * (run.check.mass_kg / run.optimum.mass_kg - 1), 2)
            << " %, payload " << fixed(100 * (run.check.payload_kg / run.optimum.payload_kg - 1), 2) << " %, min bending "
            << fixed(run.check.min_bending_deg - run.optimum.min_bending_deg, 2) << " deg, burst utilisation "
            << fixed(run.check.burst_utilisation - run.optimum.burst_utilisation, 3) << "; search margin "
            << fixed(100 * config.search_margin, 1) << " %\n";
}

/// The requirements file with the command line's overrides; `--fidelity fast` is the fibre rod's
/// verdict alone, with its measured error printed.
DesignConfig configured(const nlohmann::json& document, const DesignOverrides& overrides) {
  DesignConfig config = read_design_config(document);
  if (!overrides.output_directory.empty()) config.output_directory = overrides.output_directory;
  if (!overrides.algorithm.empty()) config.optimiser.algorithm = overrides.algorithm;
  if (overrides.max_evaluations > 0) config.optimiser.max_evaluations = overrides.max_evaluations;
  if (overrides.fidelity == "fast") {
    config.verify_on_cells = false;
    config.solid_check_segment = 0;
    config.solid_corrections = 0;
    config.improvement_rounds = 0;
  }
  return config;
}

}  // namespace

int run_design(const std::string& file, const DesignOverrides& overrides) {
  CellCluster cells;  // rank 0 tells the others when it is done, however it ends
  if (!cells.root()) return serve_design(file, cells);
  const auto t0 = Clock::now();
  const nlohmann::json document = fem::load_json_file(file);  // read once: the config and the checkpoint's fingerprint
  const DesignConfig config = configured(document, overrides);
  prepare_output_directory(config.output_directory,
                           overrides.output_directory.empty() ? "output.directory" : "-o/--output");
  DesignCheckpoint checkpoint(config.output_directory, document, overrides.fresh);
  print_run_header(file, config, cells.size(), checkpoint);

  const double ref_strain =
      objectives::durability_reference_log_strain(config.requirements.durability_reference_pressure_kPa,
                                                  config.model.rra_mesh_level,
                                                  config.model.peak_averaging_radius_mm);
  std::cout << "durability reference: thesis RRA at " << config.requirements.durability_reference_pressure_kPa
            << " kPa, peak log strain " << fixed(ref_strain, 4) << " (lasted "
            << config.requirements.durability_reference_cycles << " cycles)\n";

  DesignRun run;
  run.config = &config;
  run.reference_strain = ref_strain;
  run.thesis_x = baseline_values(config);
  MeasuresMemo memo;  // the search model's measures of each design, once per run
  run.thesis = memo.measures(run.thesis_x, make_candidate(config, run.thesis_x), config.model);
  print_measures("thesis design (Tables 7, 11)", run.thesis);
  print_constraints(constraints_of(config, run.thesis, ref_strain));

  SearchLog log(config, ref_strain, run.history);  // history.csv, written as the searches go
  RoundState state;
  state.radius = config.trust_radius;
  state.x0 = run.thesis_x;
  // The first search starts corrected: the start design (the baseline) verified on the cell rod
  // first, so that no search runs on the uncorrected rod, whose error is 20-50 % where the search goes.
  if (config.verify_on_cells && (config.solid_corrections > 0 || config.improvement_rounds > 0)) {
    std::cout << "\nthe start design on the accurate model, to correct the first search by:\n";
    run.thesis_verification = verify_on_cells(config, run.thesis_x, run.thesis, ref_strain, checkpoint, cells, t0);
    if (run.thesis_verification && run.thesis_verification->ok())
      learn(config, ref_strain, state, run.thesis_x, run.thesis_verification->measures, run.thesis);
  }
  run_rounds(config, run, state, ref_strain, log, checkpoint, cells, t0, memo);
  choose_answer(config, run, state, ref_strain, memo);
  recheck_answer(config, run, state, ref_strain);
  peaks_one_level_finer(config, run, ref_strain);
  print_rounds(config, run, ref_strain);

  print_answer(config, run, ref_strain);
  run.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  write_design_outputs(run);
  std::cout << "total " << fixed(run.seconds, 1) << " s; written: " << config.output_directory
            << "/report.html, summary.json, history.csv, optimum_payload_pose.vtu, optimum_mesh.vtu\n";
  return 0;
}

}  // namespace softarm::engine

#pragma once
// Every requirement of an arm design on the accurate model (issue 33): the cell rod, whose
// sections are ring-pitch cells and end cells of the 3D model (fem/scenes/spl_cell_rod.hpp;
// within 1.4 % of the 3D reference along the thesis 3CA's curve and 2.8–4.6 % of its travel from
// the converged SPL pose). One set of cells per design, each segment's along the ramp of
// chambers 2 and 3 to the working pressure (the load every requirement speaks of), poses every
// scene below in milliseconds:
//
// - bending per segment: the segment alone on its own cells, top clamped, gravity perpendicular
//   to its axis and against the bend (the thesis' 3CA test); the tip axis' turn from rest,
//   signed towards the bend. Its ends are the end cells as the arm holds them (the top bonded to
//   its connector; the bottom bonded to the next connector on segments 1 and 2, free on 3): our
//   definition, the segment as it works in the arm.
// - payload: the whole arm hanging from the shoulder (gravity along its axis), chambers 2 and 3
//   of every segment together; the largest tip mass whose tip axis reaches the lift angle from
//   vertical at or below the working pressure (the first level where it does), held out at a
//   horizontal reach of at least lift_reach_fraction of the arm's length (payload_capacity.hpp's
//   reading; the sheath's stretch, which the cells do not resolve, is not a condition here);
// - burst: (c) a limit point of any cell or end cell below the working pressure (a chamber wall
//   ballooning between the rings inside the 3CA: the cells trace it by chamber-volume control);
//   (a), (b) the pressurised chambers' axial stretch from the cells, λ = λ₀ + |κ₀|·R_c/2 at each
//   cell (chambers 2 and 3 sit R_c/2 from the neutral plane on the stretched side, R_c the RRA
//   axis' distance from the 3CA's), mapped to the groove lips' peaks through the lone RRA's FEM
//   path as the search model maps its own (arm_evaluation.hpp);
// - durability: the same mapping's peak log strain at the working pressure;
// - mass: exact part volumes × densities, as the search model's.
#include <array>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "fem/core/parallel.hpp"
#include "fem/scenes/pressure_path.hpp"
#include "fem/scenes/spl_cell_job.hpp"
#include "fem/scenes/spl_cell_rod.hpp"
#include "fem/scenes/spl_scene.hpp"
#include "objectives/arm_evaluation.hpp"

namespace softarm::objectives {

struct CellRodEvaluation {
  /// Every measure on the cell rod; each segment's pressure_kPa / bending_deg is its lone path at
  /// the cells' levels. Fields the cell rod does not give stay as ArmMeasures' defaults
  /// (payload_tip_x_mm/z_mm hold the payload pose, rra_* the lone RRA's FEM evidence).
  ArmMeasures measures;
  std::array<fem::PathOutcome, 3> segment_outcome{fem::PathOutcome::completed, fem::PathOutcome::completed,
                                                  fem::PathOutcome::completed};
  std::array<double, 3> segment_reached_kPa{};  // each segment's cells: the working pressure or where they stopped
  int cells = 0, end_cells = 0, largest_cell_dofs = 0, largest_end_cell_dofs = 0;
  double cell_seconds = 0, pose_seconds = 0;
  fem::SolverWork cell_work;     // the cells' paths' solves, summed (Newton, factorisations, LUs, CG)
  int poses = 0;                 // rod equilibria solved (bending paths, payload search)
  std::string model;             // what was run, in words
  std::string failure;           // non-empty: no cells (the design has no ring pitch, a cell's tangent failed)
  std::string notes;             // cells that stopped short, and why
  bool ok() const { return failure.empty(); }
};

/// The accurate model's measures of `candidate` under `settings` (working pressure, target bending,
/// lift angle and reach, safety factor, the lone RRA's mesh level). `cell_levels`: outputs along the
/// cells' ramp (every 1/cell_levels of the working pressure). `adjust`, if given, changes each
/// segment's cell scene (a test's coarser mesh). `spread`, if given, runs the cells (over MPI ranks,
/// every one calling this with the same arguments; fem/scenes/spl_cell_job.hpp), else this process'
/// threads do: the same answer either way. Throws fem::InputError for a design that cannot be built.
CellRodEvaluation evaluate_arm_on_cells(const ArmCandidate& candidate, const EvaluationSettings& settings,
                                        int cell_levels = fem::kDefaultCellLevels,
                                        const std::function<void(fem::TcaSceneSpec&)>& adjust = {},
                                        const fem::TaskSpread& spread = {},
                                        const fem::TaskProgress& progress = {});

/// The arm's 3D scene whose cells the verification runs: chambers 2 and 3 of every segment at the
/// working pressure, hanging (gravity along −z), the solver settings of the design's 3D checks.
fem::SplSceneSpec arm_cell_scene(const ArmCandidate& candidate, const EvaluationSettings& settings);

/// Every field as JSON and back, exactly (a resumed design run reads the verification it wrote).
nlohmann::json to_json(const CellRodEvaluation& e);
CellRodEvaluation cell_rod_evaluation_from_json(const nlohmann::json& j);

}  // namespace softarm::objectives

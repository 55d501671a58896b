#include "fem/scenes/fidelity.hpp"

#include "fem/core/number_text.hpp"

#include <sstream>
#include <stdexcept>

namespace softarm::fem {
namespace {

std::string percent(double x) {
  std::ostringstream s;
  s.precision(3);
  s << x << " %";
  return s.str();
}

// Thesis RRA, extension at 206.8 kPa; reference Q2/P1 level 4 (77.139 mm, 350,178 dofs, 284 s):
// bench_rra_levels and bench_reduced_model. Times on one thread: Q2/P1 level 1 idle (0.56–0.77 s,
// docs/validation.md, The thesis RRA); the others from one bench_rra_levels run beside another
// solve, as ratios to level 1 there (Q1/P0 level 1: 0.25×, Q2/P1 level 3: 68×) applied to the idle
// 0.6 s.
FidelityLadder rra_ladder() {
  const std::string what = "extension of the thesis RRA at 206.8 kPa";
  return {"rra",
          "axisymmetric Q2/P1 level 4 (350,178 dofs): 77.139 mm",
          {{"reduced rod (uncalibrated chamber force)", true, 0, 0, 8.9, what, 0.01, 0},
           {"axisymmetric Q1/P0, level 1", false, 1, 1, 1.44, what, 0.15, 2222},
           {"axisymmetric Q2/P1, level 1", false, 1, 2, 0.61, what, 0.6, 6030},
           {"axisymmetric Q2/P1, level 3", false, 3, 2, 0.35, what, 40, 88818}}};
}

// Thesis 3CA, two chambers with gravity; reference 3D Hex20/P1 (27 points) with level 1's cross-
// section and level 4's element layers, half model (173,574 dofs, 3.1 GB, 429 s to 300 kPa idle on both
// threads; configs/convergence/tca_thesis_300kPa.json; docs/mesh-convergence.md, Layers to level 4:
// the whole 3CA): 90° at 277.93 kPa.
// On the 32 mm cut the cross-section is converged at level 1 once the layers are fine (0.06 % at 4
// layers) and the layers converge at order ~1 (a ring corner's singularity); over 2, 3 and 4 layers of
// the whole 3CA Richardson (fem/post/richardson.hpp) puts the reference 2.2 % short in bending at 150 kPa
// (order 1.07, 48.43° against 47.36°), and more towards the chambers' ballooning limit point, where the
// observed order falls to 0.5-0.7 and the extrapolation is not reliable (90° at 262.0 kPa at order 0.67
// from 2-4 layers, 271.8 kPa at order 1.21 from 1-3 layers). Errors are the worse of the bending along
// the curve (outputs every 30 kPa to 300 kPa, angles above 10°; the largest relative difference for the
// 3D models, the largest difference in degrees as a percentage of the reference there for the rod)
// and the 90° pressure:
// - the rod: 21.0 % (37.40° against 47.36° at 150 kPa), +6.9 % at 90° (297.2 kPa); on the main job's
//   optimised designs it is 22-48 % off (docs/reduced-model.md, Where the rod's error comes from);
// - the cell rod (fem/reduced/cell_rod.hpp) on cells about rings 1, 15 and 30 and both ends through
//   2 rings as end cells (fem/scenes/tca_end_cell.hpp), each Hex20/P1 at 27 points with level 4's
//   layers (cells 8,943 dofs, ends 15,444; 34 s for the five side by side, one thread each, to 300 kPa,
//   idle): +0.88 % at 60 kPa (15.91° against 15.78°), +1.18 % at 150 kPa, +1.40 % at 300 kPa; 90° at
//   274.2 kPa (−1.3 %); its sag under its weight −3.43° against −3.36° (the ends carry no weight of
//   their own). Without gravity against the same mesh run weightless: +0.9 % at 30 kPa to +1.4 % at
//   300 kPa; through 3 rings +0.5 % to +1.0 % (the ends' disturbance halves per ring pitch), through
//   1 ring +2.2 %, with rigid caps instead (the rung before this version) +4.0 % to +4.3 % (with
//   gravity +4.7 % at 60 kPa). On configs/tca_thesis.json the free end balloons at 314.1 kPa, where the
//   3D meshes do (309-316 kPa; 314.4 kPa with level 2's layers); the cells alone reach 344.7 kPa. `bench_tca_cell
//   configs/convergence/tca_thesis_300kPa.json --end-rings 2 --compare <reference curve.csv>`;
// - Hex20/P1 at 2×2×2 points, level 1: +0.85 % at 60 kPa, within 0.6 % above it; 90° at 278.77 kPa
//   (+0.3 %). A cancellation: across the section the 2×2×2 rule is stiff, along the axis soft, and the
//   two level-1 errors nearly cancel (32 mm cut: docs/mesh-convergence.md, One direction at a
//   time); 202 s to the limit point (314 kPa), 120 s to 300 kPa, idle, both threads.
// Left off, dominated by it (bending along the curve; 90° pressure; time): Hex20/P1 level 1 with level
// 2's layers, the default before this version (−3.35 % at 300 kPa; 287.42 kPa, +3.4 %; 423 s to the
// limit point), with level 3's layers (−1.3 %; 281.34 kPa, +1.2 %; 292 s to 300 kPa), Hex20/P1 level 2
// (287.3 kPa, +3.4 %; ~100 min on one thread), Hex27/P1 level 1 (−5.5 % at 300 kPa; 293.78 kPa,
// +5.7 %; 391 s) and Hex20/P1 level 1 at 27 points (−9.6 % at 300 kPa; 308.05 kPa, +10.8 %).
FidelityLadder tca_ladder() {
  return {"tca",
          "3D Hex20/P1, level 1 with level 4's layers, half model (173,574 dofs; Richardson over the layers: "
          "~2 % short in bending at mid-curve, more near the limit point): 90° at 277.93 kPa",
          {{"reduced rod, 17 nodes", true, 0, 0, 21.0,
            "bending angle along the curve (worst point; 90° pressure: 6.9 %); on other designs up to 48 % "
            "(docs/reduced-model.md, Where the rod's error comes from)",
            0.05, 51},
           {"cell rod: 3 ring-pitch cells and both ends through 2 rings (3D, level 4 layers)", true, 1, 2, 1.4,
            "bending along the curve (90° pressure: 1.3 %); against the layers' Richardson estimate −1.1 % at "
            "150 kPa (47.92° against 48.43°), on the 90° pressure +0.9 to +4.7 % (271.8 to 262.0 kPa, order 1.21 "
            "to 0.67)",
            34, 15444, true, false, 4, true, 2},
           {"3D Hex20/P1 at 2x2x2 Gauss points, level 1", false, 1, 2, 0.85,
            "bending along the curve (90° pressure: 0.3 %)", 202, 43992, true, true},
           {"3D Hex20/P1, level 1, layers of level 4", false, 1, 2, 0,
            "reference; against its layers' Richardson estimate −2.2 % at 150 kPa, on the 90° pressure +2.3 to +6.1 %",
            429, 173574, true, false, 4}}};
}

// SPL: the reference is Hex20/P1 at 27 points with level 1's cross-section and level 3's element
// layers, full model (configs/convergence/spl_thesis_pose_axial3.json: 764,472 dofs, a 952 GFlop
// factorisation with nnz(L) 674 M, 16.3 GB resident; 5,785 s on both threads, ~25 min of it beside a
// build and other runs; 23 load steps, 115 Newton iterations). Level 2 (~2 M dofs) does not fit this
// machine; on the 3CA the cross-section is converged at level 1 once the layers are fine, and the
// layers converge at order ~1 (docs/mesh-convergence.md, Layers beyond level 2; Layers to level 4:
// the whole 3CA). The tip with 1, 2 and 3 layers per band:
// (261.7, 299.6, 267.7), (238.7, 307.9, 277.0), (228.8, 310.1, 278.8) mm; the steps 26.1 and 10.3 mm
// fit an order of ~0.7, which leaves this reference ~21-31 mm (order 1 to 0.7) from the converged tip,
// 40 mm extrapolating each coordinate with its own order, so the errors below are lower bounds.
// Errors: the tip's distance from the reference's over the reference tip's 476 mm travel
// (docs/fidelity-ladder.md, The SPL):
// - Hex20/P1 level 1 with level 2's layers (configs/convergence/spl_thesis_pose_axial2.json, 2,845 s,
//   the reference before this version): 10.3 mm, 2.2 %; joints 5.1 mm off on average.
// - The cell rod on ring-pitch cells and end cells (fem/scenes/spl_cell_rod.hpp: 9 cells and 6 end cells
//   through 2 rings, each segment's top bonded to its connector, its bottom too but the tip's, free;
//   Hex20/P1 at 27 points, level 1, level 4's layers; half models where a segment's pressures allow,
//   else full: up to 16,593 dofs a cell, 35,214 an end cell; each cell's GJ from the same cell with
//   periodic faces at rest, each bonded end's twist from its end cell at rest (twist_compliance.hpp);
//   ~225 s, the cells side by side on one thread each, the rod 10 ms for six poses;
//   configs/spl_thesis_pose.json's default): tip 22.1 mm, 4.6 %; joints 10.1 mm off on average;
//   each segment's own bend 70.17°, 90.47°, 18.01° against 67.79°, 86.08°, 20.03°. Against the
//   reference's Richardson estimates of the converged tip, (198.6, 316.8, 284.3) mm at order 0.7 and
//   (209.0, 314.5, 282.4) at order 1 (2 and 3 layers per band, ratio 1.5): 18.7 and 13.2 mm, where
//   the reference itself is 31.4 and 20.6 mm off them (13.0 and 15.0 mm against the tips extrapolated
//   before as if the layers had doubled, 16.4 and 10.3 mm from the reference). The bonded ends' twist moved the tip 1.7 mm
//   closer (with the cells' GJ over the ends: 23.8 mm, 5.0 %; joints 10.4 mm; bends 70.28°, 90.58°,
//   18.01°; 15.1 and 17.1 mm from the Richardson tips); its cost, 18.6 s of one thread, was measured
//   on a machine that ran the whole default in 354 s and the 3CA default in 101 s (52 s on the
//   machine of the other figures), hence ~225 s. On rigid caps (the rung before this version,
//   102 s): tip 20.1 mm, 4.2 %, joints 7.9 mm; bends 68.42°, 88.60°, 18.46°; 17.8 and 16.9 mm from the
//   Richardson tips. The end cells are kept, though the reference prefers rigid caps: at equal mesh
//   on short SPLs whose ends are most of each segment (no gravity), the 3D model bends segments 1 and
//   2 as the end cells do (within 0.8 % with 7 rings, 141,102 dofs; 1.7 % with 5, test [spl]) and
//   rigid caps do not (−6 % to −16 %); the tip 2.3 % and 2.5 % of its travel off against 6.6 % and
//   12.8 %. On the thesis arm, whose weight's moments and last fifth of the ramp (the distal segment
//   curling back) the short ones lack, the two differ by less than the reference's own distance from
//   converged (21-40 mm).
//   (With the chord lids before the closed ones, chamber_pressure_form.cpp, rigid caps: tip 20.2 mm,
//   joints 9.5 mm, bends 65.82°, 84.77°, 18.11°.)
//   Measured on the way there (bench_spl_cell_rod --compare <reference summary.json> [--full]
//   [--torsion-scales ...]):
//   - GJ from the fibre section's polar moment (at mid-height, rings left out) instead of the cells':
//     38.1 mm, 8.0 %; that GJ halved or doubled: 176 or 76 mm (chord lids). Torsion carries the pose:
//     the segments bend about their own axes and the weight beyond each twists it.
//   - Full-model cells everywhere (on rigid caps, 196 s), whose out-of-plane bending compliance under
//     pressure is up to twice the in-plane one (the half model takes the in-plane value for both): 40.5 mm, 8.5 %
//     (42.9 mm with the chord lids). Which of the two is nearer the converged pose is open (the
//     reference is 21-40 mm from it).
// - The spatial rod (0.9-1.1 s, bench_reduced_model; 57 nodes x 4 unknowns): 211 mm, 44 %; joints
//   120 mm off on average; in one plane it poses the thesis 3CA within 0.3 % of the planar rod
//   (test_spatial_rod).
// - Hex8 is a qualitative preview (it locks in bending: the 3CA reaches 34° instead of 107° at
//   344.7 kPa, −68 %; its SPL tip is 281 mm off).
// Left off, dominated by the cell rod on this pose (slower and further from the reference):
// - Hex20/P1 level 1 at 27 points (configs/convergence/spl_thesis_pose_hex20.json, the config's default
//   before this version; 256,164 dofs, 1,036 s): 36.3 mm, 7.6 %; joints 18.8 mm.
// - Hex20 at 2x2x2 points, level 1 (configs/convergence/spl_thesis_pose_hex20r.json, 2,474 s): 29.0 mm,
//   6.1 %; joints 17.9 mm.
FidelityLadder spl_ladder() {
  const std::string tip = "tip position: distance over the reference tip's 476 mm travel";
  // The same tip's distance from the converged tip as the reference's layers extrapolate it
  // (Richardson over 2 and 3 layers per band, ratio 1.5, at the order 0.7 that 1, 2 and 3 layers show
  // and at order 1: (198.6, 316.8, 284.3) and (209.0, 314.5, 282.4) mm,
  // benchmarks/data/spl_thesis_pose_axial3_joints.json), the estimate of
  // the converged reference that issue 6 asks the errors against; the selection keeps the
  // measured run's error (a lower bound), the estimate's order being itself uncertain.
  const auto richardson = [](double at_order_07_mm, double at_order_1_mm) {
    return "; from the Richardson tips (order 0.7 / 1) " + percent(100 * at_order_07_mm / 476) + " / " +
           percent(100 * at_order_1_mm / 476) + " (" + number_text(at_order_07_mm, 3) + " / " +
           number_text(at_order_1_mm, 3) + " mm)";
  };
  return {"spl",
          "3D Hex20/P1, level 1 with level 3's layers, full model (764,472 dofs; level 2 does not fit; ~20-40 mm "
          "from converged at the tip by Richardson over the layers): tip (228.8, 310.1, 278.8) mm",
          {{"reduced spatial rod, 17 nodes per segment", true, 0, 0, 44.0, tip + " (joints 120 mm off on average)" + richardson(228, 222), 1.1,
            228},
           {"3D Hex8/P0, level 1 (preview: locks in bending)", false, 1, 1, 68, "3CA bending at 344.7 kPa", 48, 66132},
           {"cell rod: 3 ring-pitch cells per segment and both ends through 2 rings (3D, level 4 layers)", true, 1, 2,
            4.6,
            tip + " (joints 10.1 mm off on average; at equal mesh on a short SPL 2.3 %: docs/cell-rod.md, "
                  "End cells on the SPL)" + richardson(18.7, 13.2),
            225, 35214, true,
            false, 4, true, 2},
           {"3D Hex20/P1, level 1, layers of level 2", false, 1, 2, 2.2,
            tip + " (joints 5.1 mm off on average)" + richardson(41.7, 30.9), 2845,
            510318, true, false, 2},
           {"3D Hex20/P1, level 1, layers of level 3", false, 1, 2, 0, "reference" + richardson(31.4, 20.6), 5785, 764472,
            true, false, 3}}};
}

}  // namespace

const FidelityLadder& fidelity_ladder(const std::string& scene) {
  static const FidelityLadder rra = rra_ladder(), tca = tca_ladder(), spl = spl_ladder();
  if (scene == "rra") return rra;
  if (scene == "tca") return tca;
  if (scene == "spl") return spl;
  throw std::invalid_argument("fidelity_ladder: unknown scene " + scene);
}

double fidelity_target_percent(const std::string& fidelity) {
  if (fidelity == "fast") return kCheapestModel;
  if (fidelity == "balanced") return 2;
  if (fidelity == "accurate") return 0.5;
  throw std::invalid_argument("fidelity_target_percent: unknown fidelity " + fidelity);
}

ModelSelection select_model(const std::string& scene, double target_percent) {
  const FidelityLadder& ladder = fidelity_ladder(scene);
  if (target_percent == kCheapestModel) {
    const ModelLevel& cheapest = ladder.levels.front();
    return {cheapest, "the cheapest model, whatever its error: measured error " + percent(cheapest.error_percent) +
                          " (" + cheapest.error_measure + ") against " + ladder.reference};
  }
  for (const ModelLevel& m : ladder.levels)
    if (m.error_percent <= target_percent)
      return {m, "the cheapest model within " + percent(target_percent) + ": measured error " +
                     percent(m.error_percent) + " (" + m.error_measure + ") against " + ladder.reference};
  const ModelLevel& best = ladder.levels.back();
  return {best, "no model is measured within " + percent(target_percent) + "; the most accurate one has " +
                    percent(best.error_percent) + " against " + ladder.reference};
}

}  // namespace softarm::fem

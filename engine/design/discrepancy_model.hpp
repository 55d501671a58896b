#pragma once
// How far the search model is from the accurate one, as a function of the design: the model
// management of `softarm design` (issue 33). Every design verified on the cell rod
// (objectives/cell_rod_evaluation.hpp) gives each constraint's discrepancy
//     δ_i(u_j) = g_i^cells(u_j) − g_i^search(u_j)
// at its point u_j in the normalised design space (each variable mapped to [0, 1] over its
// bounds; every categorical choice at 0, so that no slope extrapolates across materials). The
// search then runs on
//     g̃_i(u) = g_i^search(u) + δ_i(u_c) + b_iᵀ (u − u_c),
// u_c the newest verified design: an additive correction (Eldred, Giunta & Collis 2004) whose
// linear term interpolates every other verified design exactly, the minimum-norm slope b_i with
// D b_i = Δ_i (rows of D: u_j − u_c; Δ_ij = δ_i(u_j) − δ_i(u_c)). At u_c it is zeroth-order
// consistent, and first-order consistent along every direction the verified designs span: a
// secant update of the correction, in the spirit of the trust-region model management of
// Alexandrov, Dennis, Lewis & Torczon (1998), which asks for the accurate gradient, where one
// cell-rod gradient would cost a verification per variable. The search around u_c is held to a
// box of half-width `radius` (engine/design/design_command.cpp): the linear term is trusted
// only near the designs it was fitted on.
#include <string>
#include <vector>

namespace softarm::engine {

class DiscrepancyModel {
 public:
  /// A verified design: its normalised point, and each constraint's g by the accurate and by the
  /// search model there (uncorrected). The newest becomes the centre.
  void add(const std::vector<double>& u, const std::vector<double>& g_accurate, const std::vector<double>& g_search);

  bool empty() const { return points_.empty(); }
  int points() const { return static_cast<int>(points_.size()); }
  const std::vector<double>& centre() const { return points_.back().u; }

  /// δ(u), one entry per constraint (empty before the first verified design: no correction).
  std::vector<double> at(const std::vector<double>& u) const;

  /// "δ at the centre: payload −0.41, …; linear term from N other verified designs" (g units).
  std::string describe(const std::vector<std::string>& names) const;

 private:
  struct Point {
    std::vector<double> u, delta;
  };
  std::vector<Point> points_;
  std::vector<std::vector<double>> slope_;  // per constraint, over u
  void fit();
};

}  // namespace softarm::engine

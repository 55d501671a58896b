#pragma once
// The scalar root of a shooting residual f(m) (arm_rod.hpp: the tip moment as a
// function of the clamp moment), where f may be undefined (NaN) beyond an edge:
// a section past its limit point or a fibre outside its table.
//
// Why more than the secant method: under a heavy tip mass near the working
// pressure the clamp section works close to its limit point. There f has a
// positive local minimum next to the root, and the root lies in a narrow band
// where f plunges before the NaN edge (measured on a design of the main job:
// f = +244 N·mm at m = −1081.9, −499 N·mm at −1084.1, NaN beyond ≈ −1090).
// The plain secant circles the minimum for its 80 iterations, and whether it
// strayed into the band decided the payload capacity to ±10 % between designs
// 1e-4 apart. So:
//   1. secant from the warm start, stepping back towards the last defined point
//      when a trial is undefined (as before);
//   2. every defined evaluation updates the bracket, the nearest pair of
//      opposite signs; once there is one, Illinois regula falsi inside it
//      (Dahlquist & Björck, Numerical Methods, §6.2), which cannot leave it;
//   3. a secant that stalls with no bracket searches outwards from the point of
//      least |f|, both ways, with doubling steps; at an undefined point it
//      bisects back towards the defined side, where the band lies.
// No root found (f of one sign up to the edges on both sides) is a limit point.
#include <functional>
#include <string>

namespace softarm::fem {

struct ShootingRoot {
  double m = 0, f = 0;  // the last evaluation's argument and value (the root when converged)
  bool converged = false;
  int evaluations = 0;
};

struct ShootingSettings {
  double tolerance = 1e-10;  // |f| ≤ tolerance·scale
  double scale = 1;          // of f and m alike (a moment scale, N·mm)
  double first_step = 1e-4;  // the secant's first step, × scale
  double max_step = 0.5;     // no secant jump larger than this, × scale
  int secant_iterations = 40;
  int bracket_iterations = 100;
};

/// `f(m)` evaluates the residual (NaN where undefined) and leaves its state behind: the
/// last call made is always at the returned m.
ShootingRoot shooting_root(const std::function<double(double)>& f, double start, const ShootingSettings& settings);

}  // namespace softarm::fem

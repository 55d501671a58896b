#pragma once
// The count behind Newton's unstable-branch guard (NewtonSettings::max_indefinite_iterations).

namespace softarm::fem {

/// The count after an iteration: an iteration on an indefinite tangent adds one unless it halved the
/// best residual so far (`new_best`); one that did halve it leaves the count; a positive definite
/// iteration clears it only where it halved it too. Past the thesis 3CA's free-end limit point a
/// shifted run stalled at 3.6e-3, one positive definite iteration threw the residual to 0.41, and
/// four more indefinite ones followed before the step was given up: 13 iterations, each a
/// factorisation and its failed tries, where 10 do without the clearing. The first
/// iteration has no best to halve: it counts as no progress when indefinite and clears when not.
inline int indefinite_without_progress_after(int count, bool positive_definite, bool first, bool new_best) {
  if (positive_definite) return first || new_best ? 0 : count;
  return first || !new_best ? count + 1 : count;
}

}  // namespace softarm::fem

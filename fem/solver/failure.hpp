#pragma once
// Typed solver failures (FEBio's approach): each one tells the load stepper
// what went wrong so it can choose a retry (cut the step back, drop the
// predictor) and, when retries are exhausted, tell the user why.
#include <string>

namespace softarm::fem {

enum class Failure {
  none,
  inverted_element,      // det F <= 0 somewhere, even after line search
  line_search_failed,    // no step length reduced the energy or the residual
  max_iterations,        // Newton did not converge in the allowed iterations
  diverged,              // residual grew by orders of magnitude
  singular_tangent,      // neither Cholesky nor LU could factorise the tangent
  unstable_branch,       // the tangent stayed indefinite for several iterations that made no progress,
                         // or Newton converged on an indefinite one: no stable equilibrium near this
                         // load (past a limit point), so the step is hopeless
};

inline const char* to_string(Failure f) {
  switch (f) {
    case Failure::none: return "none";
    case Failure::inverted_element: return "inverted_element";
    case Failure::line_search_failed: return "line_search_failed";
    case Failure::max_iterations: return "max_iterations";
    case Failure::diverged: return "diverged";
    case Failure::singular_tangent: return "singular_tangent";
    case Failure::unstable_branch: return "unstable_branch";
  }
  return "unknown";
}

}  // namespace softarm::fem

// The algorithms behind Options::algorithm, their names and their traits.
//
// Choice (NLopt: https://nlopt.readthedocs.io/en/latest/NLopt_Algorithms/):
//  - nlopt:cobyla        derivative-free local, handles inequality constraints
//                        natively with linear models: the default, since each
//                        evaluation is a FEM solve and no gradient is needed.
//  - nlopt:auglag_bobyqa augmented Lagrangian (AUGLAG) around BOBYQA's quadratic
//                        models, derivative-free; often fewer evaluations than
//                        COBYLA on smooth objectives.
//  - nlopt:isres         global, stochastic (evolution strategy with stochastic
//                        ranking of constraints); uses 80 % of its budget, then a
//                        COBYLA polish from the best point with the rest.
//  - nlopt:slsqp         sequential quadratic programming, gradient-based.
//  - nlopt:ccsaq         conservative convex separable quadratic approximations
//                        (CCSA family, Svanberg 2002), gradient-based. Chosen
//                        over its sibling LD_MMA: NLopt 2.7.1's MMA stalls on
//                        a quadratic with one linear constraint (it proposes the
//                        same bound corner forever; cf. stevengj/nlopt issues
//                        #191 and #482), CCSAQ converges on it in 10 calls.
//  - ipopt               interior point (Ipopt, limited-memory quasi-Newton
//                        Hessian), gradient-based.
// Gradients are finite differences (finite_difference.hpp).
#pragma once

#include <string>
#include <vector>

namespace softarm::optimise::detail {

enum class Algorithm { cobyla, auglag_bobyqa, isres, slsqp, ccsaq, ipopt };

/// Throws std::invalid_argument listing algorithm_names() for an unknown name.
Algorithm parse_algorithm(const std::string& name);
bool uses_gradients(Algorithm a);
bool is_global(Algorithm a);

}  // namespace softarm::optimise::detail

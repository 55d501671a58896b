#pragma once
// The tube wall of a ring-reinforced actuator as its rings hold it: rigid rings
// keep the wall's radius R_i (the rings' inner radius, the grooves' bottom)
// from changing, and the wall is incompressible, so one number, the axial
// stretch λ, fixes the whole wall between the chamber (R_c) and R_i. Per unit
// reference length a circle of reference radius R goes to
//     r(R)² = R_i² − (R_i² − R²)/λ,
// with principal stretches (λ, r/R, R/(λ r)): the wall thins and the chamber
// widens as it extends. Two consequences the free-fibre section misses:
//  - the wall is stiffer than a free fibre (it cannot contract in hoop);
//  - the chamber's volume per reference length, V' = π(R_i² λ − R_i² + R_c²),
//    grows at dV'/dλ = π R_i² at any λ, so the pressure's work makes an axial
//    force p·π R_i² on the ringed length, not p·π R_c² (the cap's area).
// Evidence (docs/reduced-model.md, Where the rod's error comes from; What the rings do): the
// thesis 3CA in 3D with rings of tube silicone instead of ABS bends 0.04° at 50 kPa against 16.2°.
#include "fem/materials/hyperelastic_law.hpp"
#include "fem/reduced/fibre_law.hpp"

namespace softarm::fem {

/// Smallest λ the confined kinematics allow: the chamber closes at λ = 1 − R_c²/R_i².
double confined_wall_min_stretch(double chamber_radius_mm, double confinement_radius_mm);

/// The wall's mean nominal axial stress P(λ) = (1/A) dΠ/dλ, Π = ∫ W 2πR dR over
/// R_c ≤ R ≤ R_i, A = π(R_i² − R_c²), tabulated as a FibreLaw from just above the
/// closing stretch to 6.
FibreLaw confined_wall_law(const HyperelasticLaw& law, double chamber_radius_mm, double confinement_radius_mm,
                           int points = 801);

}  // namespace softarm::fem

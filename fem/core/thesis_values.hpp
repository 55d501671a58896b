#pragma once
// The thesis' test conditions that softarm takes as its defaults (spec §1, §3): one place, each with
// its source. Every one is a default only: the configs that use it can override it (the requirements'
// max_pressure_kPa and durability_reference_pressure_kPa, a scene's load).
namespace softarm::fem::thesis {

/// 50 psi: the SPL's supply pressure, the 3CA's bending test (two chambers 0 → 344.7 kPa, spec §1) and
/// the requirements' working pressure (spec §3, Table 1).
inline constexpr double kWorkingPressure_kPa = 344.7;

/// 30 psi: the lone RRA's extension test and its cycling test, 0 ↔ 206.8 kPa for 1.1 M cycles on
/// average (spec §1): the durability criterion's reference.
inline constexpr double kRraTestPressure_kPa = 206.8;

}  // namespace softarm::fem::thesis

#pragma once
// π and the degree, spelled once (C++20's std::numbers::pi). Angles are radians inside softarm and
// degrees where a key, an option or a printout says _deg: angle_deg = angle_rad · kDeg.
#include <numbers>

namespace softarm::fem {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kDeg = 180 / std::numbers::pi;  // degrees per radian

}  // namespace softarm::fem

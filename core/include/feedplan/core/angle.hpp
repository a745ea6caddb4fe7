#pragma once
// Angle conversions. The library works in radians; degrees appear only in user-facing text and
// specs (docs/method.md §3).

#include <numbers>

namespace feedplan {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kTwoPi = 2.0 * std::numbers::pi;

constexpr double deg_to_rad(double angle_deg) { return angle_deg * kPi / 180.0; }
constexpr double rad_to_deg(double angle_rad) { return angle_rad * 180.0 / kPi; }

}  // namespace feedplan

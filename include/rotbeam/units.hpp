// Unit conversions used across the layers, each written once.
#pragma once

#include <cmath>

namespace rotbeam {

/// An angular speed in rev/min as rad/s: ω = 2π n / 60.
inline constexpr double rad_per_s_from_rpm(double rpm) { return rpm * M_PI / 30.0; }

/// Radians as degrees.
inline constexpr double degrees(double rad) { return rad * 180.0 / M_PI; }

}  // namespace rotbeam

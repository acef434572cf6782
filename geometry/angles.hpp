// Angle constants, one definition for every library: degrees to radians and back, pi, ln 2.
#pragma once

#include <cmath>

namespace msislab {

inline constexpr double kPi = M_PI;
inline constexpr double kDegToRad = M_PI / 180.0;
inline constexpr double kRadToDeg = 180.0 / M_PI;
inline constexpr double kLn2 = 0.69314718055994530942;

}  // namespace msislab

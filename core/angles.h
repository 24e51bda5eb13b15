// Avenues — angle conversions, named for what they return (pbrt-v4's xFromY, read right
// to left): rad_from_deg(90) is π/2. Plans and the command line speak degrees; every
// computation works in radians. Nothing else in the tree defines a "kDeg".
#pragma once

#include <numbers>

namespace avenues {

/// Radians from degrees.
constexpr double rad_from_deg(double deg) { return deg * (std::numbers::pi / 180.0); }
/// Degrees from radians.
constexpr double deg_from_rad(double rad) { return rad * (180.0 / std::numbers::pi); }

}  // namespace avenues

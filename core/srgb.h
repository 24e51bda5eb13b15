// Avenues — sRGB encoding (IEC 61966-2-1): 8-bit colours as files write them, to the
// linear light Avenues computes in, and back.
#pragma once

#include <array>
#include <cmath>

namespace avenues {

/// An sRGB-encoded component in [0, 1] as linear light in [0, 1].
inline double linear_from_srgb(double e) { return e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4); }
/// Its inverse, the sRGB transfer function: linear light in [0, 1] as an encoded component
/// in [0, 1] (what a picture's 8-bit code, or an MTL Kd as Avenues reads it, holds).
inline double srgb_from_linear(double v) { return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055; }
/// An sRGB-encoded colour (an MTL Kd, a table's RGB) as linear light, component by component.
inline std::array<double, 3> linear_from_srgb(const std::array<double, 3>& e) {
  return {linear_from_srgb(e[0]), linear_from_srgb(e[1]), linear_from_srgb(e[2])};
}

}  // namespace avenues

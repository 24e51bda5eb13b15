// Avenues — doubles rounded to a float's precision, as single-precision files store them.
//
// Written out with frexp and ldexp because GCC 12 at -O3 vectorises double(float(x)) on
// neighbouring fields wrongly and drops the rounding of some of them: a test that meant to
// store a mesh in floats kept some of its coordinates as doubles, and a check of whether a
// soup is stored in floats could say no for a soup that is.
#pragma once

#include <cmath>

#include "core/geometry.h"

namespace avenues {

/// v rounded to a float's 24-bit significand (ties to even), kept as a double. (No float
/// subnormals or overflow: coordinates in metres are far from both.)
inline double to_float(double v) {
  int e = 0;
  const double m = std::frexp(v, &e);
  return std::ldexp(std::nearbyint(std::ldexp(m, 24)), e - 24);
}

inline Vec3 to_float(Vec3 p) { return {to_float(p.x), to_float(p.y), to_float(p.z)}; }

/// True when v is a float's value: a file stored in single precision holds only these.
inline bool is_float(double v) { return to_float(v) == v; }

}  // namespace avenues

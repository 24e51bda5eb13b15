// An independent reference for visibility: brute-force ray casting against every opaque
// polygon of a cell complex (no cells, no portals, no masks involved).
#pragma once

#include <cmath>
#include <limits>
#include <vector>

#include "cells/cell_complex.h"

namespace avenues::testing {

/// Distance along `dir` from `o` to the first opaque polygon hit (dir need not be unit).
inline double first_hit(const CellComplex& c, Vec3 o, Vec3 dir) {
  double best = std::numeric_limits<double>::infinity();
  for (const Cell& cell : c.cells)
    for (const Face& f : cell.faces) {
      double den = dot(f.plane.n, dir);
      if (den == 0) continue;
      double t = -f.plane.eval(o) / den;
      if (!(t > 0) || t >= best) continue;
      Vec3 p = o + t * dir;
      for (const OpaquePoly& op : f.opaque) {
        // Inside the convex polygon (counter-clockwise about the inward normal -n).
        bool in = true;
        const size_t m = op.poly.size();
        for (size_t k = 0; k < m && in; ++k) {
          Vec3 a = op.poly[k], b = op.poly[(k + 1) % m];
          in = dot(cross(b - a, p - a), f.plane.n) <= 1e-12;
        }
        if (in) {
          best = t;
          break;
        }
      }
    }
  return best;
}

/// Length of the part of segment o + t·dir, t in [t0, t1], inside the cell's prism.
inline double length_inside(const Cell& cell, Vec3 o, Vec3 dir, double t0, double t1) {
  for (const Face& f : cell.faces) {
    double a = f.plane.eval(o), b = dot(f.plane.n, dir);  // inside: a + t·b <= 0
    if (b == 0) {
      if (a > 0) return 0;
      continue;
    }
    double t = -a / b;
    if (b > 0) t1 = std::min(t1, t);
    else t0 = std::max(t0, t);
    if (t0 >= t1) return 0;
  }
  return (t1 - t0) * length(dir);
}

}  // namespace avenues::testing

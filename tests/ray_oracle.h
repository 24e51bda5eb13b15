// An independent reference for visibility: brute-force ray casting against every opaque
// polygon of a cell complex (no cells, no portals, no masks involved).
#pragma once

#include <cmath>
#include <limits>
#include <vector>

#include "cells/cell_complex.h"
#include "visibility/camera.h"
#include "visibility/visible_set.h"

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

struct OracleResult {
  int missing = 0;  ///< (ray, cell) pairs: a ray crosses the cell before its first hit, the cell is not visible
  int extra = 0;    ///< avenues over a pixel in size whose cell the ray through their mask never enters
  int rays = 0;
  bool ok() const { return missing == 0 && extra == 0; }
};

/// Checks a visible set against rays: one ray per pixel centre (every `step` pixels) —
/// each cell it crosses before its first opaque hit must be visible — and, for each avenue
/// whose mask covers more than a pixel, the ray through the mask's centroid must enter the
/// avenue's cell (the eye's own cell is exempt: the eye may stand on its face).
inline OracleResult check_visible_set(const CellComplex& c, const Camera& cam, const VisibleSet& vs, int step = 1) {
  OracleResult r;
  std::vector<uint8_t> visible(c.cells.size(), 0);
  for (CellId id : vs.cells) visible[size_t(id)] = 1;
  for (int j = step / 2; j < cam.height; j += step)
    for (int i = step / 2; i < cam.width; i += step) {
      const Vec3 dir = cam.ray_through_raster({i + 0.5, j + 0.5});
      const double t = first_hit(c, cam.eye, dir);
      ++r.rays;
      for (CellId id = 0; id < CellId(c.cells.size()); ++id)
        if (!visible[size_t(id)] && length_inside(c.cells[size_t(id)], cam.eye, dir, 0, t) > 1e-6) ++r.missing;
    }
  const double px2 = (cam.width / (2 * cam.half_width())) * (cam.height / (2 * cam.half_height()));
  for (const Avenue& a : vs.avenues) {
    double area = 0, cx = 0, cy = 0;
    for (size_t m = 0; m < a.mask.size(); ++m) {
      const Vec2 p = a.mask[m], q = a.mask[(m + 1) % a.mask.size()];
      const double w = cross(p, q);
      area += w / 2, cx += (p.x + q.x) * w / 6, cy += (p.y + q.y) * w / 6;
    }
    if (area * px2 <= 1 || a.depth == 0) continue;
    const Vec3 dir = (cx / area) * cam.right + (cy / area) * cam.up + cam.forward;
    if (!(length_inside(c.cells[size_t(a.cell)], cam.eye, dir, 0, first_hit(c, cam.eye, dir)) > 0)) ++r.extra;
  }
  return r;
}

}  // namespace avenues::testing

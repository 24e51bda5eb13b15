// An independent reference for visibility: brute-force ray casting against every opaque
// polygon of a cell complex (no cells, no portals, no masks involved).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "cells/cell_complex.h"
#include "visibility/camera.h"
#include "visibility/visible_set.h"

namespace avenues::testing {

/// Distance along `dir` from `o` to the first opaque polygon hit (dir need not be unit).
/// An eye within kOnBoundary of a surface stands on it, as the search takes it (in the
/// cells on both sides): that surface does not stop its rays.
inline double first_hit(const CellComplex& c, Vec3 o, Vec3 dir) {
  double best = std::numeric_limits<double>::infinity();
  for (const Cell& cell : c.cells)
    for (const Face& f : cell.faces) {
      double den = dot(f.plane.n, dir);
      if (den == 0) continue;
      if (std::fabs(f.plane.eval(o)) <= kOnBoundary * length(f.plane.n)) continue;
      double t = -f.plane.eval(o) / den;
      if (!(t > 0) || t >= best) continue;
      Vec3 p = o + t * dir;
      for (const OpaquePoly& op : f.opaque) {
        // Inside the convex polygon (counter-clockwise about the inward normal -n), and
        // within its bounds: the edge test alone holds a polygon of no area (a needle a few
        // picometres long, a portal piece that rounded to nothing) to be the whole line
        // through it.
        bool in = true;
        const size_t m = op.poly.size();
        Box3 bounds;
        for (const Vec3& q : op.poly) bounds.add(q);
        const double tol = 1e-9 * std::max({1.0, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
        in = bounds.contains(p, tol);
        for (size_t k = 0; k < m && in; ++k) {
          Vec3 a = op.poly[k], b = op.poly[(k + 1) % m];
          // Two corners a rounding apart bound nothing: the edge between them has no
          // direction of its own, and may turn the rounded polygon inward.
          if (length(b - a) <= 1e-12 * std::max({1.0, std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)})) continue;
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
    if (signed_area(a.mask) * px2 <= 1 || a.depth == 0) continue;
    const Vec2 mid = centroid(a.mask);  // core/geometry.h
    const Vec3 dir = mid.x * cam.right + mid.y * cam.up + cam.forward;
    if (!(length_inside(c.cells[size_t(a.cell)], cam.eye, dir, 0, first_hit(c, cam.eye, dir)) > 0)) ++r.extra;
  }
  return r;
}

/// A picture's frame on the plane its parallel rays start from: pixel (i, j) of nx × ny
/// (rows from the bottom here) starts its ray at origin + ((i + ½)/nx)·right + ((j + ½)/ny)·up.
struct ParallelFrame {
  Vec3 origin, right, up, direction;
  int nx = 0, ny = 0;
};

/// The frame of a parallel camera's picture on the cut plane (the rays through the window's
/// corners, followed along forward to the cut).
inline ParallelFrame frame_on_cut(const Camera& cam, const Plane& cut) {
  const double hw = cam.half_width(), hh = cam.half_height(), nf = dot(cut.n, cam.forward);
  auto onto = [&](Vec3 p) { return p + (-cut.eval(p) / nf) * cam.forward; };
  ParallelFrame f;
  f.origin = onto(cam.eye + (cam.shift_x - hw) * cam.right + (cam.shift_y - hh) * cam.up);
  f.right = onto(cam.eye + (cam.shift_x + hw) * cam.right + (cam.shift_y - hh) * cam.up) - f.origin;
  f.up = onto(cam.eye + (cam.shift_x - hw) * cam.right + (cam.shift_y + hh) * cam.up) - f.origin;
  f.direction = cam.forward;
  f.nx = cam.width, f.ny = cam.height;
  return f;
}

/// Parallel rays (one per pixel centre, every `step` pixels) from the frame: each cell a ray
/// crosses before its first opaque hit must be in vs.cells (counted in `missing`).
inline OracleResult check_parallel_rays(const CellComplex& c, const ParallelFrame& f, const std::vector<CellId>& cells,
                                        int step = 1) {
  OracleResult r;
  std::vector<uint8_t> visible(c.cells.size(), 0);
  for (CellId id : cells) visible[size_t(id)] = 1;
  for (int j = step / 2; j < f.ny; j += step)
    for (int i = step / 2; i < f.nx; i += step) {
      const Vec3 o = f.origin + ((i + 0.5) / f.nx) * f.right + ((j + 0.5) / f.ny) * f.up;
      const double t = first_hit(c, o, f.direction);
      ++r.rays;
      for (CellId id = 0; id < CellId(c.cells.size()); ++id)
        if (!visible[size_t(id)] && length_inside(c.cells[size_t(id)], o, f.direction, 0, t) > 1e-6) ++r.missing;
    }
  return r;
}

/// check_parallel_rays for a parallel search from `cut`, and the converse: each avenue
/// beyond the cut whose mask covers more than a pixel has its cell entered by the ray
/// through the mask's centroid (counted in `extra`).
inline OracleResult check_parallel_visible_set(const CellComplex& c, const Camera& cam, const Plane& cut,
                                               const VisibleSet& vs, int step = 1) {
  OracleResult r = check_parallel_rays(c, frame_on_cut(cam, cut), vs.cells, step);
  const double px2 = (cam.width / (2 * cam.half_width())) * (cam.height / (2 * cam.half_height()));
  const double nf = dot(cut.n, cam.forward);
  for (const Avenue& a : vs.avenues) {
    if (signed_area(a.mask) * px2 <= 1 || a.depth == 0) continue;
    const Vec2 mid = centroid(a.mask);  // core/geometry.h
    Vec3 o = cam.eye + mid.x * cam.right + mid.y * cam.up;
    o = o + (-cut.eval(o) / nf) * cam.forward;
    if (!(length_inside(c.cells[size_t(a.cell)], o, cam.forward, 0, first_hit(c, o, cam.forward)) > 0)) ++r.extra;
  }
  return r;
}

}  // namespace avenues::testing

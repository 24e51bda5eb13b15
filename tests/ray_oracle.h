// An independent reference for visibility: brute-force ray casting against every opaque
// polygon of a cell complex (no cells, no portals, no masks involved).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "cells/cell_complex.h"
#include "visibility/camera.h"
#include "visibility/visible_set.h"

namespace avenues::testing {

/// The distance along `dir` from `o` to face f's opaque polygons where it is less than
/// `best`, else `best`. An eye within kOnBoundary of the face's plane stands on it, as the
/// search takes it (in the cells on both sides): that face does not stop its rays.
inline double face_hit(const Face& f, Vec3 o, Vec3 dir, double best) {
  const double den = dot(f.plane.n, dir);
  if (den == 0) return best;
  if (std::fabs(f.plane.eval(o)) <= kOnBoundary * length(f.plane.n)) return best;
  const double t = -f.plane.eval(o) / den;
  if (!(t > 0) || t >= best) return best;
  const Vec3 p = o + t * dir;
  for (const OpaquePoly& op : f.opaque) {
    // Inside the convex polygon (counter-clockwise about the inward normal -n), and
    // within its bounds: the edge test alone holds a polygon of no area (a needle a few
    // picometres long, a portal piece that rounded to nothing) to be the whole line
    // through it.
    const size_t m = op.poly.size();
    Box3 bounds;
    for (const Vec3& q : op.poly) bounds.add(q);
    const double tol = 1e-9 * std::max({1.0, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
    bool in = bounds.contains(p, tol);
    for (size_t k = 0; k < m && in; ++k) {
      Vec3 a = op.poly[k], b = op.poly[(k + 1) % m];
      // Two corners a rounding apart bound nothing: the edge between them has no
      // direction of its own, and may turn the rounded polygon inward.
      if (length(b - a) <= 1e-12 * std::max({1.0, std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)})) continue;
      in = dot(cross(b - a, p - a), f.plane.n) <= 1e-12;
    }
    if (in) return t;
  }
  return best;
}

/// Distance along `dir` from `o` to the first opaque polygon hit (dir need not be unit):
/// every face of every cell tried (OracleIndex::first_hit finds the same by boxes).
inline double first_hit(const CellComplex& c, Vec3 o, Vec3 dir) {
  double best = std::numeric_limits<double>::infinity();
  for (const Cell& cell : c.cells)
    for (const Face& f : cell.faces) best = face_hit(f, o, dir, best);
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

/// A hierarchy of boxes (median splits along the longest side) over items given by their
/// boxes: a ray's segment visits only the items whose boxes it passes through. The boxes
/// are grown by a millionth of their size from the origin, a billion times what the exact
/// tests round by, so an item it skips is one the exact test would reject.
class BoxTree {
 public:
  explicit BoxTree(std::vector<Box3> boxes) : boxes_(std::move(boxes)) {
    for (Box3& b : boxes_) {
      const double reach = b.magnitude();
      b = b.grown(1e-6 * reach);
    }
    order_.resize(boxes_.size());
    for (size_t k = 0; k < order_.size(); ++k) order_[k] = uint32_t(k);
    if (order_.empty()) return;
    nodes_.emplace_back();
    build(0, 0, uint32_t(order_.size()));
  }

  /// Calls visit(item) for each item whose box the segment o + t·dir, t in [0, t1] meets,
  /// nearer boxes first; visit returns the segment's new end (t1 or less).
  template <class Visit>
  void visit(Vec3 o, Vec3 dir, double t1, Visit&& visit) const {
    descend([&](const Box3& box, double& at) { return enters(box, o, dir, t1, at); },
            [&](uint32_t item) {
              t1 = visit(item);
              return false;
            });
  }

  /// Calls visit(item) for each item whose box holds p within tol, until visit returns true.
  template <class Visit>
  void visit_holding(Vec3 p, double tol, Visit&& visit) const {
    descend(
        [&](const Box3& box, double& at) {
          at = 0;
          return box.contains(p, tol);
        },
        visit);
  }

 private:
  struct Node {
    Box3 box;
    uint32_t first = 0;  ///< a leaf's first item in order_, or an inner node's first child
    uint32_t count = 0;  ///< items of a leaf; 0: inner
  };

  static double along(Vec3 v, int axis) { return axis == 0 ? v.x : axis == 1 ? v.y : v.z; }

  /// Calls visit(item) for each item whose box meets(box, at) holds, until visit returns
  /// true; of two children, the one meets() puts at the lesser `at` first.
  template <class Meets, class Visit>
  void descend(Meets&& meets, Visit&& visit) const {
    if (nodes_.empty()) return;
    uint32_t stack[128];  // a median split halves the items: 128 levels are never reached
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& n = nodes_[stack[--top]];
      double at = 0;
      if (!meets(n.box, at)) continue;
      if (n.count > 0) {
        for (uint32_t k = n.first; k < n.first + n.count; ++k)
          if (meets(boxes_[order_[k]], at) && visit(order_[k])) return;
        continue;
      }
      double a = 0, b = 0;
      const bool ea = meets(nodes_[n.first].box, a), eb = meets(nodes_[n.first + 1].box, b);
      if (ea && eb) {
        stack[top++] = a <= b ? n.first + 1 : n.first;  // the nearer on top
        stack[top++] = a <= b ? n.first : n.first + 1;
      } else if (ea) {
        stack[top++] = n.first;
      } else if (eb) {
        stack[top++] = n.first + 1;
      }
    }
  }

  /// Whether the segment o + t·dir, t in [0, t1], meets box b; `at` is where it enters.
  static bool enters(const Box3& b, Vec3 o, Vec3 dir, double t1, double& at) {
    double t0 = 0;
    for (int axis = 0; axis < 3; ++axis) {
      const double oa = along(o, axis), da = along(dir, axis), lo = along(b.lo, axis), hi = along(b.hi, axis);
      if (da == 0) {
        if (oa < lo || oa > hi) return false;
        continue;
      }
      double ta = (lo - oa) / da, tb = (hi - oa) / da;
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta), t1 = std::min(t1, tb);
      if (t0 > t1) return false;
    }
    at = t0;
    return true;
  }

  /// Makes nodes_[slot] the node over order_[first, last), and its children below it.
  void build(size_t slot, uint32_t first, uint32_t last) {
    Box3 box, mids;
    for (uint32_t k = first; k < last; ++k) {
      const Box3& b = boxes_[order_[k]];
      box.add(b.lo), box.add(b.hi);
      mids.add(0.5 * (b.lo + b.hi));
    }
    nodes_[slot].box = box;
    if (last - first <= 4) {
      nodes_[slot].first = first, nodes_[slot].count = last - first;
      return;
    }
    const Vec3 span = mids.hi - mids.lo;
    const int axis = span.x >= span.y && span.x >= span.z ? 0 : span.y >= span.z ? 1 : 2;
    const uint32_t mid = first + (last - first) / 2;
    std::nth_element(order_.begin() + first, order_.begin() + mid, order_.begin() + last, [&](uint32_t a, uint32_t b) {
      return along(boxes_[a].lo + boxes_[a].hi, axis) < along(boxes_[b].lo + boxes_[b].hi, axis);
    });
    // The two children side by side, so that an inner node names only the first.
    const size_t children = nodes_.size();
    nodes_.emplace_back(), nodes_.emplace_back();
    nodes_[slot].first = uint32_t(children);
    build(children, first, mid);
    build(children + 1, mid, last);
  }

  std::vector<Box3> boxes_;
  std::vector<uint32_t> order_;
  std::vector<Node> nodes_;
};

/// The ray oracle with its faces and cells in box trees, built once for many rays: first_hit
/// and the cells a ray crosses come out as the brute-force loops find them (tested in
/// ray_oracle_test.cpp), in a time that grows with the log of the complex's size.
class OracleIndex {
 public:
  explicit OracleIndex(const CellComplex& c) : c_(c), faces_(), face_tree_(face_boxes(c, faces_)), cell_tree_(cell_boxes(c)) {}

  /// first_hit(c, o, dir).
  double first_hit(Vec3 o, Vec3 dir) const {
    double best = std::numeric_limits<double>::infinity();
    face_tree_.visit(o, dir, best, [&](uint32_t k) {
      best = face_hit(c_.cells[faces_[k].first].faces[faces_[k].second], o, dir, best);
      return best;
    });
    return best;
  }

  /// Calls f(cell) for each cell the segment o + t·dir, t in [0, t1], runs inside for more
  /// than a micrometre (length_inside): the cells a ray crosses before its first hit. Only
  /// the cells whose boxes the segment meets are tried.
  template <class F>
  void cells_crossed(Vec3 o, Vec3 dir, double t1, F&& f) const {
    cell_tree_.visit(o, dir, t1, [&](uint32_t k) {
      if (length_inside(c_.cells[k], o, dir, 0, t1) > 1e-6) f(CellId(k));
      return t1;
    });
  }

 private:
  static std::vector<Box3> face_boxes(const CellComplex& c, std::vector<std::pair<uint32_t, uint32_t>>& faces) {
    std::vector<Box3> boxes;
    for (size_t i = 0; i < c.cells.size(); ++i)
      for (size_t j = 0; j < c.cells[i].faces.size(); ++j) {
        const Face& f = c.cells[i].faces[j];
        if (f.opaque.empty()) continue;
        Box3 b;
        for (const OpaquePoly& op : f.opaque)
          for (Vec3 q : op.poly) b.add(q);
        faces.push_back({uint32_t(i), uint32_t(j)});
        boxes.push_back(b);
      }
    return boxes;
  }
  static std::vector<Box3> cell_boxes(const CellComplex& c) {
    std::vector<Box3> boxes(c.cells.size());
    for (size_t i = 0; i < c.cells.size(); ++i)
      for (const Face& f : c.cells[i].faces)
        for (Vec3 q : f.poly) boxes[i].add(q);
    return boxes;
  }

  const CellComplex& c_;
  std::vector<std::pair<uint32_t, uint32_t>> faces_;  ///< (cell, face) of each face with opaque polygons
  BoxTree face_tree_, cell_tree_;
};

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
  const OracleIndex index(c);
  std::vector<uint8_t> visible(c.cells.size(), 0);
  for (CellId id : vs.cells) visible[size_t(id)] = 1;
  // The eye's own cell holds it. An eye within kOnBoundary of its faces stands on them, and
  // a ray leaving it between those planes runs inside for less than kOnBoundary / sin of its
  // grazing angle (13 µm at 1.25e-4 rad: random plan 5743), with no avenue of its own.
  if (vs.eye_cell != kNoCell)
    for (const Face& f : c.cells[size_t(vs.eye_cell)].faces)
      if (std::fabs(f.plane.eval(cam.eye)) <= kOnBoundary * length(f.plane.n)) visible[size_t(vs.eye_cell)] = 1;
  for (int j = step / 2; j < cam.height; j += step)
    for (int i = step / 2; i < cam.width; i += step) {
      const Vec3 dir = cam.ray_through_raster({i + 0.5, j + 0.5});
      const double t = index.first_hit(cam.eye, dir);
      ++r.rays;
      index.cells_crossed(cam.eye, dir, t, [&](CellId id) { r.missing += !visible[size_t(id)]; });
    }
  const double px2 = (cam.width / (2 * cam.half_width())) * (cam.height / (2 * cam.half_height()));
  for (const Avenue& a : vs.avenues) {
    if (signed_area(a.mask) * px2 <= 1 || a.depth == 0) continue;
    const Vec2 mid = centroid(a.mask);  // core/geometry.h
    const Vec3 dir = mid.x * cam.right + mid.y * cam.up + cam.forward;
    if (!(length_inside(c.cells[size_t(a.cell)], cam.eye, dir, 0, index.first_hit(cam.eye, dir)) > 0)) ++r.extra;
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
inline OracleResult check_parallel_rays(const CellComplex& c, const OracleIndex& index, const ParallelFrame& f,
                                        const std::vector<CellId>& cells, int step = 1) {
  OracleResult r;
  std::vector<uint8_t> visible(c.cells.size(), 0);
  for (CellId id : cells) visible[size_t(id)] = 1;
  for (int j = step / 2; j < f.ny; j += step)
    for (int i = step / 2; i < f.nx; i += step) {
      const Vec3 o = f.origin + ((i + 0.5) / f.nx) * f.right + ((j + 0.5) / f.ny) * f.up;
      const double t = index.first_hit(o, f.direction);
      ++r.rays;
      index.cells_crossed(o, f.direction, t, [&](CellId id) { r.missing += !visible[size_t(id)]; });
    }
  return r;
}
inline OracleResult check_parallel_rays(const CellComplex& c, const ParallelFrame& f, const std::vector<CellId>& cells,
                                        int step = 1) {
  return check_parallel_rays(c, OracleIndex(c), f, cells, step);
}

/// check_parallel_rays for a parallel search from `cut`, and the converse: each avenue
/// beyond the cut whose mask covers more than a pixel has its cell entered by the ray
/// through the mask's centroid (counted in `extra`).
inline OracleResult check_parallel_visible_set(const CellComplex& c, const Camera& cam, const Plane& cut,
                                               const VisibleSet& vs, int step = 1) {
  const OracleIndex index(c);
  OracleResult r = check_parallel_rays(c, index, frame_on_cut(cam, cut), vs.cells, step);
  const double px2 = (cam.width / (2 * cam.half_width())) * (cam.height / (2 * cam.half_height()));
  const double nf = dot(cut.n, cam.forward);
  for (const Avenue& a : vs.avenues) {
    if (signed_area(a.mask) * px2 <= 1 || a.depth == 0) continue;
    const Vec2 mid = centroid(a.mask);  // core/geometry.h
    Vec3 o = cam.eye + mid.x * cam.right + mid.y * cam.up;
    o = o + (-cut.eval(o) / nf) * cam.forward;
    if (!(length_inside(c.cells[size_t(a.cell)], o, cam.forward, 0, index.first_hit(o, cam.forward)) > 0)) ++r.extra;
  }
  return r;
}

}  // namespace avenues::testing

// Avenues — a stereo pair of eyes.
//
// Jones 1971: "the program can be made to create two views from slightly displaced
// viewpoints and to present these simultaneously ... as a stereoscopic pair". The two eyes
// stand an interocular distance apart along the camera's right vector, both looking along
// the same forward vector — never toed in, which would tilt the two picture planes against
// each other and give vertical parallax. Instead each eye's window is shifted on its picture
// plane (Camera::shift_x, an off-axis frustum) so that the two frusta converge at a stated
// distance: a point on the centre line at that distance appears at the same raster position
// in both pictures (zero parallax), nearer points stand out of the page, farther ones behind.
// The left eye at e − (i/2)·right sees the convergence point e + D·forward at X = i/2, Z = D,
// so its window is centred at x = i/(2D); the right eye's at −i/(2D).
//
// Each eye is located in its own cell and sees through its own avenues. The rig reports what
// makes a pair unusable, so the command line can refuse it with a clear message: an eye
// inside a solid (a thick wall, a slab) or outside the far box, or an opaque face between the
// two eyes (a pair straddling a wall of no thickness, where each eye would see another room).
// Eyes in different cells joined by a portal or a transparent face are fine.
//
// Header-only: small, and used by both the command line and the renderer.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "cells/cell_complex.h"
#include "visibility/camera.h"

namespace avenues {

/// How a stereo pair is put on paper.
enum class StereoLayout : uint8_t {
  Parallel,  ///< one drawing, left eye's view on the left (for parallel free viewing, stereoscopes)
  Cross,     ///< one drawing, left eye's view on the right (for cross-eyed free viewing)
  Pair,      ///< two files, NAME-left.EXT and NAME-right.EXT
};

inline const char* to_string(StereoLayout l) {
  return l == StereoLayout::Parallel ? "parallel" : l == StereoLayout::Cross ? "cross" : "pair";
}

/// Parses "parallel", "cross" or "pair"; false if it is none of them.
inline bool parse_stereo_layout(const std::string& s, StereoLayout& out) {
  for (StereoLayout l : {StereoLayout::Parallel, StereoLayout::Cross, StereoLayout::Pair})
    if (s == to_string(l)) {
      out = l;
      return true;
    }
  return false;
}

struct StereoOptions {
  double interocular = 0.065;  ///< [m] > 0: distance between the eyes
  double converge = 2.0;       ///< [m] > 0: distance ahead where the two views coincide
};

struct StereoRig {
  enum class Problem : uint8_t {
    None,
    EyeInSolid,       ///< `eye` is inside `inside` (a wall, a slab)
    EyeOutsideBox,    ///< `eye` is outside the far box
    WallBetweenEyes,  ///< an opaque face stands between the eyes; `inside` says between which rooms
  };
  Camera left, right;
  Location left_at, right_at;  ///< where each eye is: its cell, or the solid it is inside
  Problem problem = Problem::None;
  std::string eye;     ///< "left" or "right": the eye at fault (EyeInSolid, EyeOutsideBox)
  std::string inside;  ///< what that eye is inside, or where the wall between the eyes stands

  /// The eyes are in different cells (which is fine unless problem says otherwise).
  bool eyes_apart() const { return left_at.cell != right_at.cell; }
  /// One sentence for the command line; empty when there is no problem.
  std::string message() const {
    switch (problem) {
      case Problem::None: return "";
      case Problem::EyeInSolid: return "the " + eye + " eye of the stereo pair is inside " + inside;
      case Problem::EyeOutsideBox: return "the " + eye + " eye of the stereo pair is outside the far box";
      case Problem::WallBetweenEyes:
        return "the eyes of the stereo pair stand on either side of a wall (" + inside +
               "); move the eye or shorten --interocular";
    }
    return "";
  }
};

namespace detail {

/// Closed containment of q, lying in the plane of the convex polygon with normal n.
inline bool in_convex_3d(const std::vector<Vec3>& poly, Vec3 n, Vec3 q, double tol) {
  bool pos = false, neg = false;
  for (size_t k = 0; k < poly.size(); ++k) {
    const Vec3 a = poly[k], b = poly[(k + 1) % poly.size()];
    const double s = dot(cross(b - a, q - a), n) / length(b - a);
    pos |= s > tol;
    neg |= s < -tol;
  }
  return !(pos && neg);
}

/// Walks the segment a→b through the cells from `cell` (which holds a), crossing portals
/// (transparent faces, doors, ...): true if an opaque face stops it before b.
inline bool opaque_between(const CellComplex& c, CellId cell, Vec3 a, Vec3 b) {
  constexpr double kTol = 1e-9;  // [m]
  const Vec3 d = b - a;
  double t = 0;
  for (size_t steps = 0; steps < c.cells.size(); ++steps) {
    const Cell& here = c.cells[size_t(cell)];
    // Where the segment leaves this convex cell: the first face it crosses outwards.
    double t_exit = 1;
    for (const Face& f : here.faces) {
      const double rate = dot(f.plane.n, d);
      if (rate > 0) t_exit = std::min(t_exit, -f.plane.eval(a) / rate);
    }
    if (t_exit >= 1) return false;
    t = std::max(t, t_exit);
    const Vec3 q = a + t * d;
    CellId next = kNoCell;
    for (const Face& f : here.faces) {
      if (!(dot(f.plane.n, d) > 0) || std::fabs(f.plane.eval(q)) > kTol) continue;
      for (PortalId pi : f.portals) {
        const Portal& p = c.portals[size_t(pi)];
        if (in_convex_3d(p.poly, p.plane.n, q, kTol)) next = p.other(cell);
      }
    }
    if (next == kNoCell) return true;
    cell = next;
  }
  return false;
}

inline std::string place_name(const CellComplex& c, CellId id) {
  const Cell& cell = c.cells[size_t(id)];
  return cell.room >= 0 ? "room '" + c.rooms[size_t(cell.room)].name + "'" : std::string(to_string(cell.kind));
}

}  // namespace detail

/// The two eyes of `centre` (the cyclopean eye between them), located in `complex`. Throws
/// std::runtime_error if the interocular or convergence distance is not a positive length.
inline StereoRig stereo_rig(const CellComplex& complex, const Camera& centre, const StereoOptions& options) {
  if (!(options.interocular > 0 && std::isfinite(options.interocular)))
    throw std::runtime_error("the interocular distance must be a positive length in metres");
  if (!(options.converge > 0 && std::isfinite(options.converge)))
    throw std::runtime_error("the convergence distance must be a positive length in metres");
  StereoRig rig;
  const double half = options.interocular / 2, shift = options.interocular / (2 * options.converge);
  rig.left = centre;
  rig.left.eye = centre.eye - half * centre.right;
  rig.left.shift_x = centre.shift_x + shift;
  rig.right = centre;
  rig.right.eye = centre.eye + half * centre.right;
  rig.right.shift_x = centre.shift_x - shift;
  const CellId hint = complex.locate(centre.eye).cell;
  rig.left_at = complex.locate(rig.left.eye, hint);
  rig.right_at = complex.locate(rig.right.eye, hint);
  for (const auto& [name, at] : {std::pair<const char*, const Location&>{"left", rig.left_at}, {"right", rig.right_at}}) {
    if (at.what == Location::What::Cell || rig.problem != StereoRig::Problem::None) continue;
    rig.problem = at.what == Location::What::Solid ? StereoRig::Problem::EyeInSolid : StereoRig::Problem::EyeOutsideBox;
    rig.eye = name;
    rig.inside = at.solid;
  }
  if (rig.problem == StereoRig::Problem::None && rig.eyes_apart()) {
    if (detail::opaque_between(complex, rig.left_at.cell, rig.left.eye, rig.right.eye)) {
      rig.problem = StereoRig::Problem::WallBetweenEyes;
      rig.inside = "the left eye in " + detail::place_name(complex, rig.left_at.cell) + ", the right eye in " +
                   detail::place_name(complex, rig.right_at.cell);
    }
  }
  return rig;
}

}  // namespace avenues

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
#include "visibility/walker.h"

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
    if (cast_segment(complex, rig.left_at.cell, rig.left.eye, rig.right.eye).blocked) {
      rig.problem = StereoRig::Problem::WallBetweenEyes;
      rig.inside = "the left eye in " + detail::place_name(complex, rig.left_at.cell) + ", the right eye in " +
                   detail::place_name(complex, rig.right_at.cell);
    }
  }
  return rig;
}

}  // namespace avenues

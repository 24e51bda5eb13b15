// Avenues — the sample raster of a half-tone picture and its map to the picture plane.
//
// A picture of W × H pixels taken with s × s samples per pixel is scanned as a raster of
// (s·W) × (s·H) samples. Sample (i, j) covers [i, i+1) × [j, j+1) in raster units, rows
// counted from the top, and is taken at its centre (i + ½, j + ½) — the camera's
// convention (visibility/camera.h), one level finer. The picture plane is Z = 1 in camera
// space, x to the right and y up, so the map is a scale and a flip of y.
#pragma once

#include "core/geometry.h"
#include "visibility/camera.h"

namespace avenues {

/// An affine function on the raster, f(x, y) = a·x + b·y + c with x, y in [samples]: the
/// inverse depth 1/Z of a plane seen in perspective (Wylie's 1/w, Bouknight's perspective
/// plane equation), or a quantity times 1/Z (perspective-correct interpolation).
struct RasterPlane {
  double a = 0, b = 0, c = 0;
  double at(double x, double y) const { return a * x + b * y + c; }
};

struct RasterMap {
  int width = 0, height = 0;  ///< [samples] > 0: the camera's size times the samples per side
  double x0 = 0, y0 = 0;      ///< picture-plane point at the raster's top-left corner (0, 0)
  double step = 0;            ///< picture-plane units per sample, > 0 (samples are square)

  /// The raster of `camera` with `per_side` samples along each side of a pixel (1, 2 or 4).
  static RasterMap of(const Camera& camera, int per_side) {
    RasterMap m;
    m.width = camera.width * per_side;
    m.height = camera.height * per_side;
    m.x0 = camera.shift_x - camera.half_width();
    m.y0 = camera.shift_y + camera.half_height();
    m.step = 2 * camera.half_width() / m.width;
    return m;
  }
  /// Picture-plane point (x, y) → raster position [samples].
  Vec2 raster_from_image(Vec2 p) const { return {(p.x - x0) / step, (y0 - p.y) / step}; }
};

}  // namespace avenues

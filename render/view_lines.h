// Avenues — the hidden-line drawing of a view, from Jones's avenues of sight.
//
// Jones 1971: "All the lines on the inner faces and edges of the cell which are not part of
// openings are dealt with by finding their projections on the picture plane, and then
// clipping them according to the mask. Since the cells are convex, there can be no
// obscuration of lines apart from that due to masking." For each avenue (cell, mask) of the
// visible set, each real line of the cell (its part t0..t1 of a RealLine) is
//   1. clipped to the near plane (camera.near) in camera space,
//   2. clipped exactly to the convex mask, in picture-plane terms but parametrically along
//      the 3D line (interval_clip.h), so that every endpoint is a point of the line,
//   3. hidden where furniture stands in front of it (Crow's method, furniture.h),
//   4. projected to raster coordinates (camera.raster_from_image).
// Each stroke is drawn once: the pieces of one RealLine id from every avenue and every cell
// are a union of parameter intervals, merged where they touch (a line shared by two cells is
// one id; a line seen through two avenues gives disjoint pieces); then strokes that lie on one
// line of the picture are merged or trimmed so that none overlaps another (stroke_merge.h).
// Weights follow line_weight.h (architecture) and furniture.h (objects).
// A parallel projection (camera.h) draws the same way, its strokes clipped to the cut plane
// instead of the near plane, its weights from the direction of view; its furniture is what
// lies beyond the cut, facing the viewer along the direction of view.
// Edges of artificial transparent faces are never drawn: they are not real lines, and the
// cell complex lists only real lines.
#pragma once

#include <optional>

#include "cells/cell_complex.h"
#include "render/drawing.h"
#include "render/furniture.h"
#include "render/line_weight.h"
#include "render/lighting.h"
#include "render/shadows.h"
#include "visibility/camera.h"
#include "visibility/visible_set.h"

namespace avenues {

struct LineOptions {
  double crease_deg = 30;  ///< [deg] in [0, 180): furniture edges whose polygons differ by more are creases
  /// Draw the plan's objects and let them hide what is behind them (in a parallel
  /// projection, what of them lies beyond `cut`).
  bool furniture = true;
  /// Outline the shadows the plan's point lights cast on the faces of cells (Layer::Shadows;
  /// shadow_outline.h). Needs a LineScene prepared with this option.
  bool shadows = false;
  /// Parallel projection only: draw what lies beyond this plane (the cut the visible set was
  /// searched from, find_visible_from_cut); none: beyond the picture plane. Shadow
  /// outlines are drawn in perspective only.
  std::optional<Plane> cut;
  /// Merge collinear strokes (merge_collinear) before returning. A caller adding strokes of
  /// its own turns this off and merges once, after.
  bool merge = true;
  /// Up to this many threads clip the avenues' lines and merge the strokes (0: as many as
  /// TBB offers). The drawing is the same with any number.
  int threads = 1;
};

/// What drawing a complex needs besides its cells, prepared once and shared by every view
/// (stereo eyes, walkthrough frames): the faces meeting each real line, the placed furniture.
struct LineScene {
  LineFaces faces;
  Furniture furniture;
  Lighting lighting;     ///< the plan's point lights, when shadows are outlined
  SceneShadows shadows;  ///< what they light (empty unless prepared with LineOptions::shadows)
};

/// Prepares the scene of `complex`. Reads the objects' meshes: throws std::runtime_error
/// naming a mesh that cannot be read.
LineScene prepare_line_scene(const CellComplex& complex);
/// The same, and with options.shadows the shadows of the plan's point lights (shadows.h).
LineScene prepare_line_scene(const CellComplex& complex, const LineOptions& options);
/// The same with the objects placed already (place_objects), not read and placed again.
LineScene prepare_line_scene(const CellComplex& complex, const std::vector<PlacedObject>& objects,
                             const LineOptions& options = {});

/// The hidden-line drawing of what `camera` sees; `visible` is find_visible() from the same
/// camera, with exact masks: a conservative set (the hull search) would draw lines that are
/// hidden, so it throws std::invalid_argument (exact_masks() gives the search to use).
/// The drawing's page is the camera's image (width × height px).
Drawing draw_view(const CellComplex& complex, const LineScene& scene, const Camera& camera, const VisibleSet& visible,
                  const LineOptions& options = {});

}  // namespace avenues

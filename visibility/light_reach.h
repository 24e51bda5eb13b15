// Avenues — what a point light reaches: Jones's avenues of sight, seen from the light.
//
// Bouknight 1969, Chapter V, leaves shadows as "THE next problem": which parts of which
// polygons a light source sees. Appel's answer was to combine "the view as seen from the
// illumination point with the view as seen from the observer position". In a cell complex
// the view from the light is the traversal find_visible() already does: light reaches a
// cell only through portals (it never leaks through a wall), and the rays from the light
// that reach a cell through a chain of portals form one convex cone.
//
// A camera sees a pyramid; a light shines every way. find_visible() is run for six 90°
// cameras at the light, one per face of a cube around it (a hair wider than 90°, so that no
// direction falls between two of them), and the avenues are merged by their chains of
// portals: one chain, one LightPath, however many cube faces its cone spans. Its cone is
// then taken from the portals themselves, exactly as Jones narrows a mask: the window of a
// path is its last portal cut to the rays that passed every earlier one (in 3D, in double),
// so the cone does not depend on the six cameras at all.
//
// A point X of the path's cell is lit through the path when it lies inside every plane
// through the light and an edge of the window (cone_planes); the cell lies beyond the last
// portal, so those planes alone pick the right nappe of the cone. Every point of the light's
// own cell is lit (a convex cell hides nothing of itself).

#pragma once

#include <algorithm>
#include <vector>

#include "cells/cell_complex.h"
#include "visibility/camera.h"
#include "visibility/visible_set.h"

namespace avenues {

/// One avenue of light: a cell and the chain of portals the light passes to reach it.
struct LightPath {
  CellId cell = kNoCell;
  std::vector<PortalId> portals;  ///< from the light outwards; empty for the light's own cell
  /// The last portal cut to the rays from the light that pass every earlier portal: convex,
  /// in the portal's plane. Empty: every direction (the light's own cell, or a cell next to
  /// it through a portal in whose plane the light stands).
  std::vector<Vec3> window;
};

struct LightReach {
  Vec3 light;                     ///< [m]
  CellId cell = kNoCell;          ///< the light's own cell
  std::vector<LightPath> paths;   ///< paths[0] is the light's own cell; then by chain of portals
  std::vector<CellId> cells;      ///< distinct cells reached, ascending
  long portals_tested = 0;        ///< summed over the six traversals
  long lost_paths = 0;            ///< chains the traversal found whose window vanished in double (grazing rays)
  double micros = 0;              ///< [µs]
  bool reaches(CellId c) const { return std::binary_search(cells.begin(), cells.end(), c); }
};


/// The planes through `light` and each edge of a convex `window` (not containing the light),
/// as inward normals: a point X is inside the cone when dot(n, X − light) >= 0 for every n.
std::vector<Vec3> cone_planes(Vec3 light, const std::vector<Vec3>& window);

/// Everything the light at `light` (in cell `light_cell`) reaches through the portals.
LightReach find_lit(const CellComplex& complex, Vec3 light, CellId light_cell, Kernel kernel = Kernel::Double);

}  // namespace avenues

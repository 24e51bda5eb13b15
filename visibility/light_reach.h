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
//
// Header-only: visibility/CMakeLists.txt lists its sources by name; this keeps the
// traversal beside find_visible() without a build change.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
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

namespace detail {

/// Sutherland–Hodgman cut of a planar polygon to the half-space f(X) >= 0.
template <class F>
std::vector<Vec3> cut_to(const std::vector<Vec3>& in, F f) {
  std::vector<Vec3> out;
  const size_t n = in.size();
  for (size_t i = 0; i < n; ++i) {
    const Vec3 a = in[i], b = in[(i + 1) % n];
    const double fa = f(a), fb = f(b);
    if (fa >= 0) out.push_back(a);
    if ((fa >= 0) != (fb >= 0)) out.push_back(a + (fa / (fa - fb)) * (b - a));
  }
  return out;
}

inline double polygon_area(const std::vector<Vec3>& p) {
  Vec3 n{0, 0, 0};
  for (size_t i = 0; i + 2 < p.size(); ++i) n = n + cross(p[i + 1] - p[0], p[i + 2] - p[0]);
  return 0.5 * length(n);
}

}  // namespace detail

/// The planes through `light` and each edge of a convex `window` (not containing the light),
/// as inward normals: a point X is inside the cone when dot(n, X − light) >= 0 for every n.
inline std::vector<Vec3> cone_planes(Vec3 light, const std::vector<Vec3>& window) {
  std::vector<Vec3> planes;
  Vec3 c{0, 0, 0};
  for (Vec3 w : window) c = c + (1.0 / double(window.size())) * w;
  for (size_t i = 0; i < window.size(); ++i) {
    Vec3 n = cross(window[i] - light, window[(i + 1) % window.size()] - light);
    const double l = length(n);
    if (!(l > 0)) continue;
    n = (1 / l) * n;
    planes.push_back(dot(n, c - light) < 0 ? -1.0 * n : n);
  }
  return planes;
}

/// Everything the light at `light` (in cell `light_cell`) reaches through the portals.
inline LightReach find_lit(const CellComplex& complex, Vec3 light, CellId light_cell,
                           Kernel kernel = Kernel::Double) {
  const auto t0 = std::chrono::steady_clock::now();
  LightReach out;
  out.light = light;
  out.cell = light_cell;
  if (light_cell == kNoCell) return out;
  out.paths.push_back({light_cell, {}, {}});
  // The six faces of a cube around the light, each a square camera a hair wider than 90°.
  const Vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  std::map<std::vector<PortalId>, CellId> chains;
  for (const Vec3& axis : axes) {
    const Camera cam = Camera::look_at(light, light + axis, 90.001, 64, 64);
    const VisibleSet vs = find_visible(complex, cam, light_cell, kernel);
    out.portals_tested += vs.portals_tested;
    for (size_t a = 1; a < vs.avenues.size(); ++a) chains.emplace(vs.path(int(a)), vs.avenues[a].cell);
  }
  // Jones's narrowing in 3D: each portal of the chain cut to the cone of the window before.
  // A light standing in a portal's plane (between two convex pieces of one room) shines
  // through it in every direction: the window stays "all directions" until a portal that
  // does not contain the light.
  const double scale = 1 + length(light);
  for (const auto& [portals, cell] : chains) {
    std::vector<Vec3> window;  // empty: every direction
    bool lost = false;
    for (size_t i = 0; i < portals.size() && !lost; ++i) {
      const Portal& portal = complex.portals[size_t(portals[i])];
      if (window.empty()) {
        if (!(std::fabs(portal.plane.eval(light)) <= 1e-9 * scale)) window = portal.poly;
        continue;
      }
      std::vector<Vec3> next = portal.poly;
      for (const Vec3& n : cone_planes(light, window)) {
        next = detail::cut_to(next, [&](Vec3 x) { return dot(n, x - light); });
        if (next.size() < 3) break;
      }
      lost = next.size() < 3 || !(detail::polygon_area(next) > 1e-12 * scale * scale);
      window = std::move(next);
    }
    if (lost) {
      ++out.lost_paths;
      continue;
    }
    out.paths.push_back({cell, portals, std::move(window)});
  }
  for (const LightPath& p : out.paths) out.cells.push_back(p.cell);
  std::sort(out.cells.begin(), out.cells.end());
  out.cells.erase(std::unique(out.cells.begin(), out.cells.end()), out.cells.end());
  out.micros = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace avenues

// Avenues — where a point light reaches through the portals (see light_reach.h).
#include "visibility/light_reach.h"

#include <chrono>
#include <cmath>
#include <map>

namespace avenues {

/// The planes through `light` and each edge of a convex `window` (not containing the light),
/// as inward normals: a point X is inside the cone when dot(n, X − light) >= 0 for every n.
std::vector<Vec3> cone_planes(Vec3 light, const std::vector<Vec3>& window) {
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
LightReach find_lit(const CellComplex& complex, Vec3 light, CellId light_cell, Kernel kernel) {
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
        next = cut_polygon(next, [&](Vec3 x) { return dot(n, x - light); });
        if (next.size() < 3) break;
      }
      lost = next.size() < 3 || !(polygon_area(next) > 1e-12 * scale * scale);
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

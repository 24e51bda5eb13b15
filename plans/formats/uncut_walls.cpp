// Avenues — doors drawn over walls not cut for them (see uncut_walls.h).
#include "plans/formats/uncut_walls.h"

#include <algorithm>
#include <cmath>

#include "plans/formats/segment_grid.h"

namespace avenues {

OpenedWalls open_walls_under_swings(const std::vector<std::pair<Vec2, Vec2>>& walls, const std::vector<SwingArc>& swings) {
  OpenedWalls out;
  SegmentGrid grid(walls, 0.5);
  std::vector<std::vector<std::pair<Vec2, Vec2>>> cuts(walls.size());  // per line: the spans to open
  for (const SwingArc& sw : swings) {
    const Vec2 c = sw.hinge;
    for (const Vec2 e : {sw.end0, sw.end1}) {
      const Vec2 open = length(e - sw.end0) < 1e-9 ? sw.end1 : sw.end0;
      // The wall line through the hinge and e, running on past both by a centimetre.
      int through = -1;
      grid.near(c, 0.02, [&](size_t i) {
        const auto& [a, b] = walls[i];
        const double len = length(b - a);
        if (through >= 0 || !(len > 0) || distance_to_segment(c, a, b) > 0.02 || distance_to_segment(e, a, b) > 0.02) return;
        const double tc = dot(c - a, b - a) / len, te = dot(e - a, b - a) / len;
        if (std::min(tc, te) > 0.01 && std::max(tc, te) < len - 0.01) through = int(i);
      });
      if (through < 0) continue;
      const Vec2 l = walls[size_t(through)].second - walls[size_t(through)].first;
      const Vec2 u = (1 / length(l)) * l;
      const double t0 = std::min(dot(c, u), dot(e, u)), t1 = std::max(dot(c, u), dot(e, u));
      auto parallel_across = [&](size_t i) {  // within 2 degrees, and over the span
        const Vec2 a = walls[i].first, b = walls[i].second, d = b - a;
        const double len = length(d);
        return len > 0 && std::fabs(cross(d, u)) < 0.035 * len && std::max(dot(a, u), dot(b, u)) > t0 &&
               std::min(dot(a, u), dot(b, u)) < t1;
      };
      std::vector<size_t> near;
      grid.near(0.5 * (c + e), 0.5 * (t1 - t0) + 0.6, [&](size_t i) {
        if (parallel_across(i)) near.push_back(i);
      });
      // The wall's body lies toward its other face: the nearest parallel line across the span.
      Vec2 n{-u.y, u.x};
      double nearest = 0.6;
      for (size_t i : near) {
        const double depth = 0.5 * (dot(walls[i].first, n) + dot(walls[i].second, n)) - dot(c, n);
        if (std::fabs(depth) > 0.01 && std::fabs(depth) < std::fabs(nearest)) nearest = depth;
      }
      if (nearest < 0) n = -1.0 * n;
      if (std::fabs(nearest) >= 0.6 && dot(open - c, n) > 0) n = -1.0 * n;  // a wall of one line
      const double off = dot(c, n);
      for (size_t i : near) {
        const double depth_a = dot(walls[i].first, n) - off, depth_b = dot(walls[i].second, n) - off;
        if (std::min(depth_a, depth_b) >= -0.01 && std::max(depth_a, depth_b) <= 0.6) cuts[i].push_back({c, e});
      }
      ++out.doors;
      break;
    }
  }
  // Each line cut loses the union of its spans (its ends' projections on it).
  for (size_t i = 0; i < walls.size(); ++i) {
    const auto& [a, b] = walls[i];
    if (cuts[i].empty()) {
      out.lines.push_back(walls[i]);
      continue;
    }
    const Vec2 d = b - a;
    const double dd = dot(d, d);
    std::vector<std::pair<double, double>> spans;
    for (const auto& [p, q] : cuts[i]) spans.push_back(std::minmax(dot(p - a, d) / dd, dot(q - a, d) / dd));
    std::sort(spans.begin(), spans.end());
    double from = 0;
    for (const auto& [lo, hi] : spans) {
      if (lo > from) out.lines.push_back({a + from * d, a + std::min(lo, 1.0) * d});
      from = std::max(from, hi);
    }
    if (from < 1) out.lines.push_back({a + from * d, b});
  }
  return out;
}

}  // namespace avenues

// Avenues — door swings drawn where the walls are (see wall_swings.h).
#include "plans/formats/wall_swings.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "plans/formats/segment_grid.h"

namespace avenues {

WallSwings find_wall_swings(const std::vector<WallSwingLine>& lines, const std::vector<WallSwingArc>& arcs) {
  WallSwings out;
  out.no_wall.assign(lines.size(), false);
  std::vector<std::pair<Vec2, Vec2>> segs;
  for (const WallSwingLine& l : lines) segs.push_back({l.a, l.b});
  SegmentGrid grid(segs, 0.5);
  for (size_t k = 0; k < arcs.size(); ++k) {
    const WallSwingArc& a = arcs[k];
    if (!a.both_ways && !a.one_way) continue;
    const Vec2 c = a.c, p0 = a.p0, p1 = a.p1;
    const double r = a.r;
    const double half = 0.5 * a.sweep_deg * std::numbers::pi / 180, cs = std::cos(half), sn = std::sin(half);
    const Vec2 u = (1 / r) * (p0 - c), mid_dir{cs * u.x - sn * u.y, sn * u.x + cs * u.y};
    // The lines near the arc (any line a test below can count lies within its circle and
    // 15 cm, or touches an end).
    std::vector<size_t> near;
    grid.near(c, 1.05 * r + 0.2, [&](size_t i) { near.push_back(i); });
    std::sort(near.begin(), near.end());
    auto on_arc = [&](const WallSwingLine& s) {
      return s.curved && std::fabs(length(s.a - c) - r) < 0.005 && std::fabs(length(s.b - c) - r) < 0.005 &&
             dot(s.a - c, mid_dir) > cs * r - 0.01 && dot(s.b - c, mid_dir) > cs * r - 0.01;
    };
    auto leaf = [&](const WallSwingLine& s, Vec2 from, Vec2 to) {
      const Vec2 axis = to - from;
      const double axis_len = length(axis);
      auto off_axis = [&](Vec2 p) { return std::fabs(cross(axis, p - from)) / axis_len; };
      if (s.curved || !(axis_len > 0) || off_axis(s.a) > 0.07 || off_axis(s.b) > 0.07) return false;
      if (length(s.a - c) > 1.05 * r || length(s.b - c) > 1.05 * r) return false;
      return length(s.b - s.a) >= r / 2 || length(0.5 * (s.a + s.b) - c) > r / 2;
    };
    // Whether end e touches a line that is neither the arc nor a leaf along (from, to).
    auto touches = [&](Vec2 e, Vec2 from, Vec2 to) {
      return std::any_of(near.begin(), near.end(), [&](size_t i) {
        const WallSwingLine& s = lines[i];
        return !on_arc(s) && !leaf(s, from, to) && distance_to_segment(e, s.a, s.b) < 0.02;
      });
    };
    auto leaf_drawn = [&](Vec2 e) { return std::any_of(near.begin(), near.end(), [&](size_t i) { return leaf(lines[i], c, e); }); };
    Vec2 from, to, shut;  // the leaf's axis, and where it shuts
    if (a.both_ways) {
      from = p0, to = p1, shut = c + r * mid_dir;
      if (touches(p0, from, to) || touches(p1, from, to)) continue;
    } else {
      const bool free0 = !touches(p0, c, p0), free1 = !touches(p1, c, p1);
      if (!free0 && !free1) continue;
      if (free0 && free1 && leaf_drawn(p0) == leaf_drawn(p1)) continue;  // which way it shuts is not told
      const bool open0 = free0 && free1 ? leaf_drawn(p0) : free0;
      from = c, to = open0 ? p0 : p1, shut = open0 ? p1 : p0;
    }
    // At a wall's end: a line not along the leaf within 15 cm of the hinge.
    const Vec2 axis = to - from;
    const bool at_wall = std::any_of(near.begin(), near.end(), [&](size_t i) {
      const WallSwingLine& s = lines[i];
      if (on_arc(s) || leaf(s, from, to)) return false;
      const Vec2 d = s.b - s.a;
      const double len = length(d);
      return len > 0 && distance_to_segment(c, s.a, s.b) < 0.15 && std::fabs(dot(d, axis)) < 0.87 * len * length(axis);
    });
    if (!at_wall) continue;
    for (size_t i : near)
      if (on_arc(lines[i]) || leaf(lines[i], from, to)) out.no_wall[i] = true;
    out.swings.push_back({c, shut, k});
  }
  return out;
}

}  // namespace avenues

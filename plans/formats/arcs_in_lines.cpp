// Avenues — arcs drawn as chains of short straight lines (see arcs_in_lines.h).
#include "plans/formats/arcs_in_lines.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <optional>

namespace avenues {

std::vector<ArcOfLines> arcs_in_lines(const std::vector<std::pair<Vec2, Vec2>>& lines) {
  std::vector<ArcOfLines> out;
  double extent = 1;
  for (const auto& [a, b] : lines) extent = std::max({extent, std::fabs(a.x), std::fabs(a.y), std::fabs(b.x), std::fabs(b.y)});
  // Ends meet where they agree to a billionth of the drawing's extent.
  const double q = extent * 1e-9;
  auto key = [q](Vec2 p) { return std::pair<int64_t, int64_t>(std::llround(p.x / q), std::llround(p.y / q)); };
  std::map<std::pair<int64_t, int64_t>, std::vector<size_t>> at;  // end -> lines
  for (size_t k = 0; k < lines.size(); ++k) {
    at[key(lines[k].first)].push_back(k);
    if (key(lines[k].second) != key(lines[k].first)) at[key(lines[k].second)].push_back(k);
  }
  auto other_end = [&](size_t k, Vec2 p) { return key(lines[k].first) == key(p) ? lines[k].second : lines[k].first; };
  constexpr double kMostTurn = 36 * std::numbers::pi / 180;
  // The other line at end p of line k, where exactly two lines meet there, turning gently.
  auto next = [&](size_t k, Vec2 p) -> std::optional<size_t> {
    const std::vector<size_t>& v = at[key(p)];
    if (v.size() != 2) return std::nullopt;
    const size_t n = v[0] == k ? v[1] : v[0];
    const Vec2 u = p - other_end(k, p), w = other_end(n, p) - p;
    if (!(std::fabs(std::atan2(cross(u, w), dot(u, w))) < kMostTurn)) return std::nullopt;
    return n;
  };
  std::vector<bool> used(lines.size(), false);
  for (size_t k0 = 0; k0 < lines.size(); ++k0) {
    if (used[k0] || !(length(lines[k0].second - lines[k0].first) > 0)) continue;
    // Walk back from k0's first end to the chain's start, then forward collecting corners.
    size_t k = k0;
    Vec2 p = lines[k0].first;
    for (size_t steps = 0; steps < lines.size(); ++steps) {
      const std::optional<size_t> n = next(k, p);
      if (!n || *n == k0) break;  // an open end, or round a closed loop
      p = other_end(*n, p), k = *n;
    }
    ArcOfLines arc;
    std::vector<Vec2> pts{p};
    for (std::optional<size_t> cur = k; cur && !used[*cur];) {
      used[*cur] = true;
      arc.lines.push_back(*cur);
      pts.push_back(other_end(*cur, pts.back()));
      cur = next(*cur, pts.back());
    }
    if (arc.lines.size() < 3 || key(pts.front()) == key(pts.back())) continue;  // too short, or a closed outline
    // Turning the same way, gently, at every corner.
    double turned = 0;
    bool smooth = true;
    for (size_t i = 1; i + 1 < pts.size() && smooth; ++i) {
      const Vec2 u = pts[i] - pts[i - 1], v = pts[i + 1] - pts[i];
      const double t = std::atan2(cross(u, v), dot(u, v));
      smooth = std::fabs(t) > 1e-3 && std::fabs(t) < kMostTurn && (i == 1 || (t > 0) == (turned > 0));
      turned += t;
    }
    if (!smooth) continue;
    // The circle through the first, middle and last corners holds them all.
    const Vec2 a = pts.front(), b = pts[pts.size() / 2], c = pts.back();
    const double d = 2 * cross(b - a, c - a);
    if (!(std::fabs(d) > 0)) continue;
    const Vec2 ab = b - a, ac = c - a;
    arc.centre = a + (1 / d) * Vec2{ac.y * dot(ab, ab) - ab.y * dot(ac, ac), ab.x * dot(ac, ac) - ac.x * dot(ab, ab)};
    arc.r = length(a - arc.centre);
    if (!std::all_of(pts.begin(), pts.end(), [&](Vec2 corner) { return std::fabs(length(corner - arc.centre) - arc.r) <= 0.02 * arc.r; }))
      continue;
    // The sweep: each line's angle about the centre, summed.
    double sweep = 0;
    for (size_t i = 0; i + 1 < pts.size(); ++i)
      sweep += std::fabs(std::atan2(cross(pts[i] - arc.centre, pts[i + 1] - arc.centre), dot(pts[i] - arc.centre, pts[i + 1] - arc.centre)));
    arc.sweep_deg = sweep * 180 / std::numbers::pi;
    const bool ccw = turned > 0;
    arc.from = ccw ? a : c, arc.to = ccw ? c : a;
    out.push_back(std::move(arc));
  }
  return out;
}

}  // namespace avenues

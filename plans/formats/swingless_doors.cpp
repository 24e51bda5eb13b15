// Avenues — doors drawn without a swing (see swingless_doors.h).
#include "plans/formats/swingless_doors.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>

#include "core/angles.h"

namespace avenues {
namespace {

double segment_distance(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  return std::min({distance_to_segment(a, c, d), distance_to_segment(b, c, d), distance_to_segment(c, a, b),
                   distance_to_segment(d, a, b)});
}

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int root(int i) { return parent[size_t(i)] == i ? i : parent[size_t(i)] = root(parent[size_t(i)]); }
  void join(int i, int j) { parent[size_t(root(i))] = root(j); }
};

/// A set of lines seen along an axis: its main direction (unit), a point on its middle
/// line, its extent along (lo..hi from `mid`) and across.
struct Piece {
  std::vector<int> lines;
  Vec2 u{1, 0}, mid;
  double lo = 0, hi = 0, across = 0;
};

/// The main axis of the lines' end points (the longest line's direction when they are one
/// point), and their extents about it.
Piece measure(const std::vector<int>& lines, const std::vector<std::pair<Vec2, Vec2>>& seg) {
  Piece p;
  p.lines = lines;
  Vec2 c{0, 0};
  double w = 0, best = -1;
  for (int i : lines) {
    const auto& [a, b] = seg[size_t(i)];
    const double len = length(b - a);
    c = c + len * (0.5 * (a + b)), w += len;
    if (len > best) best = len, p.u = len > 0 ? (1 / len) * (b - a) : Vec2{1, 0};
  }
  if (w > 0) c = (1 / w) * c;
  else c = seg[size_t(lines.front())].first;
  // Second moments of the lines (uniform along each), for the main axis.
  double sxx = 0, sxy = 0, syy = 0;
  for (int i : lines) {
    const auto& [a, b] = seg[size_t(i)];
    const double len = length(b - a);
    const Vec2 p0 = a - c, p1 = b - c;
    sxx += len * (p0.x * p0.x + p0.x * p1.x + p1.x * p1.x) / 3;
    syy += len * (p0.y * p0.y + p0.y * p1.y + p1.y * p1.y) / 3;
    sxy += len * (2 * p0.x * p0.y + p0.x * p1.y + p1.x * p0.y + 2 * p1.x * p1.y) / 6;
  }
  if (sxx + syy > 1e-12) {
    const double angle = 0.5 * std::atan2(2 * sxy, sxx - syy);
    p.u = {std::cos(angle), std::sin(angle)};
  }
  const Vec2 n{-p.u.y, p.u.x};
  double lo = 1e300, hi = -1e300, clo = 1e300, chi = -1e300;
  for (int i : lines)
    for (Vec2 q : {seg[size_t(i)].first, seg[size_t(i)].second}) {
      const double t = dot(q - c, p.u), s = dot(q - c, n);
      lo = std::min(lo, t), hi = std::max(hi, t), clo = std::min(clo, s), chi = std::max(chi, s);
    }
  p.mid = c + (0.5 * (clo + chi)) * n;
  p.lo = lo, p.hi = hi, p.across = chi - clo;
  return p;
}

}  // namespace

std::vector<SwinglessDoor> find_swingless_doors(const std::vector<std::pair<Vec2, Vec2>>& door_lines,
                                                const std::vector<bool>& door_line_is_wall,
                                                const std::vector<std::pair<Vec2, Vec2>>& wall_lines,
                                                const std::vector<Vec2>& swing_points,
                                                const SwinglessDoorParams& prm) {
  const size_t n = door_lines.size();
  // 1. Pieces: lines touching one another; a piece near a swing belongs to that door.
  UnionFind touch(n);
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j)
      if (segment_distance(door_lines[i].first, door_lines[i].second, door_lines[j].first, door_lines[j].second) < 0.02)
        touch.join(int(i), int(j));
  std::vector<std::vector<int>> members(n);
  for (size_t i = 0; i < n; ++i) members[size_t(touch.root(int(i)))].push_back(int(i));
  std::vector<Piece> pieces;
  for (const std::vector<int>& m : members) {
    if (m.empty()) continue;
    bool by_swing = false;
    for (int i : m)
      for (Vec2 s : swing_points)
        by_swing = by_swing || distance_to_segment(s, door_lines[size_t(i)].first, door_lines[size_t(i)].second) < prm.near_swing;
    if (by_swing) continue;
    Piece p = measure(m, door_lines);
    if (p.across <= prm.max_across && p.hi - p.lo <= prm.max_width + 0.5) pieces.push_back(p);
  }
  // 2. Pieces along one axis are one door.
  UnionFind along(pieces.size());
  for (size_t i = 0; i < pieces.size(); ++i)
    for (size_t j = i + 1; j < pieces.size(); ++j) {
      const Piece &p = pieces[i], &q = pieces[j];
      if (std::fabs(cross(p.u, q.u)) > std::sin(rad_from_deg(10))) continue;
      const Vec2 nrm{-p.u.y, p.u.x};
      if (std::fabs(dot(q.mid - p.mid, nrm)) > prm.max_across) continue;
      const double off = dot(q.mid - p.mid, p.u);
      const double q_lo = off + std::min(q.lo * dot(q.u, p.u), q.hi * dot(q.u, p.u)),
                   q_hi = off + std::max(q.lo * dot(q.u, p.u), q.hi * dot(q.u, p.u));
      const double apart = std::max(q_lo - p.hi, p.lo - q_hi);
      if (apart < 1.0) along.join(int(i), int(j));
    }
  std::vector<std::vector<int>> groups(pieces.size());
  for (size_t i = 0; i < pieces.size(); ++i) groups[size_t(along.root(int(i)))].push_back(int(i));

  std::vector<SwinglessDoor> out;
  for (const std::vector<int>& g : groups) {
    if (g.empty()) continue;
    std::vector<int> lines;
    for (int k : g) lines.insert(lines.end(), pieces[size_t(k)].lines.begin(), pieces[size_t(k)].lines.end());
    const Piece door = measure(lines, door_lines);
    if (door.hi - door.lo < prm.min_width || door.across > prm.max_across || door.hi - door.lo > prm.max_width + 0.5)
      continue;
    const Vec2 u = door.u, nrm{-u.y, u.x};
    const Vec2 c = door.mid + (0.5 * (door.lo + door.hi)) * u;
    std::vector<bool> own(n, false);
    for (int i : lines) own[size_t(i)] = true;
    // 3. The gap's ends, looking both ways from the middle.
    auto each_wall = [&](const std::function<void(Vec2, Vec2)>& f) {
      for (const auto& [a, b] : wall_lines) f(a, b);
      for (size_t i = 0; i < n; ++i)
        if (door_line_is_wall[i] && !own[i]) f(door_lines[i].first, door_lines[i].second);
    };
    double end[2] = {1e300, 1e300};
    bool crossed[2] = {false, false};
    each_wall([&](Vec2 a, Vec2 b) {
      const double len = length(b - a);
      if (len < 1e-6) return;
      const double sa = dot(a - c, nrm), sb = dot(b - c, nrm), ta = dot(a - c, u), tb = dot(b - c, u);
      const bool parallel = std::fabs(cross(u, (1 / len) * (b - a))) < std::sin(rad_from_deg(15));
      if (parallel) {
        if (std::max(std::fabs(sa), std::fabs(sb)) > prm.max_half_wall) return;
        // A face beside the axis: the gap ends where it begins (a face running through the
        // middle is no gap's).
        if (ta > 0 && tb > 0 && std::min(ta, tb) < end[0]) end[0] = std::min(ta, tb), crossed[0] = false;
        if (ta < 0 && tb < 0 && -std::max(ta, tb) < end[1]) end[1] = -std::max(ta, tb), crossed[1] = false;
        return;
      }
      if ((sa > 0) == (sb > 0) && sa != 0 && sb != 0) return;
      const double t = ta + (tb - ta) * (sa / (sa - sb));
      const int side = t >= 0 ? 0 : 1;
      if (std::fabs(t) < end[side]) end[side] = std::fabs(t), crossed[side] = true;
    });
    // A crossed cap counts when the wall goes on past it: a face along the axis beyond.
    for (int side = 0; side < 2; ++side) {
      if (!crossed[side] || end[side] > 1e299) continue;
      const double sign = side == 0 ? 1 : -1;
      bool goes_on = false;
      each_wall([&](Vec2 a, Vec2 b) {
        const double len = length(b - a);
        if (goes_on || len < 1e-6 || std::fabs(cross(u, (1 / len) * (b - a))) > std::sin(rad_from_deg(15))) return;
        if (std::max(std::fabs(dot(a - c, nrm)), std::fabs(dot(b - c, nrm))) > prm.max_half_wall) return;
        const double ta = sign * dot(a - c, u) - end[side], tb = sign * dot(b - c, u) - end[side];
        goes_on = std::min(ta, tb) < 0.3 && std::max(ta, tb) > 0.05;
      });
      if (!goes_on) end[side] = 1e300;
    }
    SwinglessDoor d;
    d.lines = lines;
    d.where = c;
    const double width = end[0] + end[1];
    const double half = 0.5 * (door.hi - door.lo), covered = std::min(half, end[0]) + std::min(half, end[1]);
    if (end[0] < prm.max_width && end[1] < prm.max_width && width >= prm.min_width && width <= prm.max_width &&
        covered >= width / 3) {
      d.a = c - end[1] * u;
      d.b = c + end[0] * u;
      d.placed = true;
    }
    out.push_back(d);
  }
  return out;
}

}  // namespace avenues

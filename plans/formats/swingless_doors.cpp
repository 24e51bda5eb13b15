// Avenues — doors drawn without a swing (see swingless_doors.h).
#include "plans/formats/swingless_doors.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>

#include "core/angles.h"
#include "plans/formats/segment_grid.h"

namespace avenues {
namespace {

double segment_distance(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  return std::min({distance_to_segment(a, c, d), distance_to_segment(b, c, d), distance_to_segment(c, a, b),
                   distance_to_segment(d, a, b)});
}

/// Sets joined; each set's root is its smallest member, whatever order the joins come in.
struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int root(int i) { return parent[size_t(i)] == i ? i : parent[size_t(i)] = root(parent[size_t(i)]); }
  void join(int i, int j) {
    const int a = root(i), b = root(j);
    if (a != b) parent[size_t(std::max(a, b))] = std::min(a, b);
  }
};

/// The middle of a segment and a reach from it that covers the segment and `r` about it.
std::pair<Vec2, double> about(Vec2 a, Vec2 b, double r) { return {0.5 * (a + b), 0.5 * length(b - a) + r}; }

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
  // (Near neighbours come from grids of segments throughout: an office of thousands of
  // doors is not compared pair by pair.)
  // 1. Pieces: lines touching one another; a piece near a swing belongs to that door.
  UnionFind touch(n);
  SegmentGrid line_grid(door_lines, 0.5);
  for (size_t i = 0; i < n; ++i) {
    const auto [mid, reach] = about(door_lines[i].first, door_lines[i].second, 0.02);
    line_grid.near(mid, reach, [&](size_t j) {
      if (j > i && segment_distance(door_lines[i].first, door_lines[i].second, door_lines[j].first, door_lines[j].second) < 0.02)
        touch.join(int(i), int(j));
    });
  }
  std::vector<std::pair<Vec2, Vec2>> swing_at;
  for (Vec2 s : swing_points) swing_at.push_back({s, s});
  SegmentGrid swing_grid(swing_at, 0.5);
  std::vector<std::vector<int>> members(n);
  for (size_t i = 0; i < n; ++i) members[size_t(touch.root(int(i)))].push_back(int(i));
  std::vector<Piece> pieces;
  for (const std::vector<int>& m : members) {
    if (m.empty()) continue;
    bool by_swing = false;
    for (int i : m) {
      const Vec2 a = door_lines[size_t(i)].first, b = door_lines[size_t(i)].second;
      const auto [mid, reach] = about(a, b, prm.near_swing);
      swing_grid.near(mid, reach, [&](size_t k) { by_swing = by_swing || distance_to_segment(swing_points[k], a, b) < prm.near_swing; });
    }
    if (by_swing) continue;
    Piece p = measure(m, door_lines);
    if (p.across <= prm.max_across && p.hi - p.lo <= prm.max_width + 0.5) pieces.push_back(p);
  }
  // 2. Pieces along one axis are one door.
  UnionFind along(pieces.size());
  std::vector<std::pair<Vec2, Vec2>> axes;
  for (const Piece& p : pieces) axes.push_back({p.mid + p.lo * p.u, p.mid + p.hi * p.u});
  SegmentGrid axis_grid(axes, 0.5);
  for (size_t i = 0; i < pieces.size(); ++i) {
    const auto [centre, reach] = about(axes[i].first, axes[i].second, 1.0 + prm.max_across);
    axis_grid.near(centre, reach, [&](size_t j) {
      if (j <= i) return;
      const Piece &p = pieces[i], &q = pieces[j];
      if (std::fabs(cross(p.u, q.u)) > std::sin(rad_from_deg(10))) return;
      const Vec2 nrm{-p.u.y, p.u.x};
      if (std::fabs(dot(q.mid - p.mid, nrm)) > (prm.join_across < 0 ? prm.max_across : prm.join_across)) return;
      const double off = dot(q.mid - p.mid, p.u);
      const double q_lo = off + std::min(q.lo * dot(q.u, p.u), q.hi * dot(q.u, p.u)),
                   q_hi = off + std::max(q.lo * dot(q.u, p.u), q.hi * dot(q.u, p.u));
      const double apart = std::max(q_lo - p.hi, p.lo - q_hi);
      if (apart < 1.0) along.join(int(i), int(j));
    });
  }
  std::vector<std::vector<int>> groups(pieces.size());
  for (size_t i = 0; i < pieces.size(); ++i) groups[size_t(along.root(int(i)))].push_back(int(i));

  // The walls a gap may end at: the wall lines, then the door lines that are walls.
  std::vector<std::pair<Vec2, Vec2>> walls = wall_lines;
  std::vector<size_t> door_line_of;  // per entry of walls past wall_lines: its door line
  for (size_t i = 0; i < n; ++i)
    if (door_line_is_wall[i]) walls.push_back(door_lines[i]), door_line_of.push_back(i);
  SegmentGrid wall_grid(walls, 0.5);
  // Any line that could end a gap narrower than max_width, or tell that a wall goes on past
  // its end, passes within this of the gap's middle.
  const double reach = prm.max_width + prm.max_half_wall + 0.5;

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
    std::vector<int> own = lines;  // sorted, to look up (a door's few lines, not every door line)
    std::sort(own.begin(), own.end());
    // 3. The gap's ends, looking both ways from the middle.
    auto each_wall = [&](const std::function<void(Vec2, Vec2)>& f) {
      wall_grid.near(c, reach, [&](size_t k) {
        if (k >= wall_lines.size() && std::binary_search(own.begin(), own.end(), int(door_line_of[k - wall_lines.size()]))) return;
        f(walls[k].first, walls[k].second);
      });
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

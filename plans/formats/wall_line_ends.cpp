// Avenues — closing the gaps at wall lines' ends (see wall_line_ends.h).
#include "plans/formats/wall_line_ends.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <tuple>
#include <unordered_map>

#include "core/angles.h"
#include "plans/formats/segment_grid.h"

namespace avenues {
namespace {

/// The squared distance from p to segment [a, b] (no square root: the hot test of pass 0).
double distance2_to_segment(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 d = b - a;
  const double dd = dot(d, d);
  const double t = dd > 0 ? std::clamp(dot(p - a, d) / dd, 0.0, 1.0) : 0.0;
  const Vec2 q = p - (a + t * d);
  return dot(q, q);
}

/// Where the ray p + t·u (t in (0, reach]) first meets segment [a, b], or +inf.
double ray_hit(Vec2 p, Vec2 u, double reach, Vec2 a, Vec2 b) {
  const Vec2 d = b - a;
  const double den = cross(u, d);
  if (std::fabs(den) < 1e-12) return std::numeric_limits<double>::infinity();  // parallel
  const double t = cross(a - p, d) / den, s = cross(a - p, u) / den;
  if (t <= 0 || t > reach || s < -1e-9 || s > 1 + 1e-9) return std::numeric_limits<double>::infinity();
  return t;
}

/// Pass 0 (see wall_line_ends.h): joins each end of a line to the lines it nearly
/// touches, for pairs with at least one line at index >= first_new. Appends the joining
/// lines to `added`; per line end, whether it was joined and whether it touches a line
/// (with first_new > 0, an old line's end is tested against the new lines only).
struct NearEnds { std::vector<std::array<bool, 2>> joined, touches; };
NearEnds join_near_ends(const std::vector<std::pair<Vec2, Vec2>>& lines, size_t first_new, bool shared_only,
                        const WallLineEndParams& prm, std::vector<std::pair<Vec2, Vec2>>& added) {
  NearEnds ne{std::vector<std::array<bool, 2>>(lines.size(), {false, false}),
              std::vector<std::array<bool, 2>>(lines.size(), {false, false})};
  if (lines.empty()) return ne;
  // Queries reach a few millimetres: cells of 5 cm keep a dense drawing's bins short.
  const double reach = std::max(prm.touch, prm.join);
  const double cell = std::max(4 * reach, 0.05);
  SegmentGrid grid(lines, cell);
  // The old lines' ends need only meet the new lines.
  std::optional<SegmentGrid> new_lines;
  if (first_new > 0) new_lines.emplace(lines, cell, first_new);
  // Lines meeting exactly at an end point, for walking along the drawing.
  struct PointHash {
    size_t operator()(const std::pair<double, double>& p) const {
      return std::hash<double>()(p.first) * 0x9E3779B97F4A7C15ull ^ std::hash<double>()(p.second);
    }
  };
  std::unordered_map<std::pair<double, double>, std::vector<size_t>, PointHash> at_point;
  for (size_t i = 0; i < lines.size(); ++i)
    for (Vec2 p : {lines[i].first, lines[i].second}) at_point[{p.x, p.y}].push_back(i);
  // The lines reached from p along lines meeting end to end, within `budget` of walking:
  // a line this near along the drawing is a piece of the same curve (a finely drawn
  // column's outline), not one the end stops short of.
  auto reached = [&](Vec2 p, double budget) {
    // The shortest walk to each point reached (few: the budget is millimetres).
    std::vector<std::pair<Vec2, double>> best{{p, 0}};
    std::vector<std::pair<Vec2, double>> todo{{p, 0}};
    std::vector<size_t> out_lines;
    while (!todo.empty() && out_lines.size() < 4096) {
      const auto [q, d] = todo.back();
      todo.pop_back();
      for (size_t k : at_point.at({q.x, q.y})) {
        out_lines.push_back(k);
        const Vec2 r = lines[k].first == q ? lines[k].second : lines[k].first;
        const double dr = d + length(r - q);
        if (dr > budget) continue;
        auto it = std::find_if(best.begin(), best.end(), [&](const auto& b) { return b.first == r; });
        if (it == best.end()) best.push_back({r, dr});
        else if (it->second <= dr) continue;
        else it->second = dr;
        todo.push_back({r, dr});
      }
    }
    std::sort(out_lines.begin(), out_lines.end());
    return out_lines;
  };

  std::unordered_map<std::pair<double, double>, std::vector<size_t>, PointHash> reached_from;
  const double sin_along = std::sin(rad_from_deg(10));  // runs along a line below 10°
  std::set<std::tuple<double, double, size_t>> done;  // (end point, line joined to): a corner's lines join once
  for (size_t i = 0; i < lines.size(); ++i) {
    const auto [a, b] = lines[i];
    const double len = length(b - a);
    if (!(len > 0)) continue;
    for (int w = 0; w < 2; ++w) {
      const Vec2 p = w ? b : a, u = (1 / len) * (w ? b - a : a - b);
      std::vector<size_t> near_lines;
      (i < first_new ? *new_lines : grid).near(p, reach, [&](size_t j) {
        if (j == i) return;
        const auto [c, d] = lines[j];
        const double dist2 = distance2_to_segment(p, c, d);
        if (dist2 <= prm.touch * prm.touch) ne.touches[i][size_t(w)] = true;
        if (i < first_new && j < first_new) return;
        if (dist2 <= prm.join * prm.join && p != c && p != d) near_lines.push_back(j);  // not meeting it at its end exactly
      });
      if (near_lines.empty()) continue;
      std::sort(near_lines.begin(), near_lines.end());  // in the drawing's order, not the grid's
      // An end where no other line ends is carried on 1 mm by the arrangement (see
      // `touch`): it needs no joining line to a line that carrying on crosses.
      bool shared = false;
      grid.near(p, 2e-4, [&](size_t j) {
        shared = shared || (j != i && (length(lines[j].first - p) < 2e-4 || length(lines[j].second - p) < 2e-4));
      });
      if (shared_only && !shared) continue;
      // Many line ends meet at one point of a dense drawing: walk from each point once.
      auto [cached, first_time] = reached_from.try_emplace({p.x, p.y});
      if (first_time) cached->second = reached(p, 4 * prm.join);
      const std::vector<size_t>& along = cached->second;
      for (size_t j : near_lines) {
        if (std::binary_search(along.begin(), along.end(), j)) continue;
        if (!done.insert({p.x, p.y, j}).second) {
          ne.joined[i][size_t(w)] = true;
          continue;
        }
        const auto [c, d] = lines[j];
        if (!shared) {
          const double den = cross(u, d - c);
          const double th = std::fabs(den) > 1e-12 ? cross(c - p, d - c) / den : -1;
          const double sh = std::fabs(den) > 1e-12 ? cross(c - p, u) / den : -1;
          if (th >= -1e-9 && th <= 0.8 * kWallLineCarriedOn && sh > 0.01 && sh < 0.99) continue;
        }
        const double lj = length(d - c), dist = distance_to_segment(p, c, d);
        if (!(lj > 0)) continue;
        const Vec2 v = (1 / lj) * (d - c), n{-v.y, v.x};
        const double t = dot(p - c, v);
        if (t <= 0 || t >= lj) {  // nearest at its end: joined to that end, point to point
          added.push_back({p, t <= 0 ? c : d});
          ne.joined[i][size_t(w)] = true;
          continue;
        }
        // Beside it: a free end running along it stays free (a wall's end capped in pass 2).
        if (dist > prm.touch && std::fabs(cross(u, v)) < sin_along) continue;
        const Vec2 f = c + t * v;
        const double side = cross(v, p - c);  // which side of it the end lies, + the left
        // The reader snaps the drawing to 0.1 mm afterwards, moving the end and the line
        // by up to 0.07 mm: an end nearer than 0.1 mm (`touch`/5) may land on either side,
        // so it is joined across to both.
        if (std::fabs(side) < 0.2 * prm.touch || side < 0) added.push_back({p, f + prm.join_overshoot * n});
        if (std::fabs(side) < 0.2 * prm.touch || side > 0) added.push_back({p, f - prm.join_overshoot * n});
        ne.joined[i][size_t(w)] = true;
      }
    }
  }
  return ne;
}

}  // namespace

WallLineEnds close_wall_line_ends(const std::vector<std::pair<Vec2, Vec2>>& lines, const WallLineEndParams& prm) {
  WallLineEnds out;
  if (lines.empty()) return out;
  SegmentGrid grid(lines, std::max(prm.cap, 0.1));

  // Pass 0, then the free ends: (line, which end) whose point no other line comes within
  // `touch` of and that is joined to none.
  const NearEnds ne = join_near_ends(lines, 0, true, prm, out.added);
  out.joined = int(out.added.size());
  struct End { size_t line; int which; Vec2 p, u; };  // u: the line's direction out of this end
  std::vector<End> free;
  for (size_t i = 0; i < lines.size(); ++i) {
    const auto [a, b] = lines[i];
    const double len = length(b - a);
    for (int w = 0; w < 2; ++w) {
      if (!(len > prm.touch) || ne.touches[i][size_t(w)]) continue;
      free.push_back({i, w, w ? b : a, (1 / len) * (w ? b - a : a - b)});
    }
  }
  out.free_ends = int(free.size());

  // Pass 1: undershoots, carried on along the line.
  std::vector<bool> closed(free.size(), false);
  for (size_t k = 0; k < free.size(); ++k) {
    const End& e = free[k];
    double best = std::numeric_limits<double>::infinity();
    grid.near(e.p, prm.reach, [&](size_t j) {
      if (j != e.line) best = std::min(best, ray_hit(e.p, e.u, prm.reach, lines[j].first, lines[j].second));
    });
    if (std::isfinite(best)) {
      out.added.push_back({e.p, e.p + best * e.u});
      closed[k] = true;
      ++out.extended;
    }
  }

  // Pass 2: the free ends left, joined to their mutually nearest free end within `cap`.
  std::vector<Vec2> pts;
  std::vector<size_t> who;
  for (size_t k = 0; k < free.size(); ++k)
    if (!closed[k]) pts.push_back(free[k].p), who.push_back(k);
  std::vector<std::pair<Vec2, Vec2>> as_points;
  for (Vec2 p : pts) as_points.push_back({p, p});
  SegmentGrid end_grid(as_points, std::max(prm.cap, 0.1));
  std::vector<int> nearest(pts.size(), -1);
  for (size_t k = 0; k < pts.size(); ++k) {
    double best = prm.cap;
    end_grid.near(pts[k], prm.cap, [&](size_t j) {
      // Not the other end of its own line (a short line's two ends).
      if (j == k || free[who[j]].line == free[who[k]].line) return;
      const double d = length(pts[j] - pts[k]);
      if (d > prm.touch && d <= best) best = d, nearest[k] = int(j);
    });
  }
  for (size_t k = 0; k < pts.size(); ++k) {
    const int j = nearest[k];
    if (j > int(k) && nearest[size_t(j)] == int(k)) {
      out.added.push_back({pts[k], pts[size_t(j)]});
      ++out.capped;
    }
  }
  return out;
}

std::vector<std::pair<Vec2, Vec2>> join_wall_line_ends(const std::vector<std::pair<Vec2, Vec2>>& lines, size_t first_new,
                                                        const WallLineEndParams& params) {
  std::vector<std::pair<Vec2, Vec2>> added;
  join_near_ends(lines, first_new, false, params, added);
  return added;
}

}  // namespace avenues

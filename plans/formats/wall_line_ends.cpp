// Avenues — closing the gaps at wall lines' ends (see wall_line_ends.h).
#include "plans/formats/wall_line_ends.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

namespace avenues {
namespace {

/// Segments binned in square cells of side `cell`; a query visits the cells a box covers.
class SegmentGrid {
 public:
  SegmentGrid(const std::vector<std::pair<Vec2, Vec2>>& lines, double cell)
      : cell_(cell), seen_(lines.size(), 0) {
    for (size_t i = 0; i < lines.size(); ++i) {
      const auto [a, b] = lines[i];
      const Vec2 lo{std::min(a.x, b.x), std::min(a.y, b.y)}, hi{std::max(a.x, b.x), std::max(a.y, b.y)};
      // A very long line is binned along its length only (cells it passes near); one
      // longer than kMaxSteps cells (or not finite: a broken drawing) is met by every query.
      const double len = length(b - a);
      if (!(len / cell < kMaxSteps) || !(std::fabs(lo.x) < kFar && std::fabs(lo.y) < kFar && std::fabs(hi.x) < kFar && std::fabs(hi.y) < kFar)) {
        everywhere_.push_back(i);
        continue;
      }
      const int steps = std::max(1, int(std::ceil(len / cell)));
      if ((hi.x - lo.x) * (hi.y - lo.y) > 16 * double(steps) * cell * cell) {
        for (int s = 0; s <= steps; ++s) {
          const Vec2 p = a + (double(s) / steps) * (b - a);
          for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy) add(key(ix(p.x) + dx, ix(p.y) + dy), i);
        }
        continue;
      }
      for (int64_t x = ix(lo.x); x <= ix(hi.x); ++x)
        for (int64_t y = ix(lo.y); y <= ix(hi.y); ++y) add(key(x, y), i);
    }
  }
  /// Calls f(index) once for each line binned in a cell the box [p - r, p + r] covers.
  template <class F>
  void near(Vec2 p, double r, F f) {
    ++stamp_;
    for (size_t i : everywhere_) f(i);
    if (!(std::fabs(p.x) < kFar && std::fabs(p.y) < kFar)) return;
    for (int64_t x = ix(p.x - r); x <= ix(p.x + r); ++x)
      for (int64_t y = ix(p.y - r); y <= ix(p.y + r); ++y) {
        auto it = bins_.find(key(x, y));
        if (it == bins_.end()) continue;
        for (size_t i : it->second) {
          if (seen_[i] == stamp_) continue;
          seen_[i] = stamp_;
          f(i);
        }
      }
  }

 private:
  static constexpr double kMaxSteps = 1 << 12, kFar = 1e12;  ///< [cells] (1.8 km at 0.45 m), [m]
  int64_t ix(double v) const { return int64_t(std::floor(v / cell_)); }
  static uint64_t key(int64_t x, int64_t y) { return (uint64_t(x) << 32) ^ uint64_t(uint32_t(y)); }
  void add(uint64_t k, size_t i) {
    std::vector<size_t>& bin = bins_[k];
    if (bin.empty() || bin.back() != i) bin.push_back(i);
  }
  double cell_;
  std::unordered_map<uint64_t, std::vector<size_t>> bins_;
  std::vector<uint64_t> seen_;
  std::vector<size_t> everywhere_;
  uint64_t stamp_ = 0;
};

/// Where the ray p + t·u (t in (0, reach]) first meets segment [a, b], or +inf.
double ray_hit(Vec2 p, Vec2 u, double reach, Vec2 a, Vec2 b) {
  const Vec2 d = b - a;
  const double den = cross(u, d);
  if (std::fabs(den) < 1e-12) return std::numeric_limits<double>::infinity();  // parallel
  const double t = cross(a - p, d) / den, s = cross(a - p, u) / den;
  if (t <= 0 || t > reach || s < -1e-9 || s > 1 + 1e-9) return std::numeric_limits<double>::infinity();
  return t;
}

}  // namespace

WallLineEnds close_wall_line_ends(const std::vector<std::pair<Vec2, Vec2>>& lines, const WallLineEndParams& prm) {
  WallLineEnds out;
  if (lines.empty()) return out;
  SegmentGrid grid(lines, std::max(prm.cap, 0.1));

  // Free ends: (line, which end) whose point no other line comes within `touch` of.
  struct End { size_t line; int which; Vec2 p, u; };  // u: the line's direction out of this end
  std::vector<End> free;
  for (size_t i = 0; i < lines.size(); ++i) {
    const auto [a, b] = lines[i];
    const double len = length(b - a);
    if (!(len > prm.touch)) continue;
    for (int w = 0; w < 2; ++w) {
      const Vec2 p = w ? b : a, u = (1 / len) * (w ? b - a : a - b);
      bool touches = false;
      grid.near(p, prm.touch, [&](size_t j) {
        if (j != i && distance_to_segment(p, lines[j].first, lines[j].second) <= prm.touch) touches = true;
      });
      if (!touches) free.push_back({i, w, p, u});
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

}  // namespace avenues

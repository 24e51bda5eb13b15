// Avenues — the order a pen plotter draws strokes in (see pen_order.h).
#include "render/pen_order.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace avenues {

namespace {

/// The ends of one pen's segments in a uniform grid: end e of segment i has id 2·i + e.
/// A bucket is a slice of `items`; ends of drawn segments are swapped out of their slice
/// when a search meets them, so each is skipped at most once.
class EndGrid {
 public:
  EndGrid(const std::vector<std::array<Vec2, 2>>& segments, const std::vector<uint32_t>& ids,
          const std::vector<uint8_t>& drawn)
      : segments_(segments), drawn_(drawn) {
    Box3 box;
    for (uint32_t i : ids)
      for (const Vec2& p : segments[i]) box.add({p.x, p.y, 0});
    lo_ = {box.lo.x, box.lo.y};
    const double w = box.hi.x - box.lo.x, h = box.hi.y - box.lo.y, m = double(2 * ids.size());
    // About two ends per square; a degenerate (flat) box falls back to its length.
    cell_ = std::max({std::sqrt(w * h * 2 / m), std::max(w, h) * 2 / m, 1e-9});
    nx_ = std::clamp(int(w / cell_) + 1, 1, 2048);
    ny_ = std::clamp(int(h / cell_) + 1, 1, 2048);
    cell_ = std::max({cell_, w / nx_ * (1 + 1e-12), h / ny_ * (1 + 1e-12)});
    start_.assign(size_t(nx_) * size_t(ny_) + 1, 0);
    for (uint32_t i : ids)
      for (const Vec2& p : segments[i]) ++start_[bucket(p) + 1];
    for (size_t b = 1; b < start_.size(); ++b) start_[b] += start_[b - 1];
    live_.assign(start_.size() - 1, 0);
    items_.resize(start_.back());
    for (uint32_t i : ids)
      for (uint32_t e = 0; e < 2; ++e) {
        const size_t b = bucket(segments[i][e]);
        items_[size_t(start_[b] + live_[b]++)] = 2 * i + e;
      }
  }

  /// The end nearest `p` of a segment not yet drawn; there must be one.
  uint32_t nearest(Vec2 p) {
    const int cx = square(p.x - lo_.x, nx_), cy = square(p.y - lo_.y, ny_);
    uint32_t best = 0;
    double best_d2 = std::numeric_limits<double>::infinity();
    for (int r = 0; r <= std::max(nx_, ny_); ++r) {
      for (int j = cy - r; j <= cy + r; ++j) {
        if (j < 0 || j >= ny_) continue;
        const bool edge_row = j == cy - r || j == cy + r;
        for (int i = cx - r; i <= cx + r; i += edge_row ? 1 : 2 * std::max(r, 1)) {
          if (i >= 0 && i < nx_) scan(size_t(j) * size_t(nx_) + size_t(i), p, best, best_d2);
        }
      }
      // Ends in rings beyond r lie at least r squares from p's square (and from p, which
      // projects into it when it lies outside the grid).
      if (best_d2 <= (r * cell_) * (r * cell_)) break;
    }
    return best;
  }

 private:
  /// The square along one axis holding offset `d` from the grid's corner, clamped to the grid.
  int square(double d, int n) const { return int(std::clamp(std::floor(d / cell_), 0.0, double(n - 1))); }
  size_t bucket(Vec2 p) const { return size_t(square(p.y - lo_.y, ny_)) * size_t(nx_) + size_t(square(p.x - lo_.x, nx_)); }

  void scan(size_t b, Vec2 p, uint32_t& best, double& best_d2) {
    uint32_t* first = items_.data() + start_[b];
    for (uint32_t k = 0; k < live_[b];) {
      const uint32_t id = first[k];
      if (drawn_[id / 2]) {  // drawn since: swap it out of the live slice
        first[k] = first[--live_[b]];
        continue;
      }
      const Vec2 d = segments_[id / 2][id % 2] - p;
      const double d2 = dot(d, d);
      if (d2 < best_d2 || (d2 == best_d2 && id < best)) best = id, best_d2 = d2;
      ++k;
    }
  }

  const std::vector<std::array<Vec2, 2>>& segments_;
  const std::vector<uint8_t>& drawn_;
  Vec2 lo_;
  double cell_ = 1;
  int nx_ = 1, ny_ = 1;
  std::vector<uint32_t> start_, live_, items_;
};

}  // namespace

PenPlan plan_pen_paths(const std::vector<std::array<Vec2, 2>>& segments, const std::vector<int>& pens, Vec2 start) {
  std::vector<int> pen_list(pens.begin(), pens.end());
  std::sort(pen_list.begin(), pen_list.end());
  pen_list.erase(std::unique(pen_list.begin(), pen_list.end()), pen_list.end());

  // A pen-down path grows while the next segment starts where the pen is.
  Vec2 at = start;
  double travel = 0;
  bool in_path = false;
  auto draw = [&](std::vector<PenPath>& paths, int pen, Vec2 from, Vec2 to) {
    const double distance = length(from - at);
    if (!in_path || distance > 0) {
      travel += distance;
      paths.push_back({pen, {from}});
      in_path = true;
    }
    paths.back().points.push_back(to);
    at = to;
  };

  // As given: pen by pen, each segment from its first end.
  std::vector<PenPath> given;
  for (int pen : pen_list) {
    in_path = false;
    for (size_t i = 0; i < segments.size(); ++i)
      if (pens[i] == pen) draw(given, pen, segments[i][0], segments[i][1]);
  }
  const double travel_given = travel;

  // Nearest end first.
  std::vector<PenPath> greedy;
  at = start;
  travel = 0;
  std::vector<uint8_t> drawn(segments.size(), 0);
  for (int pen : pen_list) {
    std::vector<uint32_t> ids;
    for (size_t i = 0; i < segments.size(); ++i)
      if (pens[i] == pen) ids.push_back(uint32_t(i));
    EndGrid grid(segments, ids, drawn);
    in_path = false;
    for (size_t left = ids.size(); left > 0; --left) {
      const uint32_t end = grid.nearest(at), i = end / 2, e = end % 2;
      drawn[i] = 1;
      draw(greedy, pen, segments[i][e], segments[i][1 - e]);
    }
  }

  // Greedy is a heuristic: on a drawing already in a good order it can lose; keep the better.
  PenPlan plan;
  plan.travel_before = travel_given;
  const bool greedy_wins = travel <= travel_given;
  plan.travel_after = greedy_wins ? travel : travel_given;
  plan.paths = greedy_wins ? std::move(greedy) : std::move(given);
  return plan;
}

}  // namespace avenues

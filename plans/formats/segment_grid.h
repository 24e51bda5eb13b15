// Avenues — line segments binned in a uniform grid, for "which lines pass near this
// point" over a drawing's many lines (wall line ends, the DXF reader's fills).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/geometry.h"

namespace avenues {

/// Segments (those from index `first` on) binned in square cells of side `cell`; a
/// query visits the cells a box covers.
class SegmentGrid {
 public:
  SegmentGrid(const std::vector<std::pair<Vec2, Vec2>>& lines, double cell, size_t first = 0)
      : cell_(cell), seen_(lines.size(), 0) {
    for (size_t i = first; i < lines.size(); ++i) {
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
      // Its box's cells where they are few; else the cells along it.
      const double box_cells = double(ix(hi.x) - ix(lo.x) + 1) * double(ix(hi.y) - ix(lo.y) + 1);
      if (box_cells > 4 * double(steps)) {
        // Piece by piece, each at most a cell long: the cells of each piece's box, grown
        // by far more than the pieces' ends round by (two to four cells a piece).
        const double grow = 1e-6 * cell;
        Vec2 p = a;
        for (int s = 1; s <= steps; ++s) {
          const Vec2 q = s == steps ? b : a + (double(s) / steps) * (b - a);
          for (int64_t x = ix(std::min(p.x, q.x) - grow); x <= ix(std::max(p.x, q.x) + grow); ++x)
            for (int64_t y = ix(std::min(p.y, q.y) - grow); y <= ix(std::max(p.y, q.y) + grow); ++y) add(key(x, y), i);
          p = q;
        }
        continue;
      }
      for (int64_t x = ix(lo.x); x <= ix(hi.x); ++x)
        for (int64_t y = ix(lo.y); y <= ix(hi.y); ++y) add(key(x, y), i);
    }
  }
  /// Calls f(index) once for each line binned in a cell the box [p - r, p + r] covers, in
  /// the order of the cells (by x, then y), each cell's lines in the order they were added.
  template <class F>
  void near(Vec2 p, double r, F f) {
    ++stamp_;
    for (size_t i : everywhere_) f(i);
    if (!(std::fabs(p.x) < kFar && std::fabs(p.y) < kFar)) return;
    auto visit = [&](const std::vector<size_t>& bin) {
      for (size_t i : bin) {
        if (seen_[i] == stamp_) continue;
        seen_[i] = stamp_;
        f(i);
      }
    };
    const int64_t x0 = ix(p.x - r), x1 = ix(p.x + r), y0 = ix(p.y - r), y1 = ix(p.y + r);
    // A box over more cells than there are bins (a long line's neighbours, in a drawing a
    // few kilometres across) looks through the bins instead: the same bins, in the same order.
    if (double(x1 - x0 + 1) * double(y1 - y0 + 1) > 4.0 * double(bins_.size())) {
      // A key holds x and y to 32 bits (key()): a bin is in the box when its x is one of the
      // box's x to 32 bits, and so its y.
      auto offset = [](uint64_t k, int64_t from) { return uint64_t(uint32_t(uint32_t(k) - uint32_t(from))); };
      const uint64_t wide = uint64_t(x1 - x0), high = uint64_t(y1 - y0);
      in_box_.clear();
      for (const auto& [k, bin] : bins_) {
        const uint64_t dx = offset(k >> 32, x0), dy = offset(k, y0);
        if ((wide >= 0xffffffffu || dx <= wide) && (high >= 0xffffffffu || dy <= high)) in_box_.push_back({(dx << 32) | dy, &bin});
      }
      std::sort(in_box_.begin(), in_box_.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
      for (const auto& [order, bin] : in_box_) visit(*bin);
      return;
    }
    for (int64_t x = x0; x <= x1; ++x)
      for (int64_t y = y0; y <= y1; ++y) {
        auto it = bins_.find(key(x, y));
        if (it != bins_.end()) visit(it->second);
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
  std::vector<std::pair<uint64_t, const std::vector<size_t>*>> in_box_;  ///< near()'s bins, when it looks through them
  uint64_t stamp_ = 0;
};

}  // namespace avenues

// Avenues — what is already drawn, pixel by pixel (see occlusion_buffer.h).
#include "render/occlusion_buffer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

namespace avenues {

namespace {

constexpr double kOne = double(kSubpixelOne);
/// [samples] how far inside a polygon and its clip region a covered cell's centres lie.
constexpr double kInside = 1e-6;
constexpr int kCells = OcclusionBuffer::kTile * OcclusionBuffer::kTile;

/// The intervals a convex outline takes of row lines met from the top down, walking its two
/// chains of sides (OcclusionBuffer::Chains) once however many lines are asked for.
class RowWalker {
 public:
  explicit RowWalker(const OcclusionBuffer::Chains& chains) : c_(chains) {}
  /// The interval [l, r] of the line at height y, no higher than the last asked for; false
  /// unless the line passes strictly between the outline's highest and lowest corners (by
  /// 1e-6 of a sample), where every point strictly between l and r is strictly inside.
  bool at(double y, double& l, double& r) {
    if (!(y > c_.top + kInside && y < c_.bottom - kInside)) return false;
    l = HUGE_VAL, r = -HUGE_VAL;
    for (int k = 0; k < 2; ++k) {
      const std::vector<Vec2>& c = c_.side[k];
      size_t& i = next_[k];
      while (i + 2 < c.size() && c[i + 1].y < y) ++i;
      const double x = c[i].x + (y - c[i].y) * c_.slope[k][i];  // a side under y: not level
      l = std::min(l, x), r = std::max(r, x);
    }
    return l <= r;
  }

 private:
  const OcclusionBuffer::Chains& c_;
  size_t next_[2] = {0, 0};
};

/// The samples [first, last] whose centres i + ½ lie in [from, to], clamped to [0, n).
void samples_in(double from, double to, int n, int& first, int& last) {
  const double a = std::max(std::ceil(from - 0.5), 0.0), b = std::min(std::floor(to - 0.5), double(n - 1));
  if (!(a <= b)) {
    first = 1, last = 0;
    return;
  }
  first = int(a), last = int(b);
}

}  // namespace

void OcclusionBuffer::reset(int width, int height, int per_side) {
  const int s = std::max(1, per_side);
  const int across = std::max(0, width) / s, down = std::max(0, height) / s;
  const int tiles_across = (across + kTile - 1) / kTile, tiles_down = (down + kTile - 1) / kTile;
  if (s != per_side_ || across != across_ || down != down_) {
    per_side_ = s, across_ = across, down_ = down;
    tiles_across_ = tiles_across, tiles_down_ = tiles_down;
    const size_t tiles = size_t(tiles_across) * size_t(tiles_down);
    cells_.assign(tiles * kCells, 0.0f);
    least_.assign(tiles, 0.0f);
    unsettled_.assign(tiles, 0);
    floor_.assign(tiles, 0.0f);
    stamp_.assign(tiles, 0);
    cell_stamp_.assign(tiles, 0);
    generation_ = 0;
  }
  if (++generation_ == 0) {  // wrapped: every stamp would look current
    std::fill(stamp_.begin(), stamp_.end(), 0);
    std::fill(cell_stamp_.begin(), cell_stamp_.end(), 0);
    generation_ = 1;
  }
}

void OcclusionBuffer::Chains::build(const std::vector<FixedPoint>& outline) {
  const size_t n = outline.size();
  size_t first = 0, last = 0;
  for (size_t i = 1; i < n; ++i) {
    if (outline[i].y < outline[first].y) first = i;
    if (outline[i].y > outline[last].y) last = i;
  }
  auto point = [&](size_t i) { return Vec2{double(outline[i].x) / kOne, double(outline[i].y) / kOne}; };
  side[0].clear(), side[1].clear();
  for (size_t i = first;; i = (i + 1) % n) {
    side[0].push_back(point(i));
    if (i == last) break;
  }
  for (size_t i = first;; i = (i + n - 1) % n) {
    side[1].push_back(point(i));
    if (i == last) break;
  }
  for (int k = 0; k < 2; ++k) {
    slope[k].clear();
    for (size_t i = 0; i + 1 < side[k].size(); ++i) {
      const Vec2 p = side[k][i], q = side[k][i + 1];
      slope[k].push_back(q.y != p.y ? (q.x - p.x) / (q.y - p.y) : 0);
    }
  }
  top = point(first).y, bottom = point(last).y;
}

void OcclusionBuffer::touch(size_t t) {
  if (stamp_[t] == generation_) return;
  least_[t] = 0;
  unsettled_[t] = 0;
  floor_[t] = 0;
  stamp_[t] = generation_;
}

void OcclusionBuffer::touch_cells(size_t t) {
  touch(t);
  if (cell_stamp_[t] == generation_) return;
  std::fill_n(cells_.begin() + std::ptrdiff_t(t * kCells), kCells, 0.0f);
  cell_stamp_[t] = generation_;
}

float OcclusionBuffer::least(size_t t) const {
  if (!unsettled_[t]) return least_[t];
  const int tx = int(t % size_t(tiles_across_)), ty = int(t / size_t(tiles_across_));
  const int cols = std::min(kTile, across_ - tx * kTile), rows = std::min(kTile, down_ - ty * kTile);
  const float* c = &cells_[t * kCells];
  float least = std::numeric_limits<float>::infinity();
  for (int r = 0; r < rows; ++r)
    for (int k = 0; k < cols; ++k) least = std::min(least, c[r * kTile + k]);
  least_[t] = least;
  unsettled_[t] = 0;
  return least;
}

bool OcclusionBuffer::inside_run(double l, double r, int& first, int& last) const {
  // Cell c's centres run from c·s + ½ to c·s + s − ½; grown by kInside they must lie in (l, r).
  const int s = per_side_;
  const double a = std::max(std::floor((l + kInside - 0.5) / s), 0.0);
  const double b = std::min(std::ceil((r - kInside - s + 0.5) / s), double(across_ - 1));
  if (!(a <= b)) return false;
  first = int(a), last = int(b);
  // The floor and ceiling above may be one off by rounding: settle the ends by the test itself.
  while (first <= last && !(first * s + 0.5 - kInside > l)) ++first;
  while (last >= first && !(last * s + s - 0.5 + kInside < r)) --last;
  return first <= last;
}

void OcclusionBuffer::cover(const std::vector<FixedPoint>& outline, const std::vector<FixedPoint>* clip,
                            int32_t clip_key, const RasterPlane& depth) {
  if (outline.size() < 3 || across_ == 0 || down_ == 0) return;
  const int s = per_side_;
  // The rows both the outline and the clip region reach.
  int64_t y0 = outline[0].y, y1 = y0;
  for (const FixedPoint& p : outline) y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  if (clip && clip->size() >= 3) {
    int64_t c0 = (*clip)[0].y, c1 = c0;
    for (const FixedPoint& p : *clip) c0 = std::min(c0, p.y), c1 = std::max(c1, p.y);
    y0 = std::max(y0, c0), y1 = std::min(y1, c1);
    if (y0 > y1) return;
  }
  const int r0 = int(std::clamp(std::floor(double(y0) / kOne / s), 0.0, double(down_ - 1)));
  const int r1 = int(std::clamp(std::floor(double(y1) / kOne / s), 0.0, double(down_ - 1)));
  shape_.build(outline);
  RowWalker shape(shape_);
  std::optional<RowWalker> region;
  if (clip && clip->size() >= 3) {
    // Many polygons share their avenue's clip region: its chains are made once a picture.
    if (clip_key < 0 || clip_key != region_key_ || region_generation_ != generation_) {
      region_.build(*clip);
      region_key_ = clip_key, region_generation_ = generation_;
    }
    region.emplace(region_);
  }
  // The interval of the outline and the clip region on the line at height y (ascending).
  auto interval = [&](double y, double& l, double& r) {
    double l2, r2;
    if (!shape.at(y, l, r)) return false;
    if (region) {
      if (!region->at(y, l2, r2)) return false;
      l = std::max(l, l2), r = std::min(r, r2);
    }
    return l < r;
  };
  // 1/Z's least over a rectangle of centres: at its corner against the plane's slope.
  // Stored a little below it (by more than a float's rounding, far less than the 1e-6 of
  // hides()), so that the float never says nearer than the plane is.
  constexpr double kBelow = 1 - 2.5e-7;
  auto least_over = [&depth](double left, double right, double top, double bottom) {
    return depth.at(depth.a >= 0 ? left : right, depth.b >= 0 ? top : bottom);
  };
  struct Row {
    bool top = false, bottom = false;  // the lines through its first and last centres meet it
    double lt = 0, rt = 0, lb = 0, rb = 0;
  };
  std::array<Row, kTile> rows;
  for (int ty = r0 / kTile; ty <= r1 / kTile; ++ty) {
    const size_t row_of_tiles = size_t(ty) * size_t(tiles_across_);
    const int tile_rows = std::min(kTile, down_ - ty * kTile);
    const int ra = std::max(r0, ty * kTile), rb = std::min(r1, ty * kTile + tile_rows - 1);
    // Each row's cells are those whose centres lie strictly inside the outline and the
    // region on the lines through its first and last rows of centres (both convex: the
    // corners of the centres' rectangle strictly inside).
    for (int r = ra; r <= rb; ++r) {
      Row& row = rows[size_t(r - ty * kTile)];
      row.top = interval(r * s + 0.5, row.lt, row.rt);
      if (s == 1) {  // one row of centres: one line
        row.bottom = row.top, row.lb = row.lt, row.rb = row.rt;
      } else {
        row.bottom = interval(r * s + s - 0.5, row.lb, row.rb);
      }
    }
    // Tiles the polygon covers whole take a floor, 1 value for 64 cells.
    int ta = 1, tb = 0, first, last;
    const Row &upper = rows[0], &lower = rows[size_t(tile_rows - 1)];
    if (ra == ty * kTile && rb == ty * kTile + tile_rows - 1 && upper.top && lower.bottom &&
        inside_run(std::max(upper.lt, lower.lb), std::min(upper.rt, lower.rb), first, last)) {
      ta = (first + kTile - 1) / kTile;
      tb = (last + 1) / kTile - 1;
      if (last == across_ - 1) tb = last / kTile;  // the raster's last tile, perhaps narrower
    }
    for (int tx = ta; tx <= tb; ++tx) {
      const size_t t = row_of_tiles + size_t(tx);
      const int cols = std::min(kTile, across_ - tx * kTile);
      const double v = least_over(tx * kTile * s + 0.5, (tx * kTile + cols) * s - 0.5, ty * kTile * s + 0.5,
                                  (ty * kTile + tile_rows) * s - 0.5);
      if (!(v > 0)) continue;
      touch(t);
      floor_[t] = std::max(floor_[t], float(v * kBelow));
    }
    // The cells of the rest, row by row.
    for (int r = ra; r <= rb; ++r) {
      const Row& row = rows[size_t(r - ty * kTile)];
      if (!row.top || !row.bottom ||
          !inside_run(std::max(row.lt, row.lb), std::min(row.rt, row.rb), first, last))
        continue;
      const double top = r * s + 0.5, bottom = r * s + s - 0.5;
      for (int c = first; c <= last; ++c) {
        const int tx = c / kTile;
        if (tx >= ta && tx <= tb) {  // a whole tile: jump past the run of them
          c = std::min(last, (tb + 1) * kTile - 1);
          continue;
        }
        const double v = least_over(c * s + 0.5, c * s + s - 0.5, top, bottom);
        if (!(v > 0)) continue;
        const size_t t = row_of_tiles + size_t(tx);
        touch_cells(t);
        float& cell = cells_[t * kCells + size_t((r % kTile) * kTile + c % kTile)];
        cell = std::max(cell, float(v * kBelow));
        unsettled_[t] = 1;
      }
    }
  }
}

bool OcclusionBuffer::cells_above(size_t t, int c0, int c1, int r0, int r1, double need) const {
  const float* c = &cells_[t * kCells];
  for (int r = r0; r <= r1; ++r)
    for (int k = c0; k <= c1; ++k)
      if (!(double(c[r * kTile + k]) > need)) return false;
  return true;
}

bool OcclusionBuffer::hides(Vec2 lo, Vec2 hi, double inv_z) const {
  if (across_ == 0 || !(inv_z > 0) || !std::isfinite(inv_z)) return false;
  // The outline may reach past the box by its rounding (1/512 of a sample); 1/64 is ample.
  constexpr double reach = 1.0 / 64;
  const int s = per_side_;
  int i0, i1, j0, j1;
  samples_in(lo.x - reach, hi.x + reach, across_ * s, i0, i1);
  samples_in(lo.y - reach, hi.y + reach, down_ * s, j0, j1);
  if (i0 > i1 || j0 > j1) return true;
  const int c0 = i0 / s, c1 = i1 / s, r0 = j0 / s, r1 = j1 / s;
  const double need = inv_z * (1 + 1e-6);
  for (int ty = r0 / kTile; ty <= r1 / kTile; ++ty) {
    for (int tx = c0 / kTile; tx <= c1 / kTile; ++tx) {
      const size_t t = size_t(ty) * size_t(tiles_across_) + size_t(tx);
      if (stamp_[t] != generation_) return false;  // nothing drawn there yet
      if (double(floor_[t]) > need) continue;       // covered whole by something nearer
      // The box's cells in this tile, in the tile's own numbering.
      const int k0 = std::max(c0 - tx * kTile, 0), k1 = std::min(c1 - tx * kTile, kTile - 1);
      const int q0 = std::max(r0 - ty * kTile, 0), q1 = std::min(r1 - ty * kTile, kTile - 1);
      const bool whole = k0 == 0 && k1 == std::min(kTile, across_ - tx * kTile) - 1 && q0 == 0 &&
                         q1 == std::min(kTile, down_ - ty * kTile) - 1;
      if (cell_stamp_[t] != generation_) return false;  // its cells hold nothing beyond the floor
      if (whole ? !(double(least(t)) > need) : !cells_above(t, k0, k1, q0, q1, need)) return false;
    }
  }
  return true;
}

long OcclusionBuffer::covered() const {
  long n = 0;
  for (size_t t = 0; t < stamp_.size(); ++t) {
    if (stamp_[t] != generation_) continue;
    if (cell_stamp_[t] != generation_) {
      if (floor_[t] > 0) n += long(std::min(kTile, across_ - int(t % size_t(tiles_across_)) * kTile)) *
                               long(std::min(kTile, down_ - int(t / size_t(tiles_across_)) * kTile));
      continue;
    }
    const int tx = int(t % size_t(tiles_across_)), ty = int(t / size_t(tiles_across_));
    const int cols = std::min(kTile, across_ - tx * kTile), rows = std::min(kTile, down_ - ty * kTile);
    for (int r = 0; r < rows; ++r)
      for (int k = 0; k < cols; ++k) n += std::max(cells_[t * kCells + size_t(r * kTile + k)], floor_[t]) > 0;
  }
  return n;
}

}  // namespace avenues

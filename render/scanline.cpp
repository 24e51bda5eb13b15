// Avenues — the scanline engine (see scanline.h for the passes and the conventions).
#include "render/scanline.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace avenues {

namespace {

constexpr int64_t kHalf = kSubpixelOne / 2;  ///< a sample centre's offset from its corner

/// Floor and ceiling of a / b for b > 0, in integers.
int64_t floor_div(int64_t a, int64_t b) { return a / b - ((a % b != 0) && (a < 0)); }
int64_t ceil_div(int64_t a, int64_t b) { return -floor_div(-a, b); }

/// First row whose sample centre y = row + ½ lies at or below the fixed-point y.
int32_t first_row_at_or_below(int64_t y) { return int32_t(ceil_div(y - kHalf, kSubpixelOne)); }

/// Twice the signed area of an outline, exactly: in 128 bits, where no sum of products of
/// coordinates (each below 2^29) can overflow.
__extension__ typedef __int128 Wide;
Wide area2(const std::vector<FixedPoint>& v) {
  Wide a = 0;
  for (size_t i = 0, n = v.size(); i < n; ++i) {
    const FixedPoint p = v[i], q = v[(i + 1) % n];
    a += Wide(p.x) * q.y - Wide(q.x) * p.y;
  }
  return a;
}

}  // namespace

int orientation(const std::vector<FixedPoint>& outline) {
  const Wide a = area2(outline);
  return a > 0 ? 1 : a < 0 ? -1 : 0;
}

void ScanCounters::add(const ScanCounters& o) {
  scanlines += o.scanlines;
  intersections += o.intersections;
  spans += o.spans;
  implicit_lines += o.implicit_lines;
  depth_sorts += o.depth_sorts;
  depth_comparisons += o.depth_comparisons;
  active_max = std::max(active_max, o.active_max);
}

// --- the edge table ------------------------------------------------------------------

EdgeTable::EdgeTable(int width, int height, const std::vector<ScreenPolygon>& polygons,
                     const std::vector<ClipRegion>& clips) {
  build(width, height, polygons, clips);
}

void EdgeTable::build(int width, int height, const std::vector<ScreenPolygon>& polygons,
                      const std::vector<ClipRegion>& clips) {
  width_ = width;
  height_ = height;
  polygons_ = &polygons;
  clip_count_ = clips.size();
  edges_.clear();
  constexpr int64_t kFar = int64_t(1) << 62;
  // A clip region is empty outside its rows and its box, so the polygons it cuts need no
  // edges there.
  struct Box {
    Rows rows;
    int64_t x_lo, x_hi;
  };
  std::vector<Box> boxes(clips.size());
  // A region no polygon refers to cuts nothing (a view resolved by depth drops every piece
  // of a cell that lies behind what is drawn, but keeps its mask's region): its edges would
  // only be stepped from row to row.
  std::vector<uint8_t> cuts(clips.size(), 0);
  for (const ScreenPolygon& poly : polygons)
    if (poly.clip >= 0) cuts[size_t(poly.clip)] = 1;
  for (size_t k = 0; k < clips.size(); ++k) {
    if (!cuts[k]) continue;
    boxes[k].rows = add_outline(clips[k].outline, int32_t(k), true, {0, height}, -kFar, kFar);
    boxes[k].x_lo = kFar;
    boxes[k].x_hi = -kFar;
    for (FixedPoint v : clips[k].outline) {
      boxes[k].x_lo = std::min(boxes[k].x_lo, v.x);
      boxes[k].x_hi = std::max(boxes[k].x_hi, v.x);
    }
  }
  polygon_rows_.assign(polygons.size(), Rows{});
  for (size_t p = 0; p < polygons.size(); ++p) {
    const ScreenPolygon& poly = polygons[p];
    Box box{{0, height}, 0, int64_t(width) * kSubpixelOne};  // the window
    if (poly.clip >= 0) {
      const Box& c = boxes[size_t(poly.clip)];
      box = {c.rows, std::max(box.x_lo, c.x_lo), std::min(box.x_hi, c.x_hi)};
    }
    int64_t x_lo = kFar, x_hi = -kFar;
    for (FixedPoint v : poly.outline) {
      x_lo = std::min(x_lo, v.x);
      x_hi = std::max(x_hi, v.x);
    }
    if (x_hi <= box.x_lo || x_lo >= box.x_hi) continue;  // wholly beside its region: never seen
    polygon_rows_[p] = add_outline(poly.outline, int32_t(p), false, box.rows, box.x_lo, box.x_hi);
  }
  polygon_clip_.assign(polygons.size(), -1);
  for (size_t p = 0; p < polygons.size(); ++p) polygon_clip_[p] = polygons[p].clip;
  // Bouknight's Appendix 1: a card sort into one bin per row, then the bins in row order;
  // the same for the polygons (Wylie's y-entry table).
  row_start_.assign(size_t(height) + 1, 0);
  for (const Edge& e : edges_) ++row_start_[size_t(e.first_row) + 1];
  for (int r = 0; r < height; ++r) row_start_[size_t(r) + 1] += row_start_[size_t(r)];
  std::vector<int32_t> fill(row_start_.begin(), row_start_.end() - 1);
  unsorted_.swap(edges_);
  edges_.resize(unsorted_.size());
  for (const Edge& e : unsorted_) edges_[size_t(fill[size_t(e.first_row)]++)] = e;
  polygon_row_start_.assign(size_t(height) + 1, 0);
  for (const Rows& r : polygon_rows_)
    if (r.first < r.end) ++polygon_row_start_[size_t(r.first) + 1];
  for (int r = 0; r < height; ++r) polygon_row_start_[size_t(r) + 1] += polygon_row_start_[size_t(r)];
  fill.assign(polygon_row_start_.begin(), polygon_row_start_.end() - 1);
  polygon_order_.resize(size_t(polygon_row_start_.back()));
  polygons_ending_.assign(size_t(height) + 1, 0);
  for (size_t p = 0; p < polygon_rows_.size(); ++p)
    if (polygon_rows_[p].first < polygon_rows_[p].end) {
      polygon_order_[size_t(fill[size_t(polygon_rows_[p].first)]++)] = int32_t(p);
      ++polygons_ending_[size_t(polygon_rows_[p].end)];
    }
}

EdgeTable::Rows EdgeTable::add_outline(const std::vector<FixedPoint>& v, int32_t owner, bool clip, Rows within,
                                       int64_t x_lo, int64_t x_hi) {
  const size_t n = v.size();
  Rows rows{within.end, within.first};
  if (n < 3) return rows;
  const Wide a = area2(v);
  if (a == 0) return rows;  // no area: seen edge-on
  for (size_t i = 0; i < n; ++i) {
    const FixedPoint p = v[i], q = v[(i + 1) % n];
    if (p.y == q.y) continue;  // horizontal: the half-open rows of its neighbours bound it
    const bool down = q.y > p.y;
    const FixedPoint top = down ? p : q, bottom = down ? q : p;
    Edge e;
    e.x0 = top.x;
    e.y0 = top.y;
    e.dx = bottom.x - top.x;
    e.dy = bottom.y - top.y;
    e.first_row = std::max(first_row_at_or_below(top.y), within.first);
    e.end_row = std::min(first_row_at_or_below(bottom.y), within.end);
    if (e.first_row >= e.end_row) continue;  // crosses no sample centre in the window
    rows = {std::min(rows.first, e.first_row), std::max(rows.end, e.end_row)};
    e.owner = owner;
    e.clip = clip;
    // The interior lies left of each directed edge when the signed area is positive
    // (x right, y down): an edge running down the raster then bounds it on the right.
    e.left = (a > 0) != down;
    if (e.left ? std::max(p.x, q.x) <= x_lo : std::min(p.x, q.x) >= x_hi) continue;  // cannot matter
    edges_.push_back(e);
  }
  return rows;
}

// --- the scan ------------------------------------------------------------------------

namespace {
constexpr int32_t kNoSpan = INT32_MAX;  ///< span key of a polygon with nothing on this row
constexpr int64_t kUnbounded = int64_t(1) << 62;
}  // namespace

ScanlineEngine::ScanlineEngine(const EdgeTable& table, bool implicit_lines) { reset(table, implicit_lines); }

void ScanlineEngine::reset(const EdgeTable& table, bool implicit_lines) {
  table_ = &table;
  polygons_ = table.polygons_;
  implicit_lines_ = implicit_lines;
  const size_t n = polygons_->size();
  polygon_extent_.assign(n, Extent{});
  clip_extent_.assign(table.clip_count_, Extent{});
  span_left_.assign(n, kNoSpan);
  span_right_.assign(n, kNoSpan);
  inside_at_.assign(n, -1);
  row_ = 0;
  active_.clear();
  on_row_.clear();
  ends_.clear();
  coverage_.clear();
  inside_.clear();
  objects_.clear();
  out_ = nullptr;
  row_spans_.clear();
  row_centre_ = 0.5;
  repeats_ = repeated_ = depth_free_ = seen_known_ = same_order_ = false;
  counters_ = {};
}

void ScanlineEngine::enter(const EdgeTable::Edge& e, int row) {
  // The crossing with row r is the first sample i with i + ½ >= x(r + ½), i.e.
  //   i = ceil(num / den),  num = (x0 − ½)·dy + (y − y0)·dx,  den = 256·dy,
  // in fixed-point units; each row down adds 256·dx to num.
  ActiveEdge a;
  const int64_t y = int64_t(row) * kSubpixelOne + kHalf;
  const int64_t num = (e.x0 - kHalf) * e.dy + (y - e.y0) * e.dx;
  a.den = kSubpixelOne * e.dy;
  a.crossing = ceil_div(num, a.den);
  a.remainder = a.crossing * a.den - num;
  const int64_t step = kSubpixelOne * e.dx;
  a.step_q = floor_div(step, a.den);
  a.step_r = step - a.step_q * a.den;
  a.end_row = e.end_row;
  a.owner = e.owner;
  a.clip = e.clip;
  a.left = e.left;
  active_.push_back(a);
}

void ScanlineEngine::enter_polygon(int32_t p) {
  span_left_[size_t(p)] = span_right_[size_t(p)] = kNoSpan;
  on_row_.push_back(p);
}

void ScanlineEngine::start(int row) {
  active_.clear();
  for (int32_t p : on_row_) span_left_[size_t(p)] = span_right_[size_t(p)] = kNoSpan;
  on_row_.clear();
  ends_.clear();
  row_ = row;
  repeats_ = repeated_ = depth_free_ = seen_known_ = same_order_ = false;
  if (row < 0 || row >= table_->height_) return;
  // Bouknight's bin of lines starting below the window, generalised to any first row:
  // every edge (and polygon) that began above this row and still crosses it, then this
  // row's bin.
  const int32_t through = table_->row_start_[size_t(row) + 1];
  for (int32_t i = 0; i < through; ++i)
    if (table_->edges_[size_t(i)].end_row > row) enter(table_->edges_[size_t(i)], row);
  const int32_t polys = table_->polygon_row_start_[size_t(row) + 1];
  for (int32_t i = 0; i < polys; ++i) {
    const int32_t p = table_->polygon_order_[size_t(i)];
    if (table_->polygon_rows_[size_t(p)].end > row) enter_polygon(p);
  }
}

void ScanlineEngine::touch(Extent& x, const ActiveEdge& a) {
  if (x.row != row_) {
    x.row = row_;
    x.has_left = x.has_right = false;
  }
  if (a.left) {
    x.left = x.has_left ? std::max(x.left, a.crossing) : a.crossing;
    x.has_left = true;
  } else {
    x.right = x.has_right ? std::min(x.right, a.crossing) : a.crossing;
    x.has_right = true;
  }
}

const SpanRow& ScanlineEngine::scan() {
  repeated_ = repeats_;
  if (repeated_) {  // the row above again: its spans, kept in row_spans_
    count_row();
  } else {
    row_spans_.clear();
    out_ = &row_spans_;
    extents_of_row();
    spans_of_polygons(true);
    const long sorts = counters_.depth_sorts;
    walk();
    depth_free_ = counters_.depth_sorts == sorts;
    seen_known_ = depth_free_;
  }
  counters_.spans += long(row_spans_.size());
  next_row();
  return row_spans_;
}

void ScanlineEngine::scan_coverage() {
  repeated_ = repeats_;
  if (repeated_) {
    count_row();
    next_row();
    return;
  }
  extents_of_row();
  spans_of_polygons(false);
  depth_free_ = true;
  next_row();
}

void ScanlineEngine::count_row() {
  if (active_.empty()) return;
  ++counters_.scanlines;
  counters_.intersections += long(active_.size());
  counters_.active_max = std::max(counters_.active_max, int(active_.size()));
}

void ScanlineEngine::extents_of_row() {
  row_centre_ = row_ + 0.5;
  count_row();
  for (const ActiveEdge& a : active_) touch(a.clip ? clip_extent_[size_t(a.owner)] : polygon_extent_[size_t(a.owner)], a);
}

void ScanlineEngine::spans_of_polygons(bool sort) {
  // Each polygon's span [L, R): right of its left edges, left of its right edges (no edge
  // on a side: unbounded there), cut by its clip region and the window.
  const int64_t width = table_->width_;
  coverage_.clear();
  entering_.clear();
  for (int32_t p : on_row_) {
    const Extent& x = polygon_extent_[size_t(p)];
    const bool mine = x.row == row_;
    int64_t l = mine && x.has_left ? x.left : -kUnbounded;
    int64_t r = mine && x.has_right ? x.right : kUnbounded;
    const int32_t clip = table_->polygon_clip_[size_t(p)];
    if (clip >= 0) {
      const Extent& c = clip_extent_[size_t(clip)];
      if (c.row == row_ && c.has_left && c.has_right) {
        l = std::max(l, c.left);
        r = std::min(r, c.right);
      } else {
        r = l;  // the clip region has nothing on this row
      }
    }
    l = std::max<int64_t>(l, 0);
    r = std::min<int64_t>(r, width);
    if (l < r) {
      if (span_left_[size_t(p)] == kNoSpan) entering_.push_back(p);
      span_left_[size_t(p)] = int32_t(l);
      span_right_[size_t(p)] = int32_t(r);
      coverage_.push_back({int32_t(l), int32_t(r), p});
    } else {
      span_left_[size_t(p)] = span_right_[size_t(p)] = kNoSpan;
    }
  }
  if (!sort) return;
  // The span ends in scan order, as one list of words (x, leaves before enters, polygon):
  // a total order, so the list is the same however it is sorted, and at equal x a polygon
  // left comes before one entered (Bouknight). The list was in order on the row above and
  // spans move little from row to row, so an insertion sort of the ends that go on, each
  // at its new x, has next to nothing to do (Bouknight sorts his active list anew each
  // scanline; coherence makes it cheap). Ends new on this row are sorted among themselves
  // and merged in: the intersection of a polygon, its clip region and the window is convex,
  // so each polygon's span begins and ends once, but where thousands of spans do, inserting
  // each one by one would be quadratic. A row whose order changed a lot (a bound on the
  // shifts) is sorted afresh.
  size_t kept = 0;
  for (const uint64_t end : ends_) {
    const int32_t p = end_polygon(end);
    if (span_left_[size_t(p)] == kNoSpan) continue;  // no span on this row
    const bool enters = end_enters(end);
    ends_[kept++] = span_end(enters ? span_left_[size_t(p)] : span_right_[size_t(p)], enters, p);
  }
  same_order_ = kept == ends_.size() && entering_.empty();
  ends_.resize(kept);
  size_t shifts = 0;
  const size_t shift_limit = 4 * ends_.size() + 64;
  for (size_t i = 1; i < ends_.size(); ++i) {
    const uint64_t end = ends_[i];
    size_t j = i;
    for (; j > 0 && end < ends_[j - 1]; --j) ends_[j] = ends_[j - 1];
    ends_[j] = end;
    shifts += i - j;
    if (shifts > shift_limit) {
      std::sort(ends_.begin(), ends_.end());
      break;
    }
  }
  same_order_ = same_order_ && shifts == 0;
  if (entering_.empty()) return;
  entering_ends_.clear();
  for (const int32_t p : entering_) {
    entering_ends_.push_back(span_end(span_left_[size_t(p)], true, p));
    entering_ends_.push_back(span_end(span_right_[size_t(p)], false, p));
  }
  std::sort(entering_ends_.begin(), entering_ends_.end());
  merged_.resize(ends_.size() + entering_ends_.size());
  std::merge(ends_.begin(), ends_.end(), entering_ends_.begin(), entering_ends_.end(), merged_.begin());
  ends_.swap(merged_);
}

inline void ScanlineEngine::emit(int32_t x0, int32_t x1, int32_t polygon) {
  if (x0 >= x1) return;
  if (!out_->empty() && out_->back().polygon == polygon && out_->back().x1 == x0) {
    out_->back().x1 = x1;
    return;
  }
  out_->push_back({x0, x1, polygon});
}

void ScanlineEngine::walk() {
  // Left to right through the span ends (in order: at equal x, polygons left before
  // polygons entered). Between two ends the set of polygons the ray is in is fixed:
  // resolve it there.
  const int32_t width = table_->width_;
  const size_t n = ends_.size();
  // The ends in the order of the row before, which was resolved without depth: the ray is
  // in the same polygons after each end as it was there, so the same one is seen. Where
  // an end begins a run that was empty on the row before, it was not resolved: walk.
  if (same_order_ && seen_known_) {
    size_t i = 0;
    int32_t x = 0;
    bool known = true;
    while (x < width && known) {
      while (i < n && end_x(ends_[i]) <= x) ++i;
      const int32_t next = i < n ? std::min(end_x(ends_[i]), width) : width;
      const int32_t seen = i == 0 ? -1 : seen_after_[i - 1];
      known = seen != kUnresolved;
      if (known) emit(x, next, seen);
      x = next;
    }
    if (known) return;
    out_->clear();
  }
  seen_after_.assign(n, kUnresolved);
  size_t i = 0;
  int32_t x = 0;
  while (x < width) {
    for (; i < n && end_x(ends_[i]) <= x; ++i) {
      const int32_t p = end_polygon(ends_[i]);
      if (end_enters(ends_[i])) {
        inside_at_[size_t(p)] = int32_t(inside_.size());
        inside_.push_back(p);
      } else {
        const int32_t at = inside_at_[size_t(p)];
        const int32_t last = inside_.back();
        inside_[size_t(at)] = last;
        inside_at_[size_t(last)] = at;
        inside_.pop_back();
        inside_at_[size_t(p)] = -1;
      }
    }
    const int32_t next = i < n ? std::min(end_x(ends_[i]), width) : width;
    // One polygon or none: nothing to resolve (most runs), and no call.
    if (inside_.size() <= 1) emit(x, next, inside_.empty() ? -1 : inside_[0]);
    else resolve(x, next);
    if (i > 0) seen_after_[i - 1] = out_->back().polygon;  // (resolved with depth: not kept, below)
    x = next;
  }
  for (int32_t p : inside_) inside_at_[size_t(p)] = -1;
  inside_.clear();
}

void ScanlineEngine::next_row() {
  // Down a row: drop the edges that end, step the others exactly, let the new ones in;
  // the same for the polygons.
  // Stepped in place: only the crossing and its remainder change. An edge is moved
  // down the list only when one before it has ended.
  // Whether anything moves: if no edge ends, begins or steps to another sample, no polygon
  // ends or begins, and the row was resolved without depth, the next row is this one again.
  size_t kept = 0;
  const size_t n = active_.size();
  int64_t moved = 0;
  for (size_t i = 0; i < n; ++i) {
    ActiveEdge& a = active_[i];
    if (a.end_row <= row_ + 1) continue;
    const int64_t over = a.step_r - a.remainder;
    const int64_t step = a.step_q + (over > 0);
    a.crossing += step;
    a.remainder = over > 0 ? a.den - over : -over;
    moved |= step;
    if (kept != i) active_[kept] = a;
    ++kept;
  }
  bool changed = moved != 0 || kept != n;
  active_.resize(kept);
  ++row_;
  if (row_ <= table_->height_ && table_->polygons_ending_[size_t(row_)] > 0) {
    changed = true;
    auto ended = [&](int32_t p) {
      if (table_->polygon_rows_[size_t(p)].end > row_) return false;
      span_left_[size_t(p)] = span_right_[size_t(p)] = kNoSpan;  // out of the sorted lists on the next row
      return true;
    };
    on_row_.erase(std::remove_if(on_row_.begin(), on_row_.end(), ended), on_row_.end());
  }
  repeats_ = false;
  if (row_ >= table_->height_) return;
  const int32_t edges = table_->row_start_[size_t(row_)], edges_end = table_->row_start_[size_t(row_) + 1];
  const int32_t polys = table_->polygon_row_start_[size_t(row_)], polys_end = table_->polygon_row_start_[size_t(row_) + 1];
  repeats_ = !changed && edges == edges_end && polys == polys_end && depth_free_;
  for (int32_t i = edges; i < edges_end; ++i) enter(table_->edges_[size_t(i)], row_);
  for (int32_t i = polys; i < polys_end; ++i) enter_polygon(table_->polygon_order_[size_t(i)]);
}

namespace {

/// Among faces, the deepest avenue's is seen; ties (only where rounding lets two avenues
/// of one depth overlap) go to the earlier avenue, then the earlier polygon.
bool deeper_face(const std::vector<ScreenPolygon>& polys, int32_t p, int32_t q) {
  if (q < 0) return true;
  const ScreenPolygon &a = polys[size_t(p)], &b = polys[size_t(q)];
  if (a.rank != b.rank) return a.rank > b.rank;
  if (a.group != b.group) return a.group < b.group;
  return p < q;
}

}  // namespace

void ScanlineEngine::resolve(int32_t x0, int32_t x1) {
  int32_t deepest_face = -1;
  objects_.clear();
  for (int32_t p : inside_) {
    if ((*polygons_)[size_t(p)].role == PolygonRole::Object) objects_.push_back(p);
    else if (deeper_face(*polygons_, p, deepest_face)) deepest_face = p;
  }
  if (objects_.empty()) return emit(x0, x1, deepest_face);
  // Objects by avenue, nearest avenue (fewest portals) first.
  std::sort(objects_.begin(), objects_.end(), [&](int32_t p, int32_t q) {
    const ScreenPolygon &a = (*polygons_)[size_t(p)], &b = (*polygons_)[size_t(q)];
    if (a.rank != b.rank) return a.rank < b.rank;
    if (a.group != b.group) return a.group < b.group;
    return p < q;
  });
  if (candidates_.size() < objects_.size() + 1) candidates_.resize(objects_.size() + 1);
  resolve_groups(x0, x1, 0, deepest_face, 0);
}

void ScanlineEngine::resolve_groups(int32_t x0, int32_t x1, size_t first, int32_t deepest_face, int level) {
  if (first == objects_.size()) return emit(x0, x1, deepest_face);
  const int32_t group = (*polygons_)[size_t(objects_[first])].group;
  size_t last = first;
  while (last < objects_.size() && (*polygons_)[size_t(objects_[last])].group == group) ++last;
  // The candidates: this avenue's objects and its face (the depth bound of its cell).
  OwnLines<int32_t>& cands = candidates_[size_t(level)];
  cands.assign(objects_.begin() + std::ptrdiff_t(first), objects_.begin() + std::ptrdiff_t(last));
  int32_t face = -1;
  for (int32_t p : inside_) {
    const ScreenPolygon& poly = (*polygons_)[size_t(p)];
    if (poly.role == PolygonRole::Face && poly.group == group && deeper_face(*polygons_, p, face)) face = p;
  }
  if (face >= 0) cands.push_back(face);
  // An object seen is final; where the cell's face is nearest, the ray leaves the cell and
  // the deeper avenues decide.
  auto take = [&](int32_t s0, int32_t s1, int32_t winner) {
    if ((*polygons_)[size_t(winner)].role == PolygonRole::Object) emit(s0, s1, winner);
    else resolve_groups(s0, s1, last, deepest_face, level + 1);
  };
  if (cands.size() == 1) return take(x0, x1, cands[0]);
  if (!implicit_lines_) return take(x0, x1, nearest(cands, x0));  // no interpenetration: one order all along
  // Bouknight: depth sort at the left end of the run; while some polygon is nearer than
  // the current one at the right end, an implicitly defined line lies between — split at
  // the first such crossing (Appendix 2) and carry on from there.
  int32_t start = x0;
  const int32_t last_x = x1 - 1;
  int32_t cur = nearest(cands, start);
  while (start < last_x) {
    ++counters_.depth_sorts;
    int32_t next = -1, at = x1;
    for (int32_t q : cands) {
      if (q == cur) continue;
      ++counters_.depth_comparisons;
      if (!(nearer_by(q, cur, last_x) > 0)) continue;
      const int32_t p = first_nearer(q, cur, start, last_x);
      bool sooner = p < at;
      if (p == at) {  // two lines cross the row at one sample: the nearer polygon there
        ++counters_.depth_comparisons;
        sooner = nearer_by(q, next, p) > 0;
      }
      if (sooner) {
        next = q;
        at = p;
      }
    }
    if (next < 0) break;
    take(start, at, cur);
    ++counters_.implicit_lines;
    cur = next;
    start = at;
  }
  take(start, x1, cur);
}

double ScanlineEngine::nearer_by(int32_t p, int32_t q, int32_t x) const {
  // 1/Z(p) − 1/Z(q) at the centre of sample x, as one affine function of x evaluated the
  // same way every time: monotonic along the row, and exactly antisymmetric in (p, q).
  const RasterPlane &a = (*polygons_)[size_t(p)].depth, &b = (*polygons_)[size_t(q)].depth;
  return (a.a - b.a) * (x + 0.5) + ((a.b - b.b) * row_centre_ + (a.c - b.c));
}

int32_t ScanlineEngine::nearest(const OwnLines<int32_t>& cands, int32_t x) {
  ++counters_.depth_sorts;
  int32_t best = cands[0];
  for (size_t i = 1; i < cands.size(); ++i) {
    ++counters_.depth_comparisons;
    const double d = nearer_by(cands[i], best, x);
    if (d > 0 || (d == 0 && cands[i] < best)) best = cands[i];
  }
  return best;
}

int32_t ScanlineEngine::first_nearer(int32_t q, int32_t cur, int32_t from, int32_t last) const {
  // Appendix 2: the planes meet where (A1 − A2)·x = (B2 − B1)·y + (C2 − C1); that is the
  // estimate, and the sign of nearer_by (monotonic) settles the sample exactly.
  const RasterPlane &a = (*polygons_)[size_t(q)].depth, &b = (*polygons_)[size_t(cur)].depth;
  const double slope = a.a - b.a;
  const double offset = (a.b - b.b) * row_centre_ + (a.c - b.c);
  int32_t p = from + 1;
  if (slope > 0) {
    const double x = std::floor(-offset / slope - 0.5) + 1;  // first sample centre past the meeting
    if (std::isfinite(x)) p = int32_t(std::clamp(x, double(from + 1), double(last)));
  }
  while (p > from + 1 && nearer_by(q, cur, p - 1) > 0) --p;
  while (p < last && !(nearer_by(q, cur, p) > 0)) ++p;
  return p;
}

// --- the secondary scan -------------------------------------------------------------

SecondaryScan::SecondaryScan(const EdgeTable& pieces) { reset(pieces); }

void SecondaryScan::reset(const EdgeTable& pieces) {
  engine_.reset(pieces);
  spans_.assign(pieces.polygons_->size(), Span{});
  row_of_.assign(spans_.size(), -1);
  moved_on_.assign(spans_.size(), -1);
  row_ = -1;
  next_ = 0;
}

void SecondaryScan::start(int row) {
  engine_.start(row);
  next_ = row;
}

void SecondaryScan::scan() {
  engine_.scan_coverage();
  row_ = next_++;
  for (const Span& sp : engine_.coverage()) {
    const size_t i = size_t(sp.polygon);
    if (row_of_[i] != row_ - 1 || spans_[i].x0 != sp.x0 || spans_[i].x1 != sp.x1) moved_on_[i] = row_;
    spans_[i] = sp;
    row_of_[i] = row_;
  }
}

bool SecondaryScan::unmoved(int32_t piece) const {
  const size_t i = size_t(piece);
  if (row_of_[i] == row_) return moved_on_[i] != row_;  // on this row: as on the row before?
  return row_of_[i] != row_ - 1;                        // not on this row, nor on the row before
}

}  // namespace avenues

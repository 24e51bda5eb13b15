// Avenues — clipping a segment by half-spaces, along the segment (internal to render/).
//
// Every cut a drawing makes — the near plane, the edges of a mask, the faces of a cell,
// Crow's cones of closer polygons — is a half-space f(P) >= 0 with f affine in P. Along a
// segment P(t) = P0 + t·(P1 − P0), f is affine in t, so what is kept is one interval,
// found from f's values at the two ends alone: t* = f0 / (f0 − f1). A mask edge on the
// picture plane, a·x + b·y + c >= 0 with x = X/Z, y = Y/Z, is such a half-space too once
// multiplied by Z > 0: a·X + b·Y + c·Z >= 0. So clipping happens in picture-plane terms
// but parametrically along the 3D segment, and every endpoint drawn is a point of the
// original line at one computed parameter (Jones 1971: "a candidate line can only
// intersect the mask outline twice, and the visible segment ... can be readily determined").
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include <boost/sort/spreadsort/integer_sort.hpp>

namespace avenues::detail {

/// A parameter interval [t0, t1] along a segment; empty unless t0 < t1.
struct Interval {
  double t0 = 0, t1 = 1;
};

/// Keeps the part of `s` where f >= 0, f affine along the segment with f(0) = f0 and
/// f(1) = f1 (any parameterisation in which `s` is given). False when nothing is left.
inline bool clip_interval(Interval& s, double f0, double f1) {
  if (f0 >= 0 && f1 >= 0) return s.t0 < s.t1;
  if (!(f0 >= 0) && !(f1 >= 0)) return false;
  const double t = f0 / (f0 - f1);
  if (f0 < 0) s.t0 = std::max(s.t0, t);
  else s.t1 = std::min(s.t1, t);
  return s.t0 < s.t1;
}

/// An interval of the line or edge with id `key`.
struct KeyedInterval {
  int32_t key;
  Interval interval;
};

/// Sorts by (key, t0) and merges, per key, intervals that overlap or touch (gap <= `touch`):
/// a line seen through several avenues, or lying on several cells, becomes disjoint pieces.
/// (Boost's spreadsort, a radix sort, by key (ids, never negative); then each key's few
/// intervals by t0.)
inline void merge_intervals(std::vector<KeyedInterval>& v, double touch) {
  boost::sort::spreadsort::integer_sort(
      v.begin(), v.end(), [](const KeyedInterval& x, unsigned shift) { return x.key >> shift; },
      [](const KeyedInterval& a, const KeyedInterval& b) { return a.key < b.key; });
  for (size_t i = 0; i < v.size();) {
    size_t j = i + 1;
    while (j < v.size() && v[j].key == v[i].key) ++j;
    if (j - i > 1)
      std::sort(v.begin() + std::ptrdiff_t(i), v.begin() + std::ptrdiff_t(j),
                [](const KeyedInterval& a, const KeyedInterval& b) { return a.interval.t0 < b.interval.t0; });
    i = j;
  }
  size_t out = 0;
  for (size_t i = 0; i < v.size(); ++i) {
    if (out > 0 && v[out - 1].key == v[i].key && v[i].interval.t0 <= v[out - 1].interval.t1 + touch)
      v[out - 1].interval.t1 = std::max(v[out - 1].interval.t1, v[i].interval.t1);
    else
      v[out++] = v[i];
  }
  v.resize(out);
}

/// Removes `hidden` from sorted, disjoint `intervals`.
inline void subtract_interval(std::vector<Interval>& intervals, Interval hidden) {
  std::vector<Interval> out;
  out.reserve(intervals.size() + 1);
  for (const Interval& s : intervals) {
    if (hidden.t1 <= s.t0 || hidden.t0 >= s.t1) {
      out.push_back(s);
      continue;
    }
    if (s.t0 < hidden.t0) out.push_back({s.t0, hidden.t0});
    if (hidden.t1 < s.t1) out.push_back({hidden.t1, s.t1});
  }
  intervals.swap(out);
}

}  // namespace avenues::detail

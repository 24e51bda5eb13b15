// Avenues — the corners of a piece's boundary as its cell's footprint has them.
//
// Merging (merge.cpp) decides which pieces are convex and extrusion (extrude.cpp,
// footprint_of) turns their boundaries into footprints; both judge corners here, so that
// a piece merged as convex is convex as a footprint. Points of the exact triangulation a
// rounding apart (distinct in exact arithmetic, a few ulps apart once rounded) are one
// point: the side between them has a direction that is rounding noise, and a merge judged
// on it once accepted a corner that turned right once the noise was dropped (random plan
// 30396: a 1 mm wall bent back at 24°).
#include <cmath>
#include <limits>

#include "cells/passes.h"

namespace avenues::detail {

bool rounding_apart(Vec2 a, Vec2 b) {
  return std::fabs(a.x - b.x) + std::fabs(a.y - b.y) <= 1e-12 * (1 + std::fabs(a.x) + std::fabs(a.y));
}

void corners_of(const std::vector<Vec2>& ring, std::vector<Corner>& out, const std::vector<uint8_t>* made) {
  const size_t m = ring.size();
  out.assign(m, Corner::Repeat);
  // The nearest point before or after k that is not a rounding from ring[k].
  auto distinct = [&](size_t k, bool forward) {
    for (size_t j = 1; j < m; ++j) {
      const Vec2 q = ring[forward ? (k + j) % m : (k + m - j) % m];
      if (!rounding_apart(q, ring[k])) return q;
    }
    return ring[k];
  };
  for (size_t k = 0; k < m; ++k) {
    if (rounding_apart(ring[k], ring[(k + m - 1) % m])) continue;  // a repeat: its run's first stands for it
    const Vec2 a = distinct(k, false), b = ring[k], c = distinct(k, true);
    int turn = orientation(a, b, c);
    // Where a cut crossed an edge the point lies on both exactly: a turn there within its
    // rounding (far below a nanometre) is none.
    if (turn != 0 && made && (*made)[k] && dot(b - a, c - b) > 0) {
      const double off = std::fabs(cross(c - a, b - a)) / length(c - a);
      if (off <= 64 * std::numeric_limits<double>::epsilon() * (1 + std::fabs(b.x) + std::fabs(b.y))) turn = 0;
    }
    out[k] = turn > 0 ? Corner::Left : turn < 0 ? Corner::Right
             : dot(b - a, c - b) < 0 ? Corner::Reversal : Corner::Straight;
  }
}

const std::vector<uint8_t>* ring_of(const Triangulation& T, const std::vector<int32_t>& half_edges,
                                    std::vector<Vec2>& ring, std::vector<uint8_t>& made) {
  ring.clear();
  made.clear();
  for (int32_t h : half_edges) ring.push_back(T.edge_from(h / 3, h % 3));
  if (T.cut_made.empty()) return nullptr;
  for (int32_t h : half_edges) made.push_back(T.cut_made[size_t(T.tri[size_t(h / 3)][size_t((h % 3 + 1) % 3)])]);
  return &made;
}

bool convex_footprint(const std::vector<Vec2>& ring, std::vector<Corner>& corners, std::vector<Vec2>& points,
                      const std::vector<uint8_t>* made) {
  corners_of(ring, corners, made);
  points.clear();
  for (size_t k = 0; k < ring.size(); ++k) {
    if (corners[k] == Corner::Right || corners[k] == Corner::Reversal) return false;
    if (corners[k] != Corner::Repeat) points.push_back(ring[k]);
  }
  // Every corner turns left or goes straight on; then the boundary is convex exactly when
  // it winds once, turning through 2π in all (one pinched at a point, or folded over
  // itself, winds twice or more). Each turn lies in [0, π), so the sum tells 2π from 4π
  // with room to spare for its rounding.
  const size_t n = points.size();
  if (n < 3) return false;  // every point one, or all on a line: no footprint
  double winding = 0;
  for (size_t k = 0; k < n; ++k) {
    const Vec2 d0 = points[k] - points[(k + n - 1) % n], d1 = points[(k + 1) % n] - points[k];
    winding += std::atan2(cross(d0, d1), dot(d0, d1));
  }
  return winding < 3 * 3.14159265358979323846;
}

}  // namespace avenues::detail

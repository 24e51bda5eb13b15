// Avenues — pass 3b of build_cells: cutting each band's free space afresh.
//
// One triangulation holds the outlines of every storey (pass 2), so that the bands' cells
// meet along its edges and stack on its triangles. In a band, though, the other storeys'
// corners are points inside free space, and their edges part it: the attic over a floor of
// rooms inherits every wall of that floor, and Hertel–Mehlhorn merging (pass 4), which only
// joins triangles, cannot take away a point that lies inside a region unless every
// triangle around it joins one convex piece. A house's open attic came out as 74 cells, 40
// of them slivers over the walls below and their corners; each is an avenue to every view
// that sees it.
//
// So each connected region of one class in each band is decomposed again from its own
// boundary only (triangulate_segments): Hertel–Mehlhorn merging of its own triangulation,
// or diagonals that take away its reflex corners (reflex_diagonals), whichever gives fewer
// pieces. Where that is fewer pieces than the region has now, its diagonals become cuts:
// constraints added to the one triangulation, across which that band's pieces are not
// merged. The edges between triangles of different classes are kept, so each triangle
// after lies where those before it agree, and takes their class. (A region cut into as
// many pieces keeps its cuts too where another band's cut may cross it, which could part
// it further.) The
// pieces between a band's cuts are each one convex region of triangles, which merging
// takes whole. Where a cut crosses an edge it makes a point on both, exactly, rounded
// once; a corner there within that rounding is straight (Triangulation::cut_made,
// corners_of), else every such crossing would part a piece again.
#include <algorithm>
#include <cmath>
#include <set>
#include <unordered_map>

#include "cells/passes.h"

namespace avenues::detail {

std::vector<uint8_t> band_barrier(const Outline& outline, const Triangulation& T, const Band& band, size_t b) {
  const bool storey = band.kind == Band::Kind::Storey;
  if (!storey && T.cut_start.empty()) return {};
  const int n = T.size();
  std::vector<uint8_t> barrier(3 * size_t(n), 0);
  for (int32_t h = 0; h < 3 * n; ++h)
    barrier[size_t(h)] = (storey && has_sheet_of_storey(outline, T, h, band.storey)) || has_cut_of_band(T, h, b);
  return barrier;
}

namespace {

/// One decomposition of a region afresh: its own triangulation (boundary and diagonals as
/// segments), which triangles are inside, and the convex pieces merging makes of them
/// (never across a segment: a sheet inside the region, or a diagonal).
struct Fresh {
  SegmentTriangulation S;
  std::vector<int32_t> inside;
  Pieces pieces;
};

/// Decomposes the region bounded by `segments` (local points; the inside left of segment
/// 0). False where its triangulation needs points of its own (rounded, sides cross) or
/// the boundary does not close.
bool decompose(const std::vector<Vec2>& points, const std::vector<std::array<int32_t, 2>>& segments,
               size_t boundary_segments, Fresh& out) {
  out.S = triangulate_segments(points, segments);
  if (out.S.crossed) return false;
  const Triangulation& F = out.S.T;
  const int nf = F.size();
  out.inside.assign(size_t(nf), -1);
  const int32_t a = segments[0][0], b = segments[0][1];
  int seed = -1;
  for (int f = 0; f < nf && seed < 0; ++f)
    for (int j = 0; j < 3; ++j)
      if (F.tri[size_t(f)][size_t((j + 1) % 3)] == a && F.tri[size_t(f)][size_t((j + 2) % 3)] == b) seed = f;
  if (seed < 0) return false;
  // The inside is bounded by the boundary's segments; the diagonals after them part it.
  std::set<std::pair<int32_t, int32_t>> bounds;
  for (size_t k = 0; k < boundary_segments; ++k)
    bounds.insert({std::min(segments[k][0], segments[k][1]), std::max(segments[k][0], segments[k][1])});
  std::vector<int> stack{seed};
  out.inside[size_t(seed)] = 0;
  while (!stack.empty()) {
    const int f = stack.back();
    stack.pop_back();
    for (int j = 0; j < 3; ++j) {
      const int32_t g = F.nbr[size_t(f)][size_t(j)];
      const int32_t p = F.tri[size_t(f)][size_t((j + 1) % 3)], q = F.tri[size_t(f)][size_t((j + 2) % 3)];
      if (out.S.constrained[3 * size_t(f) + size_t(j)] && bounds.count({std::min(p, q), std::max(p, q)})) continue;
      if (g < 0) return false;  // leaked to the hull: the boundary is not closed
      if (out.inside[size_t(g)] < 0) out.inside[size_t(g)] = 0, stack.push_back(g);
    }
  }
  out.pieces = merge_convex(F, out.inside, out.S.constrained);
  return true;
}

/// Regions with more corners than this are left to Hertel–Mehlhorn merging alone (the
/// search below tries every corner against every other and every side).
constexpr size_t kMostCornersForDiagonals = 300;

/// [rad] the least angle a diagonal makes with the sides at its ends.
constexpr double kLeastAngle = 1e-3;

/// Diagonals that take away the region's reflex corners (Chazelle's and Greene's remedy,
/// greedily): first between two reflex corners where one diagonal leaves both convex,
/// then one from each reflex corner left, the one leaving its two angles most even. A
/// rectangle with a notch or an L needs one; Hertel–Mehlhorn merging of a Delaunay
/// triangulation keeps whichever diagonals its triangulation happened to have, often two
/// or three at one corner. Empty where the boundary is not one simple cycle per loop (a
/// sheet inside, a pinch) or is too large to search.
std::vector<std::array<int32_t, 2>> reflex_diagonals(const std::vector<Vec2>& points,
                                                     const std::vector<std::array<int32_t, 2>>& segments) {
  const size_t n = points.size();
  if (n > kMostCornersForDiagonals) return {};
  std::vector<int32_t> next(n, -1), prev(n, -1);
  for (auto [a, b] : segments) {
    if (next[size_t(a)] >= 0 || prev[size_t(b)] >= 0) return {};
    next[size_t(a)] = b, prev[size_t(b)] = a;
  }
  for (size_t v = 0; v < n; ++v)
    if (next[v] < 0 || prev[v] < 0) return {};
  // The interior at v: counter-clockwise from the direction to next to the direction to prev.
  auto angle_from = [&](size_t v, Vec2 d) {  // [0, 2π): counter-clockwise from v's side to next
    const Vec2 u = points[size_t(next[v])] - points[v];
    double t = std::atan2(cross(u, d), dot(u, d));
    return t < 0 ? t + 2 * M_PI : t;
  };
  std::vector<double> interior_angle(n);
  for (size_t v = 0; v < n; ++v) interior_angle[v] = angle_from(v, points[size_t(prev[v])] - points[v]);
  auto interior = [&](size_t v) { return interior_angle[v]; };
  std::vector<uint8_t> reflex(n, 0);
  for (size_t v = 0; v < n; ++v) {
    const int turn = orientation(points[size_t(prev[v])], points[v], points[size_t(next[v])]);
    if (turn == 0 && dot(points[v] - points[size_t(prev[v])], points[size_t(next[v])] - points[v]) < 0) return {};
    reflex[v] = turn < 0;
  }
  // Rays of chosen diagonals at each corner, as angles from its side to next.
  std::vector<std::vector<double>> rays(n);
  auto largest_gap = [&](size_t v, double with) {  // the widest angle left at v with one more ray
    std::vector<double> r = rays[v];
    if (with >= 0) r.push_back(with);
    r.push_back(0);
    r.push_back(interior(v));
    std::sort(r.begin(), r.end());
    double gap = 0;
    for (size_t k = 1; k < r.size(); ++k) gap = std::max(gap, r[k] - r[k - 1]);
    return gap;
  };
  constexpr double kStraight = M_PI * (1 + 1e-12);
  std::vector<std::array<int32_t, 2>> chosen;
  auto crosses = [&](Vec2 a, Vec2 b, Vec2 c, Vec2 d) {  // segments ab and cd meet anywhere but a shared end
    const int o1 = orientation(a, b, c), o2 = orientation(a, b, d), o3 = orientation(c, d, a), o4 = orientation(c, d, b);
    if (o1 * o2 < 0 && o3 * o4 < 0) return true;
    auto on = [](Vec2 p, Vec2 q, Vec2 r) {  // r on segment pq, collinear
      return std::min(p.x, q.x) <= r.x && r.x <= std::max(p.x, q.x) && std::min(p.y, q.y) <= r.y && r.y <= std::max(p.y, q.y);
    };
    return (o1 == 0 && on(a, b, c)) || (o2 == 0 && on(a, b, d)) || (o3 == 0 && on(c, d, a)) || (o4 == 0 && on(c, d, b));
  };
  auto valid = [&](size_t v, size_t w) {
    if (v == w || next[v] == int32_t(w) || prev[v] == int32_t(w)) return false;
    // Into the region at both ends, and not along a side there: a diagonal a rounding off
    // a side (two corners of a sloped wall's side, each reflex by its rounding) would part
    // a sliver off the region (random plan 3668).
    const double av = angle_from(v, points[w] - points[v]), aw = angle_from(w, points[v] - points[w]);
    if (!(av > kLeastAngle && av < interior(v) - kLeastAngle) || !(aw > kLeastAngle && aw < interior(w) - kLeastAngle))
      return false;
    const Vec2 a = points[v], b = points[w];
    for (auto [c, d] : segments) {
      if (size_t(c) == v || size_t(d) == v || size_t(c) == w || size_t(d) == w) {
        // Sharing an end: only a side lying along the diagonal meets it elsewhere.
        const size_t other = size_t(c) == v || size_t(c) == w ? size_t(d) : size_t(c);
        if (other != v && other != w && orientation(a, b, points[other]) == 0 &&
            dot(points[other] - a, b - a) > 0 && dot(points[other] - b, a - b) > 0)
          return false;
        continue;
      }
      if (crosses(a, b, points[size_t(c)], points[size_t(d)])) return false;
    }
    for (auto [c, d] : chosen) {
      if (size_t(c) == v || size_t(d) == v || size_t(c) == w || size_t(d) == w) continue;
      if (crosses(a, b, points[size_t(c)], points[size_t(d)])) return false;
    }
    return true;
  };
  auto take = [&](size_t v, size_t w) {
    chosen.push_back({int32_t(v), int32_t(w)});
    rays[v].push_back(angle_from(v, points[w] - points[v]));
    rays[w].push_back(angle_from(w, points[v] - points[w]));
  };
  auto resolved = [&](size_t v) { return !reflex[v] || largest_gap(v, -1) <= kStraight; };
  // Between two reflex corners, shortest first.
  std::vector<std::pair<double, std::array<size_t, 2>>> pairs;
  for (size_t v = 0; v < n; ++v)
    for (size_t w = v + 1; w < n && reflex[v]; ++w)
      if (reflex[w] && largest_gap(v, angle_from(v, points[w] - points[v])) <= kStraight &&
          largest_gap(w, angle_from(w, points[v] - points[w])) <= kStraight && valid(v, w))
        pairs.push_back({length(points[w] - points[v]), {v, w}});
  std::sort(pairs.begin(), pairs.end());
  for (const auto& [len, vw] : pairs) {
    (void)len;
    if (resolved(vw[0]) || resolved(vw[1]) || !valid(vw[0], vw[1])) continue;
    take(vw[0], vw[1]);
  }
  // Then each reflex corner left, to the corner that leaves its angles most even.
  for (size_t v = 0; v < n; ++v) {
    if (resolved(v)) continue;
    size_t best = n;
    double best_gap = HUGE_VAL;
    for (size_t w = 0; w < n; ++w) {
      if (w == v) continue;
      const double gap = largest_gap(v, angle_from(v, points[w] - points[v]));
      if (gap > kStraight || gap >= best_gap || !valid(v, w)) continue;
      best = w, best_gap = gap;
    }
    if (best < n) take(v, best);
  }
  return chosen;
}

/// The diagonals of a fresh decomposition of one region (bounded by the half-edges
/// `boundary` of T, the region on their left), as pairs of T's vertices; none when that
/// decomposition would have more than `pieces_now` pieces (`fresh`: how many it has), or
/// cannot be had from T's own points (rounded, the region's sides cross).
std::vector<std::array<int32_t, 2>> fresh_diagonals(const Triangulation& T, const std::vector<int32_t>& boundary,
                                                    size_t pieces_now, size_t& fresh) {
  std::vector<Vec2> points;
  std::vector<int32_t> vertex_of;  // local point -> T's vertex
  std::unordered_map<int32_t, int32_t> local;
  auto at = [&](int32_t v) {
    auto [it, added] = local.emplace(v, int32_t(points.size()));
    if (added) points.push_back(T.vert[size_t(v)]), vertex_of.push_back(v);
    return it->second;
  };
  std::vector<std::array<int32_t, 2>> segments;
  for (int32_t h : boundary) {
    const int t = h / 3, i = h % 3;
    segments.push_back({at(T.tri[size_t(t)][size_t((i + 1) % 3)]), at(T.tri[size_t(t)][size_t((i + 2) % 3)])});
  }
  Fresh best;  // (two of T's points that round to one are refused by triangulate_segments)
  if (!decompose(points, segments, segments.size(), best)) return {};
  if (const auto diagonals = reflex_diagonals(points, segments); !diagonals.empty()) {
    std::vector<std::array<int32_t, 2>> with = segments;
    with.insert(with.end(), diagonals.begin(), diagonals.end());
    Fresh other;
    if (decompose(points, with, segments.size(), other) && other.pieces.boundary.size() < best.pieces.boundary.size())
      best = std::move(other);
  }
  fresh = best.pieces.boundary.size();
  if (fresh > pieces_now) return {};
  const Triangulation& F = best.S.T;
  std::vector<std::array<int32_t, 2>> out;
  for (int f = 0; f < F.size(); ++f) {
    if (best.inside[size_t(f)] < 0) continue;
    for (int j = 0; j < 3; ++j) {
      const int32_t g = F.nbr[size_t(f)][size_t(j)];
      if (g <= f || best.inside[size_t(g)] < 0 || best.pieces.of[size_t(g)] == best.pieces.of[size_t(f)]) continue;
      out.push_back({vertex_of[size_t(F.tri[size_t(f)][size_t((j + 1) % 3)])],
                     vertex_of[size_t(F.tri[size_t(f)][size_t((j + 2) % 3)])]});
    }
  }
  return out;
}

/// The cuts of every band (see the top of this file).
std::vector<Cut> band_cuts(const Outline& outline, const Triangulation& T, const Classes& C) {
  const int n = T.size();
  // Regions cut afresh into fewer pieces than they have now need their cuts. Those cut
  // into as many keep theirs only where another band's needed cut may cross them (over
  // the box of the region): crossed, merging could part them further.
  struct Region {
    std::vector<std::array<int32_t, 2>> diagonals;
    int32_t band;
    std::array<double, 4> box;  ///< x0, y0, x1, y1
  };
  std::vector<Cut> cuts;
  std::vector<Region> equal;
  std::vector<int32_t> region_of(static_cast<size_t>(n));
  std::vector<int32_t> region, boundary, stack;
  for (size_t b = 0; b < C.bands.size(); ++b) {
    const std::vector<int32_t>& label = C.of[b];
    const std::vector<uint8_t> barrier = band_barrier(outline, T, C.bands[b], b);
    auto bars = [&](int32_t h) { return !barrier.empty() && barrier[size_t(h)]; };
    const Pieces now = merge_convex(T, label, barrier);
    std::fill(region_of.begin(), region_of.end(), -1);
    int32_t regions = 0;
    for (int seed = 0; seed < n; ++seed) {
      if (label[size_t(seed)] < 0 || region_of[size_t(seed)] >= 0) continue;
      region.clear();
      boundary.clear();
      stack.assign(1, seed);
      region_of[size_t(seed)] = regions;
      while (!stack.empty()) {
        const int t = stack.back();
        stack.pop_back();
        region.push_back(t);
        for (int i = 0; i < 3; ++i) {
          const int32_t u = T.nbr[size_t(t)][size_t(i)];
          if (u < 0 || label[size_t(u)] != label[size_t(t)] || bars(3 * t + i)) {
            boundary.push_back(3 * t + i);
            continue;
          }
          if (region_of[size_t(u)] < 0) region_of[size_t(u)] = regions, stack.push_back(u);
        }
      }
      ++regions;
      std::vector<int32_t> pieces;
      for (int t : region) pieces.push_back(now.of[size_t(t)]);
      std::sort(pieces.begin(), pieces.end());
      const size_t pieces_now = size_t(std::unique(pieces.begin(), pieces.end()) - pieces.begin());
      if (pieces_now <= 1) continue;  // (cuts of other bands crossing it leave it whole: merging's fast path)
      size_t fresh = 0;
      std::vector<std::array<int32_t, 2>> diagonals = fresh_diagonals(T, boundary, pieces_now, fresh);
      if (diagonals.empty()) continue;
      if (fresh < pieces_now) {
        for (auto [a, c] : diagonals) cuts.push_back({a, c, int32_t(b)});
        continue;
      }
      Region r{std::move(diagonals), int32_t(b), {HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL}};
      for (int t : region)
        for (int32_t v : T.tri[size_t(t)]) {
          const Vec2 p = T.vert[size_t(v)];
          r.box = {std::min(r.box[0], p.x), std::min(r.box[1], p.y), std::max(r.box[2], p.x), std::max(r.box[3], p.y)};
        }
      equal.push_back(std::move(r));
    }
  }
  if (cuts.empty()) return cuts;
  // The needed cuts' boxes, sorted by their left sides, to find those over a region's box.
  std::vector<std::pair<std::array<double, 4>, int32_t>> boxes;
  double widest = 0;
  for (const Cut& c : cuts) {
    const Vec2 p = T.vert[size_t(c.a)], q = T.vert[size_t(c.b)];
    boxes.push_back({{std::min(p.x, q.x), std::min(p.y, q.y), std::max(p.x, q.x), std::max(p.y, q.y)}, c.band});
    widest = std::max(widest, std::fabs(q.x - p.x));
  }
  std::sort(boxes.begin(), boxes.end());
  for (const Region& r : equal) {
    bool crossed = false;
    for (auto it = std::lower_bound(boxes.begin(), boxes.end(), std::make_pair(std::array<double, 4>{r.box[0] - widest, -HUGE_VAL, -HUGE_VAL, -HUGE_VAL}, INT32_MIN));
         it != boxes.end() && it->first[0] <= r.box[2] && !crossed; ++it)
      crossed = it->second != r.band && it->first[2] >= r.box[0] && it->first[1] <= r.box[3] && it->first[3] >= r.box[1];
    if (crossed)
      for (auto [a, c] : r.diagonals) cuts.push_back({a, c, r.band});
  }
  return cuts;
}

}  // namespace

void cut_bands(const Outline& outline, ExactTriangulation& exact, Classes& C) {
  const std::vector<Cut> cuts = band_cuts(outline, exact.rounded(), C);
  if (cuts.empty()) return;
  // The classes of the triangles after are their parents'; so the edges between triangles
  // of different classes (or walls) in any band are kept.
  const Triangulation& T = exact.rounded();
  const size_t before = size_t(T.size());
  std::vector<uint8_t> keep(3 * before, 0);
  for (size_t t = 0; t < before; ++t)
    for (size_t i = 0; i < 3; ++i) {
      const int32_t u = T.nbr[t][i];
      if (u < 0) continue;
      for (size_t b = 0; b < C.bands.size() && !keep[3 * t + i]; ++b)
        keep[3 * t + i] = C.of[b][t] != C.of[b][size_t(u)] || C.wall_of[b * before + t] != C.wall_of[b * before + size_t(u)];
    }
  const std::vector<int32_t> parent = exact.cut(cuts, keep);
  for (auto& of : C.of) {
    std::vector<int32_t> now(parent.size());
    for (size_t t = 0; t < parent.size(); ++t) now[t] = parent[t] < 0 ? -1 : of[size_t(parent[t])];
    of.swap(now);
  }
  std::vector<int32_t> wall_of(C.bands.size() * parent.size(), -1);
  for (size_t b = 0; b < C.bands.size(); ++b)
    for (size_t t = 0; t < parent.size(); ++t)
      if (parent[t] >= 0) wall_of[b * parent.size() + t] = C.wall_of[b * before + size_t(parent[t])];
  C.wall_of.swap(wall_of);
}

}  // namespace avenues::detail

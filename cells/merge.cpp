// Avenues — pass 4 of build_cells: Hertel–Mehlhorn merging of triangles into convex pieces.
//
// Hertel & Mehlhorn (1983): remove diagonals of a triangulation while both of their
// ends stay convex; the result has at most four times the minimum number of convex
// pieces. We remove the longest diagonals first, which in rooms tends to leave the
// short cuts from reflex corners as the only transparent faces. Convexity is decided
// by exact orientation on the rounded vertices the cells will carry (corners.cpp), so a merged
// footprint is convex (collinear vertices allowed) in exactly the doubles downstream
// code sees. Choice against the alternatives: CGAL's optimal_convex_partition_2 is
// cubic and, like the approximate and Greene partitions, takes no holes (a storey's
// free space is full of them: every wall is one); the vertical decomposition of
// Minkowski_sum_2 takes holes but shoots two cuts from every vertex, so a plain
// rectangular room with a door on each side would come out as several cells. Merging
// the triangulation we already have gives 1.0–1.25 cells per room on the bundled plans
// and the generated offices (docs/PERFORMANCE.md), at a cost linear in the triangles.
#include <algorithm>
#include <numeric>

#include "cells/passes.h"

namespace avenues::detail {

Pieces merge_convex(const Triangulation& T, const std::vector<int32_t>& label, const std::vector<uint8_t>& barrier) {
  const int n = T.size();
  // Union-find over triangles; the root holds the piece's boundary half-edges in CCW order.
  std::vector<int32_t> parent(static_cast<size_t>(n));
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int32_t x) {
    while (parent[size_t(x)] != x) x = parent[size_t(x)] = parent[size_t(parent[size_t(x)])];
    return x;
  };
  std::vector<std::vector<int32_t>> bnd(static_cast<size_t>(n));
  // Boundary order of a triangle: half-edge i goes from vertex i+1 to i+2; the CCW cycle
  // is edge 2 (v0->v1), edge 0 (v1->v2), edge 1 (v2->v0).
  for (int t = 0; t < n; ++t)
    if (label[size_t(t)] >= 0) bnd[size_t(t)] = {3 * t + 2, 3 * t + 0, 3 * t + 1};

  auto from = [&](int32_t h) { return T.tri[size_t(h / 3)][size_t((h % 3 + 1) % 3)]; };
  auto to = [&](int32_t h) { return T.tri[size_t(h / 3)][size_t((h % 3 + 2) % 3)]; };
  auto across = [&](int32_t h) { return T.nbr[size_t(h / 3)][size_t(h % 3)]; };
  auto is_barrier = [&](int32_t h) { return !barrier.empty() && barrier[size_t(h)]; };

  // Whether a boundary is convex as its cell's footprint will have it (corners_of). Two
  // convex pieces joined convexly at both ends of their shared chain are convex in exact
  // arithmetic; on the rounded points they need not be: two corners can round to one point
  // (a pinch: the piece would be two) or to points a rounding apart, whose side's direction
  // is noise (a corner judged against it can turn right once the noise is dropped).
  std::vector<Vec2> ring, points;
  std::vector<uint8_t> made;
  std::vector<Corner> corners;
  auto convex = [&](const std::vector<int32_t>& cycle) {
    return convex_footprint(ring, corners, points, ring_of(T, cycle, ring, made));
  };

  // Fast path: a connected region of one label whose whole boundary is one convex cycle
  // (a rectangular room, the roof of a rectangular building, the sky) is one piece at
  // once; merging it triangle by triangle would cost its perimeter per merge.
  {
    std::vector<uint8_t> seen(size_t(n), 0);
    std::vector<int32_t> region, stack, edges, next_of;
    for (int seed = 0; seed < n; ++seed) {
      if (label[size_t(seed)] < 0 || seen[size_t(seed)]) continue;
      region.clear();
      edges.clear();
      stack.assign(1, seed);
      seen[size_t(seed)] = 1;
      while (!stack.empty()) {
        int t = stack.back();
        stack.pop_back();
        region.push_back(t);
        for (int i = 0; i < 3; ++i) {
          int u = T.nbr[size_t(t)][size_t(i)];
          bool inside = u >= 0 && label[size_t(u)] == label[size_t(t)] && !is_barrier(3 * t + i);
          if (!inside) { edges.push_back(3 * t + i); continue; }
          if (!seen[size_t(u)]) { seen[size_t(u)] = 1; stack.push_back(u); }
        }
      }
      if (region.size() < 3) continue;
      // Chain the boundary into cycles by vertex; a vertex left twice means a pinch.
      std::vector<std::pair<int32_t, int32_t>> by_from;
      for (int32_t e : edges) by_from.push_back({from(e), e});
      std::sort(by_from.begin(), by_from.end());
      bool ok = true;
      for (size_t k = 1; k < by_from.size() && ok; ++k) ok = by_from[k].first != by_from[k - 1].first;
      if (!ok) continue;
      auto next = [&](int32_t e) {
        auto it = std::lower_bound(by_from.begin(), by_from.end(), std::make_pair(to(e), INT32_MIN));
        return it != by_from.end() && it->first == to(e) ? it->second : -1;
      };
      std::vector<int32_t> cycle{edges[0]};
      for (int32_t e = next(edges[0]); e != edges[0] && e >= 0 && cycle.size() <= edges.size(); e = next(e))
        cycle.push_back(e);
      if (cycle.size() != edges.size()) continue;  // several cycles (holes) or broken
      if (!convex(cycle)) continue;
      const int32_t root = region[0];
      for (int32_t t : region) {
        parent[size_t(t)] = root;
        std::vector<int32_t>().swap(bnd[size_t(t)]);
      }
      bnd[size_t(root)] = std::move(cycle);
    }
  }

  // Candidate diagonals: interior edges between triangles of one label, longest first.
  std::vector<std::pair<double, int32_t>> cand;
  for (int t = 0; t < n; ++t) {
    if (label[size_t(t)] < 0) continue;
    for (int i = 0; i < 3; ++i) {
      int u = T.nbr[size_t(t)][size_t(i)];
      if (u > t && label[size_t(u)] == label[size_t(t)] && !is_barrier(3 * t + i)) {
        Vec2 d = T.edge_to(t, i) - T.edge_from(t, i);
        cand.push_back({-dot(d, d), 3 * t + i});
      }
    }
  }
  std::sort(cand.begin(), cand.end());

  std::vector<int32_t> merged;
  for (auto [neg_len, h] : cand) {
    (void)neg_len;
    int32_t P = find(h / 3), Q = find(across(h));
    if (P == Q) continue;
    auto& bp = bnd[size_t(P)];
    auto& bq = bnd[size_t(Q)];
    // A half-edge of P is shared with Q when the triangle across it belongs to Q.
    auto shared_p = [&](int32_t e) { int u = across(e); return u >= 0 && find(u) == Q; };
    auto shared_q = [&](int32_t e) { int u = across(e); return u >= 0 && find(u) == P; };
    const size_t np = bp.size(), nq = bq.size();
    // Rotate so that P's shared chain is at the end and Q's likewise.
    size_t ip = 0;
    while (ip < np && !shared_p(bp[ip])) ++ip;
    if (ip == np) continue;
    // Find the start of P's shared chain (walk back while shared; convex pieces share one chain).
    size_t s = ip;
    for (size_t k = 0; k < np && shared_p(bp[(s + np - 1) % np]); ++k) s = (s + np - 1) % np;
    size_t len_p = 0;
    bool blocked = false;
    while (len_p < np && shared_p(bp[(s + len_p) % np])) {
      blocked |= is_barrier(bp[(s + len_p) % np]);
      ++len_p;
    }
    if (blocked || len_p == np) continue;
    size_t iq = 0;
    while (iq < nq && !shared_q(bq[iq])) ++iq;
    if (iq == nq) continue;
    size_t sq = iq;
    for (size_t k = 0; k < nq && shared_q(bq[(sq + nq - 1) % nq]); ++k) sq = (sq + nq - 1) % nq;
    size_t len_q = 0;
    while (len_q < nq && shared_q(bq[(sq + len_q) % nq])) ++len_q;
    if (len_q != len_p || len_q == nq) continue;  // not a single shared chain: leave apart
    // P's rest runs from b (end of chain) to a (start); Q's rest from a to b.
    // Junction at a: P's rest ends entering a, Q's rest starts leaving a.
    const int32_t p_last = bp[(s + np - 1) % np];      // enters a
    const int32_t q_first = bq[(sq + len_q) % nq];     // leaves a
    const int32_t q_last = bq[(sq + nq - 1) % nq];     // enters b
    const int32_t p_first = bp[(s + len_p) % np];      // leaves b
    const Vec2 a = T.vert[size_t(to(p_last))], b = T.vert[size_t(to(q_last))];
    if (orientation(T.vert[size_t(from(p_last))], a, T.vert[size_t(to(q_first))]) < 0) continue;
    if (orientation(T.vert[size_t(from(q_last))], b, T.vert[size_t(to(p_first))]) < 0) continue;
    merged.clear();
    for (size_t k = 0; k < np - len_p; ++k) merged.push_back(bp[(s + len_p + k) % np]);
    for (size_t k = 0; k < nq - len_q; ++k) merged.push_back(bq[(sq + len_q + k) % nq]);
    if (!convex(merged)) continue;
    parent[size_t(Q)] = P;
    bp.swap(merged);
    std::vector<int32_t>().swap(bnd[size_t(Q)]);
  }

  Pieces out;
  out.of.assign(size_t(n), -1);
  std::vector<int32_t> piece_of_root(size_t(n), -1);
  for (int t = 0; t < n; ++t) {
    if (label[size_t(t)] < 0) continue;
    int32_t r = find(t);
    if (piece_of_root[size_t(r)] < 0) {
      piece_of_root[size_t(r)] = int32_t(out.boundary.size());
      out.boundary.push_back(std::move(bnd[size_t(r)]));
      out.label.push_back(label[size_t(t)]);
    }
    out.of[size_t(t)] = piece_of_root[size_t(r)];
  }
  return out;
}

}  // namespace avenues::detail

// Avenues — each stroke once on paper (see stroke_merge.h).
#include "render/stroke_merge.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <boost/sort/spreadsort/float_sort.hpp>

#include "core/thread_arena.h"

namespace avenues {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kAngle = 1e-9;     ///< [rad] directions closer than this are one direction
constexpr double kOffset = 1e-6;    ///< [px] parallel lines closer than this are one line
constexpr double kTouch = 1e-6;     ///< [px] collinear strokes closer than this touch

/// A point of a picture line: its coordinate s along the line, and the point itself.
struct End {
  double s;
  Vec2 p;
};
struct Piece {
  End lo, hi;
};

struct Item {
  Piece piece;
  int rank;       ///< who keeps an overlap: lower first
  uint32_t order; ///< index of the input stroke
};

/// Heavier pens first (cut, outline, crease), then layers in their order (architecture first).
constexpr int kLayers = 8;
int rank_of(const Stroke& s) {
  const int w = s.weight == Weight::Cut ? 0 : s.weight == Weight::Outline ? 1 : 2;
  return w * kLayers + int(s.layer);
}
Stroke stroke_of(int rank, const Piece& p) {
  const int w = rank / kLayers;
  return {p.lo.p, p.hi.p, w == 0 ? Weight::Cut : w == 1 ? Weight::Outline : Weight::Crease, Layer(rank % kLayers)};
}

/// Merges pieces sorted by lo.s that overlap or touch.
void merge_sorted(std::vector<Piece>& v) {
  size_t out = 0;
  for (size_t i = 0; i < v.size(); ++i) {
    if (out > 0 && v[i].lo.s <= v[out - 1].hi.s + kTouch) {
      if (v[i].hi.s > v[out - 1].hi.s) v[out - 1].hi = v[i].hi;
    } else {
      v[out++] = v[i];
    }
  }
  v.resize(out);
}

/// Appends to `out` what of `p` the sorted, disjoint `claimed` leaves. `from` is where in
/// `claimed` to start looking; it moves on past what ends before p, so that pieces given in
/// order scan `claimed` once, not once each.
void subtract(const Piece& p, const std::vector<Piece>& claimed, size_t& from, std::vector<Piece>& out) {
  while (from < claimed.size() && claimed[from].hi.s <= p.lo.s) ++from;
  End lo = p.lo;
  for (size_t k = from; k < claimed.size(); ++k) {
    const Piece& c = claimed[k];
    if (c.hi.s <= lo.s) continue;
    if (c.lo.s >= p.hi.s) break;
    if (c.lo.s > lo.s + kShortestStroke) out.push_back({lo, c.lo});
    lo = c.hi;
  }
  if (p.hi.s > lo.s + kShortestStroke) out.push_back({lo, p.hi});
}

/// Resolves one picture line: rank by rank, each merges its own pieces and keeps what the
/// ranks before it did not claim.
/// Sorted by (rank, lo.s) as small keys, not as whole items.
struct LineKey {
  double s;
  int32_t rank;
  uint32_t item;
};
struct Scratch {
  std::vector<Piece> claimed, mine, kept;
  std::vector<LineKey> keys;
};
void resolve(const std::vector<Item>& line, std::vector<std::pair<uint32_t, Stroke>>& out, Scratch& scratch) {
  auto& [claimed, mine, kept, keys] = scratch;
  keys.clear();
  for (size_t i = 0; i < line.size(); ++i) keys.push_back({line[i].piece.lo.s, line[i].rank, uint32_t(i)});
  std::sort(keys.begin(), keys.end(),
            [](const LineKey& a, const LineKey& b) { return a.rank != b.rank ? a.rank < b.rank : a.s < b.s; });
  claimed.clear();
  for (size_t i = 0; i < keys.size();) {
    const int rank = keys[i].rank;
    uint32_t order = line[keys[i].item].order;
    mine.clear();
    for (; i < keys.size() && keys[i].rank == rank; ++i) {
      const Item& it = line[keys[i].item];
      mine.push_back(it.piece);
      order = std::min(order, it.order);
    }
    merge_sorted(mine);
    kept.clear();
    size_t from = 0;
    for (const Piece& p : mine) subtract(p, claimed, from, kept);  // mine is sorted and disjoint
    for (const Piece& p : kept) out.push_back({order, stroke_of(rank, p)});
    claimed.insert(claimed.end(), mine.begin(), mine.end());
    std::sort(claimed.begin(), claimed.end(), [](const Piece& a, const Piece& b) { return a.lo.s < b.lo.s; });
    merge_sorted(claimed);
  }
}

}  // namespace

void merge_collinear(std::vector<Stroke>& strokes, int threads) {
  // Sorted as small keys (direction or offset, and an index), not as whole items: a plan
  // has a hundred thousand strokes, and moving keys is what the sorts cost.
  struct Key {
    double v;
    uint32_t i;
  };
  // Boost's spreadsort (a radix sort of the doubles' bits): several times faster than a
  // comparison sort here, where directions and offsets repeat by the thousand.
  auto sort_keys = [](std::vector<Key>& k) {
    boost::sort::spreadsort::float_sort(
        k.begin(), k.end(),
        [](const Key& x, unsigned shift) { return boost::sort::spreadsort::float_mem_cast<double, int64_t>(x.v) >> shift; },
        [](const Key& x, const Key& y) { return x.v < y.v; });
  };
  std::vector<Key> dirs;  // direction, index into strokes
  dirs.reserve(strokes.size());
  for (size_t i = 0; i < strokes.size(); ++i) {
    const Stroke& s = strokes[i];
    if (const Vec2 d = s.b - s.a; dot(d, d) < kShortestStroke * kShortestStroke) continue;
    double theta = std::atan2(s.b.y - s.a.y, s.b.x - s.a.x);
    if (theta > kPi / 2 - kAngle) theta -= kPi;
    else if (theta <= -kPi / 2 - kAngle) theta += kPi;
    dirs.push_back({theta, uint32_t(i)});
  }
  sort_keys(dirs);

  // The runs of one direction are independent: spread over threads, each run whole.
  std::vector<size_t> runs;  // where each direction's run of dirs starts, and the end
  for (size_t i = 0; i < dirs.size();) {
    runs.push_back(i);
    // One direction: anchored at its first item, so tolerances do not chain.
    size_t j = i;
    while (j < dirs.size() && dirs[j].v - dirs[i].v <= kAngle) ++j;
    i = j;
  }
  runs.push_back(dirs.size());
  const size_t chunks = threads == 1 ? 1 : 16;
  std::vector<std::vector<std::pair<uint32_t, Stroke>>> outs(chunks);
  for_each_chunk(threads, dirs.size(), chunks, [&](size_t chunk, size_t lo, size_t hi) {
    std::vector<std::pair<uint32_t, Stroke>>& out = outs[chunk];
    std::vector<Item> line;
    std::vector<Key> offsets;  // offset of the line from the origin along the run's normal, index into strokes
    Scratch scratch;
    for (size_t r = size_t(std::lower_bound(runs.begin(), runs.end(), lo) - runs.begin());
         r + 1 < runs.size() && runs[r] < hi; ++r) {
      const size_t i = runs[r], j = runs[r + 1];
      const Vec2 u{std::cos(dirs[i].v), std::sin(dirs[i].v)}, n{-u.y, u.x};
      offsets.clear();
      for (size_t k = i; k < j; ++k) {
        const Stroke& st = strokes[dirs[k].i];
        offsets.push_back({dot(n, 0.5 * (st.a + st.b)), dirs[k].i});
      }
      sort_keys(offsets);
      for (size_t k = 0; k < offsets.size();) {
        size_t m = k;
        while (m < offsets.size() && offsets[m].v - offsets[k].v <= kOffset) ++m;
        if (m - k == 1) {
          out.push_back({offsets[k].i, strokes[offsets[k].i]});
        } else {
          line.clear();
          for (size_t q = k; q < m; ++q) {
            if (q + 8 < m) __builtin_prefetch(&strokes[offsets[q + 8].i]);  // in rho's order, strokes lie anywhere
            const Stroke& st = strokes[offsets[q].i];
            Item it{{{dot(u, st.a), st.a}, {dot(u, st.b), st.b}}, rank_of(st), offsets[q].i};
            if (it.piece.lo.s > it.piece.hi.s) std::swap(it.piece.lo, it.piece.hi);
            line.push_back(it);
          }
          resolve(line, out, scratch);
        }
        k = m;
      }
    }
  });
  // Back in the input's order (stable: a counting sort by input index; the pieces of one
  // input stroke all come from one run, so the chunks' order does not matter).
  std::vector<uint32_t> start(strokes.size() + 1, 0);
  size_t total = 0;
  for (const auto& out : outs) {
    total += out.size();
    for (const auto& o : out) ++start[o.first + 1];
  }
  for (size_t i = 1; i < start.size(); ++i) start[i] += start[i - 1];
  std::vector<Stroke> merged(total);
  for (const auto& out : outs)
    for (const auto& [order, s] : out) merged[start[order]++] = s;
  strokes = std::move(merged);
}

}  // namespace avenues

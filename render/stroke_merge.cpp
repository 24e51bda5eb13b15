// Avenues — each stroke once on paper (see stroke_merge.h).
#include "render/stroke_merge.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace avenues {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kAngle = 1e-9;     ///< [rad] directions closer than this are one direction
constexpr double kOffset = 1e-6;    ///< [px] parallel lines closer than this are one line
constexpr double kTouch = 1e-6;     ///< [px] collinear strokes closer than this touch
constexpr double kShortest = 1e-9;  ///< [px] shorter strokes draw nothing

/// A point of a picture line: its coordinate s along the line, and the point itself.
struct End {
  double s;
  Vec2 p;
};
struct Piece {
  End lo, hi;
};

struct Item {
  double theta;   ///< direction of lo→hi, in (−π/2 − kAngle, π/2 − kAngle]
  double rho;     ///< offset of the line from the origin, along the group's normal
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

/// Appends to `out` what of `p` the sorted, disjoint `claimed` leaves.
void subtract(const Piece& p, const std::vector<Piece>& claimed, std::vector<Piece>& out) {
  End lo = p.lo;
  for (const Piece& c : claimed) {
    if (c.hi.s <= lo.s) continue;
    if (c.lo.s >= p.hi.s) break;
    if (c.lo.s > lo.s + kShortest) out.push_back({lo, c.lo});
    lo = c.hi;
  }
  if (p.hi.s > lo.s + kShortest) out.push_back({lo, p.hi});
}

/// Resolves one picture line: rank by rank, each merges its own pieces and keeps what the
/// ranks before it did not claim.
void resolve(std::vector<Item>& line, std::vector<std::pair<uint32_t, Stroke>>& out) {
  std::sort(line.begin(), line.end(), [](const Item& a, const Item& b) {
    return a.rank != b.rank ? a.rank < b.rank : a.piece.lo.s < b.piece.lo.s;
  });
  std::vector<Piece> claimed, mine, kept;
  for (size_t i = 0; i < line.size();) {
    const int rank = line[i].rank;
    uint32_t order = line[i].order;
    mine.clear();
    for (; i < line.size() && line[i].rank == rank; ++i) {
      mine.push_back(line[i].piece);
      order = std::min(order, line[i].order);
    }
    merge_sorted(mine);
    kept.clear();
    for (const Piece& p : mine) subtract(p, claimed, kept);
    for (const Piece& p : kept) out.push_back({order, stroke_of(rank, p)});
    claimed.insert(claimed.end(), mine.begin(), mine.end());
    std::sort(claimed.begin(), claimed.end(), [](const Piece& a, const Piece& b) { return a.lo.s < b.lo.s; });
    merge_sorted(claimed);
  }
}

}  // namespace

void merge_collinear(std::vector<Stroke>& strokes) {
  std::vector<Item> items;
  items.reserve(strokes.size());
  for (size_t i = 0; i < strokes.size(); ++i) {
    const Stroke& s = strokes[i];
    Vec2 a = s.a, b = s.b;
    if (length(b - a) < kShortest) continue;
    double theta = std::atan2(b.y - a.y, b.x - a.x);
    if (theta > kPi / 2 - kAngle) theta -= kPi, std::swap(a, b);
    else if (theta <= -kPi / 2 - kAngle) theta += kPi, std::swap(a, b);
    items.push_back({theta, 0, {{0, a}, {0, b}}, rank_of(s), uint32_t(i)});
  }
  std::sort(items.begin(), items.end(), [](const Item& x, const Item& y) { return x.theta < y.theta; });

  std::vector<std::pair<uint32_t, Stroke>> out;
  out.reserve(items.size());
  std::vector<Item> line;
  for (size_t i = 0; i < items.size();) {
    // One direction: anchored at its first item, so tolerances do not chain.
    size_t j = i;
    while (j < items.size() && items[j].theta - items[i].theta <= kAngle) ++j;
    const Vec2 u{std::cos(items[i].theta), std::sin(items[i].theta)}, n{-u.y, u.x};
    for (size_t k = i; k < j; ++k) {
      Item& it = items[k];
      it.rho = dot(n, 0.5 * (it.piece.lo.p + it.piece.hi.p));
      it.piece.lo.s = dot(u, it.piece.lo.p);
      it.piece.hi.s = dot(u, it.piece.hi.p);
      if (it.piece.lo.s > it.piece.hi.s) std::swap(it.piece.lo, it.piece.hi);
    }
    std::sort(items.begin() + long(i), items.begin() + long(j), [](const Item& x, const Item& y) { return x.rho < y.rho; });
    for (size_t k = i; k < j;) {
      size_t m = k;
      while (m < j && items[m].rho - items[k].rho <= kOffset) ++m;
      if (m - k == 1) {
        out.push_back({items[k].order, strokes[items[k].order]});
      } else {
        line.assign(items.begin() + long(k), items.begin() + long(m));
        resolve(line, out);
      }
      k = m;
    }
    i = j;
  }
  std::stable_sort(out.begin(), out.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  strokes.clear();
  for (const auto& [order, s] : out) strokes.push_back(s);
}

}  // namespace avenues

// The DXF readers' grid of line segments (plans/formats/segment_grid.h): a query reports
// every line that passes through its box, each once, whether the box covers a few cells
// (looked up one by one) or more cells than there are bins (the bins looked through).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "plans/formats/segment_grid.h"

using namespace avenues;

namespace {

/// Whether segment ab meets the box [p - r, p + r] (Liang–Barsky clipping).
bool meets_box(Vec2 a, Vec2 b, Vec2 p, double r) {
  double t0 = 0, t1 = 1;
  const double d[2] = {b.x - a.x, b.y - a.y}, o[2] = {a.x, a.y}, lo[2] = {p.x - r, p.y - r}, hi[2] = {p.x + r, p.y + r};
  for (int k = 0; k < 2; ++k) {
    if (d[k] == 0) {
      if (o[k] < lo[k] || o[k] > hi[k]) return false;
      continue;
    }
    double ta = (lo[k] - o[k]) / d[k], tb = (hi[k] - o[k]) / d[k];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta), t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

}  // namespace

TEST(SegmentGrid, AQueryMeetsEveryLineThroughItsBoxOnceHoweverLargeTheBox) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> at(-400, 400), unit(-1, 1);
  std::vector<std::pair<Vec2, Vec2>> lines;
  for (int k = 0; k < 300; ++k) {
    const Vec2 a{at(rng), at(rng)};
    // Short lines, lines of a few hundred metres (binned along their length) and a few
    // longer than the grid bins at all (met by every query).
    const double len = k % 50 == 0 ? 3000 : k % 7 == 0 ? 300 : 3;
    lines.push_back({a, a + Vec2{len * unit(rng), len * unit(rng)}});
  }
  SegmentGrid grid(lines, 0.5);
  int reported = 0;
  for (int q = 0; q < 200; ++q) {
    const Vec2 p{at(rng), at(rng)};
    const double r = q % 4 == 0 ? 500 : q % 4 == 1 ? 60 : q % 4 == 2 ? 2 : 0.1;  // 2 million cells down to a few
    SCOPED_TRACE("query " + std::to_string(q) + ", r " + std::to_string(r));
    std::vector<size_t> got;
    grid.near(p, r, [&](size_t i) { got.push_back(i); });
    const std::set<size_t> once(got.begin(), got.end());
    ASSERT_EQ(once.size(), got.size()) << "a line reported twice";
    for (size_t i = 0; i < lines.size(); ++i)
      if (meets_box(lines[i].first, lines[i].second, p, r)) {
        ASSERT_TRUE(once.count(i)) << "line " << i << " missed";
      }
    reported += int(got.size());
  }
  EXPECT_GT(reported, 200 * 6);  // the six longest lines at least, every time
}

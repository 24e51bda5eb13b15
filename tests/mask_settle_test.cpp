// Tests of Mask::settle_within and Mask::within (visibility/mask.h) in double: a mask
// clipped from another keeps no vertex beyond it, however nearly parallel the lines that
// meet there, and keeps its area where a vertex strayed by a rounding.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include "visibility/mask.h"

using namespace avenues;

namespace {

using P = Point2T<double>;

Mask<double> polygon(std::vector<P> points) { return Mask<double>::hull(points, false); }

struct Bounds {
  double lo_x = HUGE_VAL, hi_x = -HUGE_VAL, lo_y = HUGE_VAL, hi_y = -HUGE_VAL;
};

Bounds bounds_of(const Mask<double>& m) {
  Bounds b;
  for (const P& v : m.polygon())
    b.lo_x = std::min(b.lo_x, v.x), b.hi_x = std::max(b.hi_x, v.x), b.lo_y = std::min(b.lo_y, v.y),
    b.hi_y = std::max(b.hi_y, v.y);
  return b;
}

/// How far the farthest vertex of m lies outside b (0: none does).
double beyond(const Mask<double>& m, const Bounds& b) {
  double d = 0;
  for (const P& v : m.polygon())
    d = std::max({d, b.lo_x - v.x, v.x - b.hi_x, b.lo_y - v.y, v.y - b.hi_y});
  return d;
}

}  // namespace

/// Needles of no area, as the clips of nearly parallel portal edges leave them (a duplex
/// view's was 1.25e-3 long and 2e-7 wide at its end), each clipped again by a line nearly
/// parallel to one of its sides: the new corner is where two nearly parallel lines meet,
/// and lands anywhere along them, even past the needle's tip, outside each of its sides by
/// less than the slack (the duplex's: 1.6e-3 past, 1.3e-8 outside). Settled, no corner
/// lies past the needle's bounds by more than the slack.
TEST(MaskSettle, ACornerRunningOnPastANeedlesTipComesBack) {
  std::mt19937 rng(16);
  std::uniform_real_distribution<double> unit(0, 1);
  int strayed = 0, kept = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const P tip{unit(rng) - 0.5, unit(rng) - 0.5};
    const double angle = 2 * std::numbers::pi * unit(rng), length = std::pow(10.0, -4 + 3 * unit(rng));
    const double width = length * std::pow(10.0, -9 + 3 * unit(rng));  // at the far end
    const P dir{std::cos(angle), std::sin(angle)};
    const P end{tip.x + length * dir.x, tip.y + length * dir.y};
    const P off{-dir.y * width / 2, dir.x * width / 2};
    const Mask<double> needle = polygon({tip, {end.x + off.x, end.y + off.y}, {end.x - off.x, end.y - off.y}});
    if (needle.empty()) continue;
    const Bounds b = bounds_of(needle);
    // A line through a point of the needle's side, turned from it by a hair.
    const double turn = std::pow(10.0, -12 + 5 * unit(rng)) * (unit(rng) < 0.5 ? -1 : 1), at = unit(rng);
    const P on{tip.x + at * (end.x + off.x - tip.x), tip.y + at * (end.y + off.y - tip.y)};
    const P along{std::cos(angle + turn), std::sin(angle + turn)};
    HalfPlane<double> line{-along.y, along.x, 0};
    line.c = -(line.a * on.x + line.b * on.y);
    for (const HalfPlane<double>& side : {line, HalfPlane<double>{-line.a, -line.b, -line.c}}) {
      Mask<double> m = needle;
      if (!m.clip(side)) continue;
      const double slack = 2e-8 * (1 + std::max(std::fabs(b.hi_x) + std::fabs(b.lo_x), std::fabs(b.hi_y) + std::fabs(b.lo_y)));
      strayed += beyond(m, b) > slack;
      if (!m.settle_within(needle)) continue;
      ++kept;
      ASSERT_LE(beyond(m, b), slack) << "trial " << trial << ": a corner lies past the needle it was clipped from";
    }
  }
  std::printf("  %d clips strayed past their needle; %d kept area once settled\n", strayed, kept);
  EXPECT_GT(strayed, 0) << "no clip met the fault";
  EXPECT_GT(kept, 0);
}

/// A triangle's corner 5e-8 past its parent's corner, along the parent's side (a duplex
/// view's clip left it): the corner is brought back, and the triangle keeps its area
/// (dropping the corner left two and lost the triangle: 58 pixels of the picture).
TEST(MaskSettle, ACornerARoundingPastItsParentsIsMovedBackNotDropped) {
  const Mask<double> parent = polygon({{0.28448497470754719, -0.36338377005395145},
                                       {0.32865821005842571, -0.36338377005395145},
                                       {0.36813292816452803, -0.20070436443162004},
                                       {0.33578436932852485, 0.0045503913951969437}});
  const P top{0.33578436932852485, 0.0045503913951969437}, left{0.28448497470754719, -0.36338377005395145};
  const P past{top.x + 1.5e-7 * (top.x - left.x), top.y + 1.5e-7 * (top.y - left.y)};  // on its side's line
  Mask<double> child = polygon({{0.31058641565742423, -0.17617665270952351}, {0.36813292816447057, -0.20070436443162368}, past});
  const double area = child.area2();
  ASSERT_GT(area, 0);
  const Bounds b = bounds_of(parent);
  ASSERT_GT(beyond(child, b), 4e-8);  // past the slack (2.7e-8 here)
  ASSERT_TRUE(child.settle_within(parent));
  EXPECT_LE(beyond(child, b), 1e-12);
  EXPECT_NEAR(child.area2(), area, 1e-6 * area);
}

/// A mask wholly inside its parent is left as it was, coefficient for coefficient.
TEST(MaskSettle, AMaskInsideItsParentIsLeftAlone) {
  const Mask<double> parent = Mask<double>::window(-1, 1, -1, 1);
  Mask<double> m = parent;
  ASSERT_TRUE(m.clip({1, 0.3, 0.2}));
  const Mask<double> before = m;
  ASSERT_TRUE(m.settle_within(parent));
  EXPECT_TRUE(m.same_as(before));
}

/// The hull search prunes a piece within what its cell was already searched through: a
/// piece along a needle's line past its tip is not within it, though each of its corners
/// lies within the slack of every half-plane of the needle.
TEST(MaskSettle, APiecePastANeedlesTipIsNotWithinIt) {
  const Mask<double> needle = polygon({{0, 0}, {1, 1e-8}, {1, -1e-8}});
  ASSERT_FALSE(needle.empty());
  const Mask<double> past = polygon({{-1, 0}, {-0.5, -0.2e-8}, {-0.5, 0.2e-8}});
  const Mask<double> inside = polygon({{0.5, 0}, {0.9, -0.3e-8}, {0.9, 0.3e-8}});
  ASSERT_FALSE(past.empty());
  ASSERT_FALSE(inside.empty());
  EXPECT_FALSE(past.within(needle));
  EXPECT_TRUE(inside.within(needle));
}

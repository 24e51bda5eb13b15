// Tests of plans/formats/wall_line_ends.cpp: which ends are free, and the lines that
// close them (an undershoot carried on, a wall's end capped, door gaps left open).
#include <gtest/gtest.h>

#include "plans/formats/wall_line_ends.h"

namespace avenues {
namespace {

using Lines = std::vector<std::pair<Vec2, Vec2>>;

TEST(WallLineEnds, AClosedOutlineHasNoFreeEnd) {
  const Lines square = {{{0, 0}, {4, 0}}, {{4, 0}, {4, 3}}, {{4, 3}, {0, 3}}, {{0, 3}, {0, 0}}};
  const WallLineEnds e = close_wall_line_ends(square);
  EXPECT_EQ(e.free_ends, 0);
  EXPECT_TRUE(e.added.empty());
}

TEST(WallLineEnds, APartitionStoppingShortIsCarriedOnToTheWall) {
  // A wall along y = 0 and a partition from (2, 3) down to (2, 0.03): 3 cm short.
  const Lines lines = {{{0, 0}, {4, 0}}, {{2, 3}, {2, 0.03}}};
  const WallLineEnds e = close_wall_line_ends(lines);
  ASSERT_EQ(e.extended, 1);
  EXPECT_NEAR(e.added[0].second.y, 0, 1e-12);
  EXPECT_NEAR(e.added[0].second.x, 2, 1e-12);
  // 8 cm short is a gap the drawing meant: left alone.
  EXPECT_EQ(close_wall_line_ends({{{0, 0}, {4, 0}}, {{2, 3}, {2, 0.08}}}).extended, 0);
}

TEST(WallLineEnds, AWallsEndsAtADoorGapAreCappedAndTheGapStaysOpen) {
  // A partition 0.2 m thick, x 4.1 and 4.3, with a 0.9 m gap from y 1.0 to 1.9.
  const Lines lines = {{{4.1, 0}, {4.1, 1.0}}, {{4.3, 0}, {4.3, 1.0}}, {{4.1, 1.9}, {4.1, 3}}, {{4.3, 1.9}, {4.3, 3}}};
  const WallLineEnds e = close_wall_line_ends(lines);
  EXPECT_EQ(e.free_ends, 8);
  EXPECT_EQ(e.capped, 4);  // both ends of both pieces, across the wall
  for (const auto& [a, b] : e.added) {
    EXPECT_NEAR(std::fabs(a.x - b.x), 0.2, 1e-12);
    EXPECT_NEAR(a.y, b.y, 1e-12);  // never across the door gap
  }
}

TEST(WallLineEnds, EndsWiderApartThanAWallStayOpen) {
  const Lines lines = {{{0, 0}, {0, 2}}, {{0.6, 0}, {0.6, 2}}};
  EXPECT_EQ(close_wall_line_ends(lines).capped, 0);
}

TEST(WallLineEnds, ACornerARoundingBesideALineIsJoinedAcrossIt) {
  // A partition's end drawn as a corner (two lines meeting at (2, -0.00006)) 0.06 mm short
  // of a wall along y = 0: no line end there is free, nothing carries the corner on.
  const Lines lines = {{{0, 0}, {4, 0}}, {{2, -3}, {2, -0.00006}}, {{2, -0.00006}, {2.2, -0.00006}}};
  const WallLineEnds e = close_wall_line_ends(lines);
  EXPECT_EQ(e.free_ends, 3);  // the wall's two and the partition's far end, at y = -3
  ASSERT_GE(e.joined, 1);
  bool crosses = false;
  for (const auto& [a, b] : e.added)
    crosses = crosses || (length(a - Vec2{2, -0.00006}) < 1e-12 && b.y > 0.0004 && std::fabs(b.x - 2) < 1e-9);
  EXPECT_TRUE(crosses) << "a line from the corner to 0.5 mm past the wall";
  WallLineEndParams none;
  none.join = 0;
  EXPECT_EQ(close_wall_line_ends(lines, none).joined, 0);
}

TEST(WallLineEnds, PiecesOfOneFinelyDrawnCurveAreNotJoined) {
  // A quarter circle of radius 5 mm in 40 pieces of 0.2 mm: each piece's ends lie within
  // 2 mm of pieces further along, reached along the curve itself.
  Lines arc;
  for (int i = 0; i < 40; ++i) {
    const double a0 = 1.5707963267948966 * i / 40, a1 = 1.5707963267948966 * (i + 1) / 40;
    arc.push_back({{0.005 * std::cos(a0), 0.005 * std::sin(a0)}, {0.005 * std::cos(a1), 0.005 * std::sin(a1)}});
  }
  EXPECT_EQ(close_wall_line_ends(arc).joined, 0);
}

TEST(WallLineEnds, LinesAddedLaterAreJoinedToTheCornersBesideThem) {
  // A door's closing line along a wall's face, added once the walls are closed, passing
  // 0.006 mm beside the jamb's corner at (1, 0), its own end beside the jamb's face line.
  const Lines lines = {{{1, 0}, {1, -0.2}}, {{1, 0}, {0.8, 0}}, {{0.97, 0.000006}, {2.03, 0.000006}}};
  const auto added = join_wall_line_ends(lines, 2);
  // Each across both ways (snapping may land either on the other side), the corner once.
  EXPECT_EQ(added.size(), 4u);
  EXPECT_TRUE(join_wall_line_ends(lines, 3).empty()) << "only pairs with a line added later";
}

}  // namespace
}  // namespace avenues

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

}  // namespace
}  // namespace avenues

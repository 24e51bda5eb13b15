// Tests of the walkthrough's frame budget (app/frame_budget.h): the steps it drops detail
// by, when it brings detail back, and that a still eye always gets full detail.
#include <gtest/gtest.h>

#include "app/frame_budget.h"

using avenues::app::Detail;
using avenues::app::FrameBudget;

TEST(FrameBudget, OverBudgetWhileMovingDropsSamplesThenResolutionThenFarObjectsOneStepAFrame) {
  FrameBudget b(16.7, 16);
  const Detail steps[] = {{16, 1}, {4, 1}, {1, 1}, {1, 2}, {1, 4}, {1, 4, true, 16}, {1, 4, true, 8}, {1, 4, true, 8}};
  for (const Detail& d : steps) {
    EXPECT_EQ(b.next(true), d) << to_string(b.next(true));
    EXPECT_EQ(b.next(false), (Detail{16, 1})) << "a still eye gets full detail";
    b.measured(40, true);
  }
  EXPECT_EQ(to_string(Detail{1, 4}), "quarter resolution, 1 sample");
  EXPECT_EQ(to_string(b.next(true)), "quarter resolution, 1 sample, no objects beyond 8 m");
  // One sample asked for: resolution is all there is to drop.
  FrameBudget one(16.7, 1);
  one.measured(20, true);
  EXPECT_EQ(one.next(true), (Detail{1, 2}));
}

// A plan lit by its own lamps: after the samples, the light at the eye (no shadows to
// draw) goes before the pixels do, and stays while resolution drops.
TEST(FrameBudget, APlanLitByItsLampsGivesThemUpBeforeItsPixels) {
  FrameBudget b(16.7, 4, true);
  const Detail steps[] = {{4, 1, true}, {1, 1, true}, {1, 1, false}, {1, 2, false}, {1, 4, false}, {1, 4, false, 16}};
  for (const Detail& d : steps) {
    EXPECT_EQ(b.next(true), d) << to_string(b.next(true));
    EXPECT_EQ(b.next(false), (Detail{4, 1, true})) << "a still eye gets full detail, lamps and all";
    b.measured(40, true);
  }
  EXPECT_EQ(to_string(Detail{1, 1, false}), "1 sample, the light at the eye");
  EXPECT_EQ(to_string(b.next(true)), "quarter resolution, 1 sample, the light at the eye, no objects beyond 8 m");
}

TEST(FrameBudget, DetailComesBackOneStepAfterHalfASecondWellUnderBudget) {
  FrameBudget b(16.7, 4);
  b.measured(30, true), b.measured(30, true);
  ASSERT_EQ(b.next(true), (Detail{1, 2}));
  for (int i = 0; i + 1 < FrameBudget::kSettle; ++i) b.measured(5, true);
  EXPECT_EQ(b.next(true), (Detail{1, 2})) << "not before kSettle fast frames";
  b.measured(12, true);  // under budget but not well under: the count starts again
  for (int i = 0; i + 1 < FrameBudget::kSettle; ++i) b.measured(5, true);
  EXPECT_EQ(b.next(true), (Detail{1, 2}));
  b.measured(5, true);
  EXPECT_EQ(b.next(true), (Detail{1, 1}));
  // Frames of a still eye (the refinement) teach the budget nothing.
  b.measured(100, false);
  EXPECT_EQ(b.next(true), (Detail{1, 1}));
}

TEST(FrameBudget, NoBudgetMeansFullDetailAlways) {
  FrameBudget b(0, 4);
  b.measured(100, true);
  EXPECT_EQ(b.next(true), (Detail{4, 1}));
}

// The first frame at a picture size (the window's first, or the first after a resize or a
// step of resolution) pays once for the texture made for it, and the first of all for the
// GL pipeline's start: it does not count against the budget. The next one does.
TEST(FrameBudget, TheFirstFrameAtASizeIsNotCounted) {
  FrameBudget b(16.7, 1);
  b.measured(62, true, 1280, 720);
  EXPECT_EQ(b.next(true), (Detail{1, 1})) << "the window's first frame";
  EXPECT_EQ(b.last_ms(), 62);
  b.measured(20, true, 1280, 720);
  EXPECT_EQ(b.next(true), (Detail{1, 2})) << "the second frame over budget drops a step";
  b.measured(40, true, 640, 360);
  EXPECT_EQ(b.next(true), (Detail{1, 2})) << "the first frame at half resolution";
  b.measured(40, true, 640, 360);
  EXPECT_EQ(b.next(true), (Detail{1, 4}));
}

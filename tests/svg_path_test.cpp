// SVG paths as polygons (plans/formats/svg_path.h): Sweet Home 3D's cut-out shapes, arcs
// and curves flattened, every command in both cases, and what breaks the grammar refused.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "plans/formats/svg_path.h"

using namespace avenues;

namespace {

double area(const std::vector<Vec2>& p) { return std::fabs(signed_area(p)); }

}  // namespace

// Sweet Home's own cut-outs: the square, a circle of two arcs, an arch (a rectangle under
// half an ellipse), a half ellipse standing on its chord; each closes, and encloses the
// area its geometry says within what 16 pieces a half turn leave out.
TEST(SvgPath, SweetHomesCutOutShapesEncloseWhatTheirGeometrySays) {
  const double pi = std::numbers::pi;
  const struct {
    const char* d;
    double area;
  } shapes[] = {
      {"M0,0 v1 h1 v-1 z", 1.0},
      {"M0,0.5 a0.5,0.5 0 1,0 1,0 a0.5,0.5 0 1,0 -1,0 z", pi / 4},
      {"M0,1 v-0.788 a0.5,0.2 0 1,1 1,0 v0.788 z", 0.788 + pi * 0.5 * 0.2 / 2},
      {"M0,1 a0.5,0.997 0 1,1 1,0 z", pi * 0.5 * 0.997 / 2},
  };
  for (const auto& s : shapes) {
    SCOPED_TRACE(s.d);
    const auto polys = svg_path_polygons(s.d);
    ASSERT_TRUE(polys.has_value());
    ASSERT_EQ(polys->size(), 1u);
    EXPECT_NEAR(area(polys->front()), s.area, 0.01 * s.area);
    for (Vec2 p : polys->front()) {  // within the unit square
      EXPECT_GE(p.x, -1e-9);
      EXPECT_LE(p.x, 1 + 1e-9);
      EXPECT_GE(p.y, -1e-9);
      EXPECT_LE(p.y, 1 + 1e-9);
    }
  }
  // The arch's top is the ellipse's: 0.2 above its springing at the middle.
  const auto arch = svg_path_polygons("M0,1 v-0.788 a0.5,0.2 0 1,1 1,0 v0.788 z");
  double top = 1;
  for (Vec2 p : arch->front()) top = std::min(top, p.y);
  EXPECT_NEAR(top, 0.012, 1e-3);
}

// Every command, absolute and relative: the same square four ways, Béziers through their
// ends, an arc whose radii are too small scaled up to a half circle on its chord, and
// numbers run together as SVG allows ("1-2", ".5.5", flags touching).
TEST(SvgPath, EveryCommandInEitherCase) {
  for (const char* d : {"M0 0 L1 0 L1 1 L0 1 Z", "m0,0 l1,0 l0,1 l-1,0 z", "M0,0 H1 V1 H0 Z", "M0,0 1,0 1,1 0,1z"}) {
    SCOPED_TRACE(d);
    const auto p = svg_path_polygons(d);
    ASSERT_TRUE(p.has_value());
    ASSERT_EQ(p->size(), 1u);
    EXPECT_NEAR(area(p->front()), 1.0, 1e-12);
    EXPECT_EQ(p->front().size(), 4u);
  }
  // A cubic and its smooth continuation, and a quadratic and its: through their ends.
  const auto c = svg_path_polygons("M0,0 C0,1 1,1 1,0 S2,-1 2,0 Q2.5,1 3,0 T4,0 Z", 8);
  ASSERT_TRUE(c.has_value());
  for (Vec2 end : {Vec2{1, 0}, Vec2{2, 0}, Vec2{3, 0}, Vec2{4, 0}}) {
    bool found = false;
    for (Vec2 p : c->front()) found |= length(p - end) < 1e-12;
    EXPECT_TRUE(found) << end.x;
  }
  // The S reflects the C's second control point: its curve dips below the line.
  double lowest = 0;
  for (Vec2 p : c->front()) lowest = std::min(lowest, p.y);
  EXPECT_LT(lowest, -0.5);
  // Radii too small for the chord: scaled up to the half circle on it.
  const auto a = svg_path_polygons("M0,0 A0.1,0.1 0 0,1 2,0 Z");
  ASSERT_TRUE(a.has_value());
  EXPECT_NEAR(area(a->front()), std::numbers::pi / 2, 0.02);  // (16 pieces a half turn)
  const auto packed = svg_path_polygons("M0,0h1v1h-1z m.5.5l1-2");
  ASSERT_TRUE(packed.has_value());
  ASSERT_EQ(packed->size(), 2u);
  EXPECT_EQ(packed->back().back(), (Vec2{1.5, -1.5}));
  const auto flags = svg_path_polygons("M0,0a1,1 0 011,1z");
  ASSERT_TRUE(flags.has_value());
  EXPECT_GT(flags->front().size(), 3u);
}

TEST(SvgPath, WhatBreaksTheGrammarIsRefused) {
  // (Numbers after a closepath once looped in place for ever: found by fuzzing.)
  for (const char* d : {"M0", "X1,1", "1,1", "M0,0 L1", "M0,0 A1,1 0 2,0 1,1", "M0,0 Lnan,1", "M0,0 L1e999,0",
                        "M0,0 h1 v1 z 5", "M0,0 h1 v1 Z1,1"})
    EXPECT_FALSE(svg_path_polygons(d).has_value()) << d;
  const auto empty = svg_path_polygons("");
  ASSERT_TRUE(empty.has_value());
  EXPECT_TRUE(empty->empty());
}

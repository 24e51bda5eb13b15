// Sloped walls (Wall::height_at_end): a wall whose top is a plane, as a gable under a roof
// is, and the cells above it, whose floor that plane is (general convex polyhedra, not
// prisms). The free space is exactly what the slope leaves, the views agree with rays cast
// through the complex, the top's edges are real lines, and the hard cases (a top through
// the ceiling, down to the floor, across an opening's head, across another wall's top)
// stay sound.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "cells/build_cells.h"
#include "plans/plan.h"
#include "plans/plan_writer.h"
#include "ray_oracle.h"
#include "test_plans.h"
#include "visibility/visible_set.h"

using namespace avenues;
using avenues::testing::wall;

namespace {

/// An 8 m × 4 m attic, 2.5 m high, its outer wall 0.3 m thick, cut in two at x = 4 by a
/// wall 0.2 m thick whose top runs from `h0` at y = 0 to `h1` at y = 4.
Plan attic(double h0, double h1) {
  Plan p;
  p.name = "attic";
  p.far_margin = 5;
  p.storeys.push_back({"attic", 0, 2.5, 0.3, {}});
  p.walls.push_back(wall("outer", {{0, 0}, {8, 0}, {8, 4}, {0, 4}, {0, 0}}, 0.3));
  Wall gable = wall("gable", {{4, 0}, {4, 4}}, 0.2);
  gable.height = h0;
  gable.height_at_end = h1;
  p.walls.push_back(gable);
  Room west, east;
  west.name = "west";
  west.label = Vec2{2, 2};
  east.name = "east";
  east.label = Vec2{6, 2};
  p.rooms = {west, east};
  return p;
}

Opening window(double at, double width, double sill, double head) {
  Opening o;
  o.name = "window";
  o.kind = OpeningKind::Window;
  o.at = at, o.width = width, o.sill = sill, o.head = head;
  return o;
}

/// Views from random eyes in the rooms (and the outside), each checked against rays cast
/// through the complex, and points inside and above the sloped wall located as solid or
/// free as the slope says.
void expect_sound(const Plan& plan, const std::string& what, int views = 24) {
  SCOPED_TRACE(what);
  const CellComplex c = build_cells(plan);
  ASSERT_EQ(cells_are_valid(c), "");
  std::mt19937 rng(7);
  int checked = 0;
  for (int k = 0; k < views; ++k) {
    CellId cell = kNoCell;
    const Vec3 eye = avenues::testing::random_eye(c, rng, cell);
    std::uniform_real_distribution<double> turn(0, 2 * std::acos(-1.0)), pitch(-0.4, 0.4);
    const double a = turn(rng), b = pitch(rng);
    const Vec3 facing{std::cos(a), std::sin(a), b};
    const Camera cam = Camera::look_at(eye, eye + facing, 80, 64, 40);
    const Location at = c.locate(cam.eye, facing);
    if (at.what != Location::What::Cell) continue;
    const VisibleSet vs = find_visible(c, cam, at.cell, Kernel::Double);
    const avenues::testing::OracleResult r = avenues::testing::check_visible_set(c, cam, vs);
    EXPECT_EQ(r.missing, 0) << "eye " << eye.x << ", " << eye.y << ", " << eye.z;
    EXPECT_EQ(r.extra, 0) << "eye " << eye.x << ", " << eye.y << ", " << eye.z;
    ++checked;
  }
  EXPECT_GE(checked, views / 2);
  // Along every sloped wall's centre line: solid a centimetre below its top, free a
  // centimetre above it (where the top is within the storey, and away from its openings).
  for (const Wall& w : plan.walls) {
    if (w.height_at_end < 0) continue;
    const Storey& st = plan.storeys[size_t(w.storey)];
    double total = 0;
    for (size_t i = 0; i + 1 < w.centre.size(); ++i) total += length(w.centre[i + 1] - w.centre[i]);
    double along = 0;
    for (size_t i = 0; i + 1 < w.centre.size(); ++i) {
      const double len = length(w.centre[i + 1] - w.centre[i]);
      for (double f : {0.1, 0.3, 0.7, 0.9}) {  // (not the middle, where another wall may meet it)
        const double s = along + f * len;
        bool in_opening = false;
        for (const Opening& o : w.openings) in_opening |= s > o.at - 0.05 && s < o.at + o.width + 0.05;
        if (in_opening) continue;
        const Vec2 p = w.centre[i] + f * (w.centre[i + 1] - w.centre[i]);
        const Vec2 from = plan.walls[0].centre[0];  // not inside the attic's outer wall
        if (std::min({p.x - from.x, p.y - from.y, from.x + 8 - p.x, from.y + 4 - p.y}) < 0.25) continue;
        const double top = w.top_at(s);
        EXPECT_NEAR(total, w.length(), 1e-9);
        if (top > 0.02 && top < st.height + 0.01) {
          EXPECT_EQ(c.locate({p.x, p.y, st.elevation + top - 0.01}).what, Location::What::Solid) << "below the top at " << s;
        }
        if (top > -0.01 && top < st.height - 0.02) {
          EXPECT_EQ(c.locate({p.x, p.y, st.elevation + top + 0.01}).what, Location::What::Cell) << "above the top at " << s;
        }
      }
      along += len;
    }
  }
}

}  // namespace

// The gable rises 0.5 m to 2.5 m along 4 m: over it, between the outer wall's inner faces
// (y = 0.15 … 3.85), free space of 0.2 m × ∫(2.5 − top) = 0.74 m³, in cells whose floor is
// the top; each face of the wall meets the top in one straight line, the wall's convex
// edge, and nothing else on it is a line.
TEST(SlopedWalls, TheSpaceOverAGableIsWhatItsSlopeLeavesAndItsEdgesAreLines) {
  const CellComplex c = build_cells(attic(0.5, 2.5));
  ASSERT_EQ(cells_are_valid(c), "");
  double volume = 0;
  int over = 0;
  for (const Cell& cell : c.cells) {
    if (cell.kind != CellKind::Doorway) continue;
    EXPECT_FALSE(cell.prism);
    volume += cell.volume();
    ++over;
  }
  EXPECT_EQ(over, 1);  // one cell, not steps
  EXPECT_NEAR(volume, 0.2 * ((2 * 3.85 - 0.25 * 3.85 * 3.85) - (2 * 0.15 - 0.25 * 0.15 * 0.15)), 1e-9);
  int sloped_lines = 0;
  for (const RealLine& l : c.lines) {
    const Vec3 d = l.b - l.a;
    if (d.z == 0 || (d.x == 0 && d.y == 0)) continue;
    ++sloped_lines;
    EXPECT_EQ(l.kind, LineKind::Convex);
    EXPECT_NEAR(std::fabs(l.a.x - 4), 0.1, 1e-9);
    EXPECT_NEAR(std::fabs(d.z / d.y), 0.5, 1e-9);  // the slope
    EXPECT_NEAR(std::fabs(d.y), 3.7, 1e-9);        // face to face of the outer wall
  }
  EXPECT_EQ(sloped_lines, 2);
  expect_sound(attic(0.5, 2.5), "gable");
}

// The hard cases: a top that rises through the ceiling (cut there, a wedge up to it), one
// that falls to the floor, a window whose head the top passes over its width, a low wall
// meeting the gable at a T whose height the top passes inside the overlap, two sloped
// walls meeting at a corner, a curved sloped wall, and the whole of it far from the origin.
TEST(SlopedWalls, HardCasesAgreeWithRaysAndLocateAsTheSlopeSays) {
  expect_sound(attic(1.0, 4.0), "through the ceiling");
  expect_sound(attic(0.0, 2.0), "from the floor");
  {
    Plan p = attic(0.5, 2.5);
    p.walls[1].openings.push_back(window(1.0, 1.2, 0.2, 1.3));  // the top passes 1.3 m at y = 1.6
    expect_sound(p, "a window's head under the slope");
  }
  // A wall from the gable east to the outer wall at y = 2, cutting the east room in two.
  auto with_t = [](Wall w) {
    Plan p = attic(0.5, 2.5);
    p.walls.push_back(std::move(w));
    Room ne;
    ne.name = "north-east";
    ne.label = Vec2{6, 3};
    p.rooms[1].label = Vec2{6, 1};
    p.rooms.push_back(ne);
    return p;
  };
  {
    Wall low = wall("low", {{4, 2}, {8, 2}}, 0.1);
    low.height = 1.5;  // the gable's top passes 1.5 m at y = 2, inside their overlap
    expect_sound(with_t(low), "a low wall at a T");
  }
  {
    Wall other = wall("other gable", {{4, 2}, {8, 2}}, 0.2);
    other.height = 2.0;
    other.height_at_end = 0.3;
    expect_sound(with_t(other), "two sloped walls at a T");
  }
  {
    Plan p = attic(0.5, 2.5);
    // A quarter circle of 8 pieces about (8, 0) from (4, 0) to the corner (8, 4), rising
    // 0.3 m to 2.2 m.
    std::vector<Vec2> arc;
    for (int k = 0; k <= 8; ++k) {
      const double t = std::acos(-1.0) / 2 * k / 8;
      arc.push_back({8 - 4 * std::cos(t), 4 * std::sin(t)});
    }
    p.walls[1] = wall("curved", arc, 0.15);
    p.walls[1].height = 0.3;
    p.walls[1].height_at_end = 2.2;
    p.rooms[1].label = Vec2{7, 1};
    expect_sound(p, "curved");
  }
  {
    Plan p = attic(0.5, 2.5);
    for (Wall& w : p.walls)
      for (Vec2& v : w.centre) v = v + Vec2{5.4e6, 5.4e6};
    for (Room& r : p.rooms) r.label = *r.label + Vec2{5.4e6, 5.4e6};
    expect_sound(p, "5,400 km from the origin", 12);
  }
}

// A gable that is one wall (Wall::top_bends): from 0.5 m at y = 0 up to its ridge, 3.5 m at
// y = 2 (through the 2.5 m ceiling), and down to 1.0 m at y = 4. The free space over it is
// the integral of what each slope leaves under the ceiling, its rising edges are the only
// sloped lines (two per face on each side of the ridge's cut), and the bent tops' hard
// cases agree with the rays: a bend under the ceiling, a level piece between two slopes,
// an opening across a bend, two bends on a wall of two segments, and all of it 5,400 km out.
TEST(SlopedWalls, AWallsTopBendsAtItsRidgeAndEachPieceIsAPlane) {
  Plan p = attic(0.5, 1.0);
  p.walls[1].top_bends = {{2, 3.5}};
  EXPECT_NEAR(p.walls[1].top_at(1), 2.0, 1e-12);
  EXPECT_NEAR(p.walls[1].top_at(3), 2.25, 1e-12);
  const CellComplex c = build_cells(p);
  ASSERT_EQ(cells_are_valid(c), "");
  // Free over y in [0.15, 3.85] under the 2.5 m ceiling: rising 1.5 m a metre from 0.5 m,
  // it meets the ceiling at y = 4/3; falling 1.25 m a metre to 1.0 m, it leaves it at y = 2.8.
  auto gap_rising = [](double y) { return 2.5 * y - (0.5 * y + 0.75 * y * y); };     // ∫ (2.5 − top)
  auto gap_falling = [](double y) { return 2.5 * y - (6.0 * y - 0.625 * y * y); };   // top = 6 − 1.25 y
  const double expected =
      0.2 * ((gap_rising(4.0 / 3) - gap_rising(0.15)) + (gap_falling(3.85) - gap_falling(2.8)));
  double volume = 0;
  for (const Cell& cell : c.cells)
    if (cell.kind == CellKind::Doorway) volume += cell.volume();
  EXPECT_NEAR(volume, expected, 1e-9);
  int sloped_lines = 0;
  for (const RealLine& l : c.lines) {
    const Vec3 d = l.b - l.a;
    if (d.z == 0 || (d.x == 0 && d.y == 0)) continue;
    ++sloped_lines;
    EXPECT_NEAR(std::fabs(l.a.x - 4), 0.1, 1e-9);
    EXPECT_TRUE(std::fabs(std::fabs(d.z / d.y) - 1.5) < 1e-9 || std::fabs(std::fabs(d.z / d.y) - 1.25) < 1e-9)
        << d.z / d.y;
  }
  EXPECT_EQ(sloped_lines, 4);
  expect_sound(p, "a ridge through the ceiling");
  {
    Plan q = attic(0.5, 0.3);
    q.walls[1].top_bends = {{1.5, 2.0}};  // a ridge under the ceiling
    q.walls[1].openings.push_back(window(1.0, 1.0, 0.2, 1.1));  // across the bend
    expect_sound(q, "a ridge under the ceiling, a window across it");
  }
  {
    Plan q = attic(0.2, 0.4);
    q.walls[1].top_bends = {{1.0, 1.8}, {3.0, 1.8}};  // level between two slopes
    expect_sound(q, "a level piece between slopes");
  }
  {
    Plan q = attic(0.5, 1.0);
    q.walls[1] = wall("bent", {{4, 0}, {4, 2}, {6, 4}}, 0.2);  // 2 + 2.83 m
    q.walls[1].height = 0.5;
    q.walls[1].height_at_end = 1.0;
    q.walls[1].top_bends = {{1.0, 2.0}, {3.0, 1.2}};  // one on each segment
    q.rooms[1].label = Vec2{7, 1};
    expect_sound(q, "bends on two segments");
  }
  {
    Plan q = p;
    for (Wall& w : q.walls)
      for (Vec2& v : w.centre) v = v + Vec2{5.4e6, 5.4e6};
    for (Room& r : q.rooms) r.label = *r.label + Vec2{5.4e6, 5.4e6};
    expect_sound(q, "a ridge 5,400 km from the origin", 12);
  }
}

// The plan format: `height_at_end` reads, writes and reads back; without `height`, below
// zero or on a wall of no thickness it is an error naming the wall.
TEST(SlopedWalls, ThePlanFormatReadsAndWritesThem) {
  const std::string base = R"(name = "g"
[[storey]]
name = "s"
height = 2.5
[[wall]]
name = "gable"
path = [[0, 0], [4, 0]]
)";
  const Plan p = parse_plan(base + "height = 0.5\nheight_at_end = 3\n", "g.toml");
  ASSERT_EQ(p.walls.size(), 1u);
  EXPECT_EQ(p.walls[0].height, 0.5);
  EXPECT_EQ(p.walls[0].height_at_end, 3);  // above the ceiling: cut there
  const Plan again = parse_plan(plan_as_toml(p), "again.toml");
  EXPECT_EQ(again.walls[0].height, 0.5);
  EXPECT_EQ(again.walls[0].height_at_end, 3);
  const Plan bent = parse_plan(base + "height = 0.5\nheight_at_end = 1\ntop_bends = [[1.5, 3], [2.5, 2.75]]\n", "g.toml");
  ASSERT_EQ(bent.walls[0].top_bends.size(), 2u);
  EXPECT_EQ(bent.walls[0].top_bends[1], (Vec2{2.5, 2.75}));
  EXPECT_EQ(parse_plan(plan_as_toml(bent), "again.toml").walls[0].top_bends, bent.walls[0].top_bends);
  for (const auto& [extra, says] : std::vector<std::pair<std::string, std::string>>{
           {"height = 1\nheight_at_end = 1\ntop_bends = [[4, 2]]\n", "before the end"},
           {"height = 1\nheight_at_end = 1\ntop_bends = [[2, 2], [1, 2]]\n", "after the bend before it"},
           {"height = 1\nheight_at_end = 1\ntop_bends = [[2, -2]]\n", "must be >= 0"},
           {"height = 1\ntop_bends = [[2, 2]]\n", "needs 'height' and 'height_at_end'"},
           {"height = 1\nheight_at_end = 1\ntop_bends = []\n", "[along, height] pairs"},
           {"height_at_end = 1\n", "needs 'height'"},
           {"height = 1\nheight_at_end = -1\n", "must be >= 0"},
           {"height = 1\nheight_at_end = 2\nthickness = 0\n", "no thickness"},
       }) {
    try {
      parse_plan(base + extra, "bad.toml");
      ADD_FAILURE() << extra;
    } catch (const PlanError& e) {
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("gable"), std::string::npos) << e.what();
    }
  }
}

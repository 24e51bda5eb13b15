// Tests of visibility/walker.h: the walking eye stays in free space, walks through doors
// but not windows, slides along walls, follows floors and climbs the stairwell; and, on
// every bundled plan, thousands of random moves never put it inside a solid.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "cells/build_cells.h"
#include "cells/mesh_scene.h"
#include "plans/formats/doom_map.h"
#include "test_meshes.h"
#include "test_plans.h"
#include "visibility/viewpoint.h"
#include "visibility/walker.h"

using namespace avenues;
using avenues::testing::plan_path;
using avenues::testing::room_named;

namespace {

const CellComplex& two_storey() {
  static const CellComplex c = build_cells(read_plan(plan_path("two-storey-house.toml")));
  return c;
}

std::string room_of(const CellComplex& c, Vec3 p) {
  const Location at = c.locate(p);
  if (at.what != Location::What::Cell) return "<solid>";
  const Cell& cell = c.cells[size_t(at.cell)];
  return cell.room >= 0 ? c.rooms[size_t(cell.room)].name : std::string(to_string(cell.kind));
}

/// Walks towards `goal` (horizontally) in steps of `step` metres for at most `steps` steps.
void walk_towards(Walker& w, Vec2 goal, int steps, double step = 0.05) {
  for (int i = 0; i < steps; ++i) {
    Vec3 d{goal.x - w.eye().x, goal.y - w.eye().y, 0};
    const double l = length(d);
    if (l < 1e-6) return;
    w.move((std::min(step, l) / l) * d, 1.0 / 60);
  }
}

}  // namespace

TEST(Walker, CastStopsAtTheFirstWallAndPassesPortals) {
  const CellComplex& c = two_storey();
  // From the hall eastwards at knee height: through the hall-living door (x = 4, y 1.5–2.4)
  // into the living room, and on to the east wall's inner face at x = 9.85, below the sill
  // of its window (y 1.5–3.5, sill 0.9 m).
  const Vec3 a{2, 2, 0.5}, b{12, 2, 0.5};
  const SegmentCast s = cast_segment(c, c.locate(a).cell, a, b);
  EXPECT_TRUE(s.blocked);
  EXPECT_NEAR(a.x + s.t * (b.x - a.x), 9.85, 1e-6);
  EXPECT_NEAR(s.normal.x, 1, 1e-9);
  EXPECT_EQ(room_of(c, a + (s.t * 0.999) * (b - a)), "living room");
  // At eye height the same segment leaves through the window, into the outside.
  const Vec3 e{2, 2, 1.6}, f{12, 2, 1.6};
  const SegmentCast out = cast_segment(c, c.locate(e).cell, e, f);
  EXPECT_FALSE(out.blocked);
  EXPECT_EQ(c.cells[size_t(out.cell)].kind, CellKind::Outside);
  // At y = 3 the middle wall stops it (the door ends at y = 2.4).
  const Vec3 a2{2, 3, 1.6}, b2{6, 3, 1.6};
  const SegmentCast s2 = cast_segment(c, c.locate(a2).cell, a2, b2);
  EXPECT_TRUE(s2.blocked);
  EXPECT_NEAR(a2.x + s2.t * (b2.x - a2.x), 3.9, 1e-6);
  // A segment that stays in the room is not blocked and ends in the cell holding its end.
  const SegmentCast s3 = cast_segment(c, c.locate(e).cell, e, {3, 3, 1.5});
  EXPECT_FALSE(s3.blocked);
  EXPECT_EQ(s3.t, 1);
  EXPECT_TRUE(c.cells[size_t(s3.cell)].contains({3, 3, 1.5}, 1e-9));
}

TEST(Walker, WalksThroughADoorButNotAWall) {
  const CellComplex& c = two_storey();
  Walker w(c, {2, 1.95, 1.6});
  ASSERT_EQ(room_of(c, w.eye()), "hall");
  walk_towards(w, {6, 1.95}, 200);
  EXPECT_EQ(room_of(c, w.eye()), "living room");
  EXPECT_NEAR(w.eye().x, 6, 1e-9);
  EXPECT_NEAR(w.eye().z, 1.6, 1e-9);
  // Straight at the middle wall where it has no door: the eye stops a clearance short of it.
  Walker v(c, {2, 3.2, 1.6});
  walk_towards(v, {6, 3.2}, 200);
  EXPECT_EQ(room_of(c, v.eye()), "hall");
  EXPECT_NEAR(v.eye().x, 3.9 - v.options().clearance, 0.051);
  EXPECT_LE(v.eye().x, 3.9 - v.options().clearance + 1e-9);
}

TEST(Walker, SlidesAlongAWall) {
  const CellComplex& c = two_storey();
  // Diagonally into the hall's west wall (inner face x = 0.15): x stops, y carries on.
  Walker w(c, {1.0, 1.0, 1.6});
  for (int i = 0; i < 100; ++i) w.move({-0.03, 0.02, 0}, 1.0 / 60);
  EXPECT_NEAR(w.eye().x, 0.15 + w.options().clearance, 0.031);
  EXPECT_GT(w.eye().y, 2.5);
  EXPECT_EQ(room_of(c, w.eye()), "hall");
}

TEST(Walker, WalkModeStopsAtAWindowFlyModePassesIt) {
  const CellComplex& c = two_storey();
  // The living room's south window: along the outer wall from x = 6 to 8, sill 0.9, head 2.1.
  Walker w(c, {7, 2, 1.6});
  walk_towards(w, {7, -2}, 200);
  EXPECT_EQ(room_of(c, w.eye()), "living room");
  EXPECT_GT(w.eye().y, 0.15);
  Walker f(c, {7, 2, 1.6});
  f.set_mode(MoveMode::Fly);
  for (int i = 0; i < 100; ++i) f.move({0, -0.05, 0}, 1.0 / 60);
  EXPECT_LT(f.eye().y, -0.5);
  EXPECT_EQ(room_of(c, f.eye()), "outside");
}

TEST(Walker, FallsToTheFloorAfterFlying) {
  const CellComplex& c = two_storey();
  Walker w(c, {7, 2, 1.6});
  w.set_mode(MoveMode::Fly);
  for (int i = 0; i < 40; ++i) w.move({0, 0, 0.05}, 1.0 / 60);
  EXPECT_GT(w.eye().z, 2.2);
  EXPECT_LT(w.eye().z, 2.6);  // under the ceiling, a clearance short
  w.set_mode(MoveMode::Walk);
  for (int i = 0; i < 120; ++i) w.move({}, 1.0 / 60);
  EXPECT_NEAR(w.eye().z, 1.6, 1e-9);
  EXPECT_NEAR(w.floor_below(), 0, 1e-9);
  // Walk mode refuses to go up where there is no stair.
  w.move({0, 0, 0.5}, 1.0 / 60);
  EXPECT_NEAR(w.eye().z, 1.6, 1e-9);
}

TEST(Walker, AroundAModelWithNoGroundTheEyeStandsAtItsFoot) {
  // A grid of open boxes (floors 0.2 m up, walls to 1.2 m) as a scene of meshes, which has
  // no ground of its own: beside the boxes nothing lies below but the far box's bottom. The
  // eye walks at eye height above the model's lowest point; a plan's walker has no such
  // ground (its floors and the outside's ground are faces).
  Mesh m = avenues::testing::open_boxes(2);
  for (Vec3& v : m.vertices) v.z += 0.2;
  const CellComplex c = build_mesh_scene({m});
  ASSERT_TRUE(c.storeys.empty());
  ASSERT_LT(c.far_box.lo.z, -0.5);
  Walker w(c, {-0.8, -0.8, 0.9});
  EXPECT_NEAR(w.ground(), 0.2, 1e-9);
  for (int i = 0; i < 120; ++i) w.move({}, 1.0 / 60);
  EXPECT_NEAR(w.floor_below(), 0.2, 1e-9);
  EXPECT_NEAR(w.eye().z, 0.2 + w.options().eye_height, 1e-9);
  // Along the grid's edge and back: still at its foot.
  for (int i = 0; i < 60; ++i) w.move({0.05, 0, 0}, 1.0 / 60);
  EXPECT_NEAR(w.eye().z, 0.2 + w.options().eye_height, 1e-9);
  // Flown below the model's foot, the eye falls to what lies below it, as before.
  w.set_mode(MoveMode::Fly);
  for (int i = 0; i < 40; ++i) w.move({0, 0, -0.05}, 1.0 / 60);
  ASSERT_LT(w.eye().z, 0.2);
  EXPECT_LT(w.floor_below(), c.far_box.lo.z + 1e-6);
  EXPECT_EQ(Walker(two_storey(), {7, 2, 1.6}).ground(), -HUGE_VAL);
}

TEST(Walker, ClimbsTheStairwellAndComesDownAgain) {
  const CellComplex& c = two_storey();
  // Under the hole in the upper floor (x 0.4–1.4, y 0.8–3.6), in the hall.
  Walker w(c, {0.9, 2.2, 1.6});
  ASSERT_TRUE(w.on_stair());
  for (int i = 0; i < 200; ++i) w.move({0, 0, 0.05}, 1.0 / 60);
  EXPECT_NEAR(w.eye().z, 2.9 + 1.6, 1e-9);
  EXPECT_EQ(room_of(c, w.eye()), "landing");
  // Off the stair onto the landing's floor, then away from the hole: the eye keeps its height.
  walk_towards(w, {2.5, 2.2}, 200);
  EXPECT_EQ(room_of(c, w.eye()), "landing");
  EXPECT_FALSE(w.on_stair());
  EXPECT_NEAR(w.eye().z, 4.5, 1e-9);
  EXPECT_NEAR(w.floor_below(), 2.9, 1e-9);
  // Back over the hole: the stair holds the eye until it goes down.
  walk_towards(w, {0.9, 2.2}, 200);
  EXPECT_TRUE(w.on_stair());
  EXPECT_NEAR(w.eye().z, 4.5, 1e-9);
  for (int i = 0; i < 200; ++i) w.move({0, 0, -0.05}, 1.0 / 60);
  EXPECT_NEAR(w.eye().z, 1.6, 1e-9);
  EXPECT_EQ(room_of(c, w.eye()), "hall");
  // Half way up, the slab's edge stops a walk off the stair.
  for (int i = 0; i < 27; ++i) w.move({0, 0, 0.05}, 1.0 / 60);
  ASSERT_GT(w.eye().z, 2.8);
  ASSERT_LT(w.eye().z, 3.3);
  const double z = w.eye().z;
  walk_towards(w, {2.5, 2.2}, 100);
  EXPECT_LE(w.eye().x, 1.4 + 1e-9);
  EXPECT_EQ(w.eye().z, z);
}

TEST(Walker, RefusesAStartInsideAWall) {
  const CellComplex& c = two_storey();
  EXPECT_THROW(Walker(c, {4, 3, 1.6}), std::runtime_error);
}

// The property: over thousands of random moves (walk and fly, turns, climbs, long and short
// steps) on every bundled plan, from the plan's viewpoint and from random rooms, the eye is
// always in a cell — located afresh, without a hint.
TEST(Walker, RandomMovesNeverEnterASolidOnAnyBundledPlan) {
  int plans = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(AVENUES_SOURCE_DIR) + "/plans")) {
    if (entry.path().extension() != ".toml") continue;
    ++plans;
    const CellComplex c = build_cells(read_plan(entry.path().string()));
    std::mt19937 rng(1971);
    std::uniform_real_distribution<double> u(-1, 1);
    std::uniform_int_distribution<int> kind(0, 19);
    std::uniform_int_distribution<size_t> any_cell(0, c.cells.size() - 1);
    // Starts: the viewpoint, then the centres of random room cells at eye height.
    std::vector<Vec3> starts = {default_viewpoint(c).eye};
    for (int tries = 0; tries < 1000 && starts.size() < 4; ++tries) {
      const Cell& k = c.cells[any_cell(rng)];
      if (k.kind != CellKind::Room || !k.prism) continue;
      const Vec2 m = centroid(k.footprint);
      const Vec3 p{m.x, m.y, std::min(k.z0 + 1.6, (k.z0 + k.z1) / 2)};
      if (c.locate(p).what == Location::What::Cell) starts.push_back(p);
    }
    double travelled = 0;
    for (const Vec3 start : starts) {
      Walker w(c, start);
      double heading = 0;
      for (int i = 0; i < 3000; ++i) {
        const int k = kind(rng);
        if (k == 0) w.set_mode(w.mode() == MoveMode::Walk ? MoveMode::Fly : MoveMode::Walk);
        heading += 0.3 * u(rng);
        const double stride = k < 3 ? 1.5 * std::fabs(u(rng)) : 0.08 * std::fabs(u(rng));  // now and then a long one
        const Vec3 d{stride * std::cos(heading), stride * std::sin(heading), k == 4 ? 0.3 * u(rng) : 0.02 * u(rng)};
        travelled += w.move(d, 1.0 / 60);
        const Location at = c.locate(w.eye());
        ASSERT_EQ(at.what, Location::What::Cell)
            << entry.path().filename() << " move " << i << ": the eye (" << w.eye().x << ", " << w.eye().y << ", "
            << w.eye().z << ") is " << (at.what == Location::What::Solid ? "inside " + at.solid : "outside the far box");
        ASSERT_TRUE(c.cells[size_t(w.cell())].contains(w.eye(), 1e-9)) << entry.path().filename() << " move " << i;
      }
    }
    EXPECT_GT(travelled, 20 * double(starts.size())) << entry.path().filename() << ": the eye hardly moved";
  }
  EXPECT_GE(plans, 5);
}

// The same on real maps: Freedoom's first levels, with a Doom player's eye and step (41 and
// 24 map units), stairs, raised floors, outdoor areas and all.
TEST(Walker, RandomMovesNeverEnterASolidOnFreedoomMaps) {
  for (const auto& [file, map] : {std::pair<std::string, std::string>{"freedoom1.wad", "E1M1"}, {"freedoom2.wad", "MAP01"}}) {
    const std::string wad = std::string(AVENUES_FREEDOOM_DIR) + "/" + file;
    if (!std::filesystem::exists(wad)) GTEST_SKIP() << wad << " is missing (apt-get install freedoom)";
    const CellComplex c = build_cells(read_doom_map(wad, map));
    WalkerOptions o;
    o.eye_height = kDoomEyeHeight;
    o.step_height = 24 * kDoomUnit;
    Walker w(c, default_viewpoint(c).eye, o);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    double heading = 0, travelled = 0;
    for (int i = 0; i < 6000; ++i) {
      if (i % 1500 == 1499) w.set_mode(w.mode() == MoveMode::Walk ? MoveMode::Fly : MoveMode::Walk);
      heading += 0.25 * u(rng);
      const Vec3 d{0.1 * std::cos(heading), 0.1 * std::sin(heading), 0.05 * u(rng)};
      travelled += w.move(d, 1.0 / 35);
      const Location at = c.locate(w.eye());
      ASSERT_EQ(at.what, Location::What::Cell) << file << ":" << map << " move " << i << ": the eye (" << w.eye().x
                                               << ", " << w.eye().y << ", " << w.eye().z << ") left free space";
    }
    EXPECT_GT(travelled, 30) << file << ":" << map;
  }
}

// A large soup cuts space by its largest surfaces only; the rest is detail, drawn in the
// cells it crosses (cells/soup_detail.h). A wall that is detail is still a wall to the
// walker: a move stops at its triangles as at an opaque face, from either side, in walk
// and fly mode alike, where the same scene decomposed whole stops at the wall's faces.
TEST(Walker, AWallThatIsASoupsDetailStopsTheEyeAsAFaceWould) {
  // A floor 10 × 10 m and a wall across it at x = 3, 3 m high.
  const Mesh floor = avenues::testing::mesh_from({{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0}}, {{0, 1, 2, 3}});
  const Mesh wall = avenues::testing::mesh_from({{3, 0, 0}, {3, 10, 0}, {3, 10, 3}, {3, 0, 3}}, {{0, 1, 2, 3}});
  const std::vector<Mesh> meshes{floor, wall};
  MeshSceneParams split;
  split.detail_above = 0;
  split.structural_triangles = 2;  // the floor only
  const CellComplex detail = build_mesh_scene(meshes, split), whole = build_mesh_scene(meshes);
  ASSERT_FALSE(detail.objects.empty()) << "the wall is detail";
  ASSERT_TRUE(whole.objects.empty()) << "the wall cuts space";
  ASSERT_EQ(detail.detail_start.size(), detail.cells.size() + 1);
  EXPECT_EQ(detail.detail_boxes.size(), detail.objects.size());
  for (const CellComplex* c : {&detail, &whole}) {
    SCOPED_TRACE(c == &detail ? "the wall as detail" : "the wall cutting space");
    const Vec3 a{1, 5, 1.6}, b{5, 5, 1.6};
    const SegmentCast across = cast_segment(*c, c->locate(a).cell, a, b);
    EXPECT_TRUE(across.blocked);
    EXPECT_NEAR(across.t, 0.5, 1e-9);
    EXPECT_NEAR(across.normal.x, 1, 1e-9) << "out of the free space the segment leaves";
    const SegmentCast back = cast_segment(*c, c->locate(b).cell, b, a);
    EXPECT_TRUE(back.blocked) << "from the other side";
    EXPECT_NEAR(back.t, 0.5, 1e-9);
    EXPECT_NEAR(back.normal.x, -1, 1e-9);
    EXPECT_FALSE(cast_segment(*c, c->locate(a).cell, a, {2, 9, 1.6}).blocked) << "along the wall";
    EXPECT_FALSE(cast_segment(*c, c->locate(a).cell, a, {4, 5, 4.6}).blocked) << "over its top";
    for (MoveMode mode : {MoveMode::Walk, MoveMode::Fly}) {
      Walker w(*c, a);
      w.set_mode(mode);
      walk_towards(w, {6, 5}, 200);
      EXPECT_LT(w.eye().x, 3 - w.options().clearance + 1e-9) << to_string(mode);
      EXPECT_GT(w.eye().x, 3 - w.options().clearance - 0.06) << to_string(mode) << ": it walked up to the wall";
    }
  }
  // A segment starting on the detail wall's plane leaves it, either way.
  const Vec3 on{3, 5, 1.6};
  EXPECT_FALSE(cast_segment(detail, detail.locate(on).cell, on, {1, 5, 1.6}).blocked);
}

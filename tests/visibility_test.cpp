// Tests of visibility/: the avenues of sight against an independent ray-casting oracle,
// on Jones's house and every bundled plan, and the hard cases of the visibility issue.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <random>
#include <set>

#include "cells/build_cells.h"
#include "ray_oracle.h"
#include "visibility/route.h"
#include "visibility/visible_set.h"
#include "test_plans.h"

using namespace avenues;
using avenues::testing::plan_path;
using avenues::testing::room_named;
using avenues::testing::check_visible_set;
using avenues::testing::OracleResult;

using avenues::testing::random_eye;

TEST(Visibility, JonesKitchenIsSeenThroughTheDoorAndSeparatelyThroughTheHatch) {
  CellComplex c = build_cells(read_plan(plan_path("jones-house.toml")));
  Camera cam = Camera::look_at({1.0, 0.5, 1.2}, {6, 3, 1.2}, 100, 400, 300);
  Location loc = c.locate(cam.eye);
  ASSERT_EQ(loc.what, Location::What::Cell);
  const RoomId K = room_named(c, "K"), D = room_named(c, "D");
  ASSERT_GE(K, 0);
  for (Kernel k : {Kernel::Double, Kernel::Exact}) {
    VisibleSet vs = find_visible(c, cam, loc.cell, k);
    int direct = 0, via_hatch = 0;
    for (size_t a = 0; a < vs.avenues.size(); ++a) {
      if (c.cells[size_t(vs.avenues[a].cell)].room != K) continue;
      bool through_dining = false;
      for (PortalId p : vs.path(int(a))) {
        const Portal& portal = c.portals[size_t(p)];
        through_dining |= c.cells[size_t(portal.cell[0])].room == D || c.cells[size_t(portal.cell[1])].room == D;
      }
      (through_dining ? via_hatch : direct)++;
    }
    EXPECT_GE(direct, 1) << to_string(k);
    EXPECT_GE(via_hatch, 1) << to_string(k);
    OracleResult r = check_visible_set(c, cam, vs, 4);
    EXPECT_EQ(r.missing, 0);
    EXPECT_EQ(r.extra, 0);
  }
}

TEST(Visibility, RandomViewsOfEveryBundledPlanAgreeWithRayCasting) {
  std::mt19937 rng(2026);
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(AVENUES_SOURCE_DIR) / "plans")) {
    if (entry.path().extension() != ".toml") continue;
    SCOPED_TRACE(entry.path().filename().string());
    CellComplex c = build_cells(read_plan(entry.path().string()));
    for (int v = 0; v < 12; ++v) {
      CellId cell;
      Vec3 eye = random_eye(c, rng, cell);
      std::uniform_real_distribution<double> yaw(0, 360), pitch(-30, 30), fov(40, 110);
      const double y = yaw(rng), p = pitch(rng), f = fov(rng);
      Camera cam = Camera::yaw_pitch(eye, y, p, f, 96, 64);
      SCOPED_TRACE("view " + std::to_string(v) + ": eye " + std::to_string(eye.x) + "," + std::to_string(eye.y) +
                   "," + std::to_string(eye.z) + " yaw " + std::to_string(y) + " pitch " + std::to_string(p) +
                   " fov " + std::to_string(f));
      VisibleSet vs = find_visible(c, cam, cell, Kernel::Double);
      OracleResult r = check_visible_set(c, cam, vs, 1);
      EXPECT_EQ(r.missing, 0) << "view " << v << " eye " << eye.x << "," << eye.y << "," << eye.z;
      EXPECT_EQ(r.extra, 0) << "view " << v;
      // The exact kernel sees the same cells.
      const VisibleSet exact = find_visible(c, cam, cell, Kernel::Exact);
      EXPECT_EQ(exact.cells, vs.cells) << "view " << v;
      EXPECT_EQ(find_visible(c, cam, cell, Kernel::Filtered).cells, exact.cells) << "view " << v;
    }
  }
}

// The search reads each cell's portals from CellComplex::portal_table, laid out by index():
// every face's portals in the face's order, as seen from the cell, with their corners. A
// complex never indexed (a copy with the table cleared) is searched through a table the
// search lays out for itself, and every avenue is the same, bit for bit, in Jones's, the
// merged and the hull search, perspective and parallel.
TEST(Visibility, EachCellsPortalsAreReadFromOneTableAndAComplexNeverIndexedSeesTheSame) {
  const CellComplex c = build_cells(read_plan(plan_path("two-storey-house.toml")));
  const CellComplex::PortalTable& t = c.portal_table;
  ASSERT_TRUE(t.fits(c));
  ASSERT_EQ(t.cell_faces.size(), c.cells.size() + 1);
  for (CellId id = 0; id < CellId(c.cells.size()); ++id) {
    const Cell& cell = c.cells[size_t(id)];
    ASSERT_EQ(size_t(t.cell_faces[size_t(id) + 1] - t.cell_faces[size_t(id)]), cell.faces.size()) << "cell " << id;
    for (size_t k = 0; k < cell.faces.size(); ++k) {
      const int32_t face = t.cell_faces[size_t(id)] + int32_t(k);
      const Face& f = cell.faces[k];
      ASSERT_EQ(size_t(t.face_seen[size_t(face) + 1] - t.face_seen[size_t(face)]), f.portals.size());
      for (size_t i = 0; i < f.portals.size(); ++i) {
        const auto& s = t.seen[size_t(t.face_seen[size_t(face)]) + i];
        const Portal& p = c.portals[size_t(f.portals[i])];
        EXPECT_EQ(s.portal, f.portals[i]);
        EXPECT_EQ(s.other, p.other(id));
        EXPECT_EQ(s.first, p.cell[0] == id);
        ASSERT_EQ(s.corners, p.poly.size());
        EXPECT_GE(s.spread, 1);
        EXPECT_LT(size_t(s.spread) + 1, std::max<size_t>(p.poly.size(), 3));
        for (size_t v = 0; v < p.poly.size(); ++v) {
          EXPECT_EQ(t.corners[size_t(s.corner0) + v].x, p.poly[v].x);
          EXPECT_EQ(t.corners[size_t(s.corner0) + v].y, p.poly[v].y);
          EXPECT_EQ(t.corners[size_t(s.corner0) + v].z, p.poly[v].z);
        }
      }
    }
  }
  CellComplex bare = c;
  bare.portal_table = {};
  ASSERT_FALSE(bare.portal_table.fits(bare));
  auto same = [](const VisibleSet& a, const VisibleSet& b) {
    if (a.avenues.size() != b.avenues.size() || a.cells != b.cells) return false;
    for (size_t i = 0; i < a.avenues.size(); ++i) {
      const Avenue &x = a.avenues[i], &y = b.avenues[i];
      if (x.cell != y.cell || x.parent != y.parent || x.portal != y.portal || x.mask.size() != y.mask.size()) return false;
      for (size_t k = 0; k < x.mask.size(); ++k)
        if (x.mask[k].x != y.mask[k].x || x.mask[k].y != y.mask[k].y) return false;
    }
    return true;
  };
  std::mt19937 rng(614);
  int avenues = 0;
  for (int v = 0; v < 24; ++v) {
    CellId cell;
    const Vec3 eye = random_eye(c, rng, cell);
    std::uniform_real_distribution<double> yaw(0, 360), pitch(-40, 40);
    const Camera cam = Camera::yaw_pitch(eye, yaw(rng), pitch(rng), 90, 96, 64);
    for (int search = 0; search < 3; ++search) {
      TraverseParams params;
      params.merge_pieces = search > 0;
      params.hull_pieces = search == 2;
      const VisibleSet a = find_visible(c, cam, cell, params), b = find_visible(bare, cam, cell, params);
      EXPECT_TRUE(same(a, b)) << "view " << v << ", search " << search;
      avenues += int(a.avenues.size());
    }
    const Camera flat = Camera::parallel(eye, eye + cam.forward, 12, 96, 64);
    EXPECT_TRUE(same(find_visible_from_cut(c, flat, flat.picture_plane(), Kernel::Double),
                     find_visible_from_cut(bare, flat, flat.picture_plane(), Kernel::Double)))
        << "view " << v << ", parallel";
  }
  EXPECT_GT(avenues, 24 * 3 * 2);  // views that see beyond their own cell
}

TEST(Route, JonesHouseFromLivingRoomToKitchenToDiningRoomOnFoot) {
  using avenues::testing::plan_path;
  CellComplex c = build_cells(read_plan(plan_path("jones-house.toml")));
  const std::vector<Vec3> way = route_through(c, {"L", "K", "D"});
  const std::vector<Vec3> path = smooth_path(c, way, 0.2);
  // Every point is in free space at eye height, and the rooms come in order L, K, L, D:
  // the hatch between kitchen and dining room is no door, so the walk goes back through L.
  std::vector<std::string> rooms;
  for (Vec3 p : path) {
    Location at = c.locate(p);
    ASSERT_EQ(at.what, Location::What::Cell) << p.x << "," << p.y << "," << p.z;
    const Cell& cell = c.cells[size_t(at.cell)];
    if (cell.room >= 0 && (rooms.empty() || rooms.back() != c.rooms[size_t(cell.room)].name))
      rooms.push_back(c.rooms[size_t(cell.room)].name);
    EXPECT_NEAR(p.z, 1.6, 1e-9);
  }
  EXPECT_EQ(rooms, (std::vector<std::string>{"L", "K", "L", "D"}));
  EXPECT_THROW(route_through(c, {"L", "Cellar"}), std::runtime_error);
}

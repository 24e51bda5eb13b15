// Tests of cells/: tiny hand-made plans, each named for what it shows, checked
// analytically (volumes, counts, positions) and by the independent validator.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include "cells/build_cells.h"
#include "plans/plan.h"
#include "test_plans.h"

using namespace avenues;
using avenues::testing::wall;

namespace {

Opening opening(const std::string& name, OpeningKind kind, double at, double width, double sill, double head) {
  Opening o;
  o.name = name;
  o.kind = kind;
  o.at = at;
  o.width = width;
  o.sill = sill;
  o.head = head;
  return o;
}

Room room(const std::string& name, Vec2 at, StoreyId s = 0) {
  Room r;
  r.name = name;
  r.label = at;
  r.storey = s;
  return r;
}

/// Two 4 m × 4 m rooms side by side, a front door, a window and an inner door.
Plan two_rooms_one_door(double thickness) {
  Plan p;
  p.name = "two rooms, one door";
  p.far_margin = 5;
  p.storeys.push_back({"ground", 0, 2.5, 0.3, {}});
  Wall outer = wall("outer", {{0, 0}, {8, 0}, {8, 4}, {0, 4}, {0, 0}}, thickness);
  outer.openings.push_back(opening("front", OpeningKind::Door, 2, 0.9, 0, 2.1));
  outer.openings.push_back(opening("east window", OpeningKind::Window, 9, 1.2, 0.9, 2.1));
  p.walls.push_back(outer);
  Wall mid = wall("mid", {{4, 0}, {4, 4}}, thickness);
  mid.openings.push_back(opening("inner", OpeningKind::Door, 1.5, 0.8, 0, 2.0));
  p.walls.push_back(mid);
  p.rooms = {room("west", {2, 2}), room("east", {6, 2})};
  return p;
}

/// One closed 4 m × 3 m room with 0.2 m walls and no openings.
Plan box_room() {
  Plan p;
  p.name = "box room";
  p.far_margin = 2;
  p.storeys.push_back({"ground", 0, 2.5, 0.3, {}});
  p.walls.push_back(wall("box", {{0, 0}, {4, 0}, {4, 3}, {0, 3}, {0, 0}}, 0.2));
  p.rooms = {room("box", {2, 1.5})};
  return p;
}

double box_area(const CellComplex& c) {
  return (c.far_box.hi.x - c.far_box.lo.x) * (c.far_box.hi.y - c.far_box.lo.y);
}

const Cell* only_cell_of_room(const CellComplex& c, RoomId r) {
  const Cell* found = nullptr;
  for (const Cell& cell : c.cells)
    if (cell.kind == CellKind::Room && cell.room == r) {
      if (found) return nullptr;
      found = &cell;
    }
  return found;
}

}  // namespace

TEST(Cells, TwoRoomsOneDoorThickWallsAreValidAndAccountForAllFreeVolume) {
  CellComplex c = build_cells(two_rooms_one_door(0.2));
  EXPECT_EQ(cells_are_valid(c), "");
  ASSERT_EQ(c.rooms.size(), 2u);
  EXPECT_EQ(c.rooms[0].name, "west");
  // Free volume, worked out by hand: the far box minus walls (outer ring 4.8 m², middle
  // wall 0.84 m² less 0.08 m² where it enters the ring), plus the three openings' volumes,
  // the slab band outside the 8.2 × 4.2 footprint, and the sky band.
  const double A = box_area(c);
  const double storey = (A - 5.56) * 2.5 + 0.9 * 0.2 * 2.1 + 1.2 * 0.2 * 1.2 + 0.8 * 0.2 * 2.0;
  const double slab = (A - 8.2 * 4.2) * 0.3;
  const double sky = A * (c.far_box.hi.z - 2.8);
  EXPECT_NEAR(total_volume(c), storey + slab + sky, 1e-6);
  // Each room is one convex cell; three doorway cells stand in the walls.
  EXPECT_NE(only_cell_of_room(c, 0), nullptr);
  EXPECT_NE(only_cell_of_room(c, 1), nullptr);
  int doorways = 0;
  for (const Cell& cell : c.cells) doorways += cell.kind == CellKind::Doorway;
  EXPECT_EQ(doorways, 3);
  // The inner door's portals are 0.8 m wide and 2.0 m high, one on each face of the wall.
  int inner = 0;
  for (const Portal& p : c.portals)
    if (p.kind == PortalKind::Door && std::fabs(p.poly[0].x - 4) < 0.2) {
      double zmax = 0, ymin = 1e9, ymax = -1e9;
      for (Vec3 v : p.poly) zmax = std::max(zmax, v.z), ymin = std::min(ymin, v.y), ymax = std::max(ymax, v.y);
      EXPECT_NEAR(zmax, 2.0, 1e-12);
      EXPECT_NEAR(ymax - ymin, 0.8, 1e-12);
      ++inner;
    }
  EXPECT_EQ(inner, 2);
}

TEST(Cells, WallsOfNoThicknessMakePortalsDirectlyBetweenRooms) {
  CellComplex c = build_cells(two_rooms_one_door(0.0));
  EXPECT_EQ(cells_are_valid(c), "");
  const double A = box_area(c);
  EXPECT_NEAR(total_volume(c), A * 2.5 + (A - 32) * 0.3 + A * (c.far_box.hi.z - 2.8), 1e-6);
  for (const Cell& cell : c.cells) EXPECT_NE(cell.kind, CellKind::Doorway);
  const Cell* west = only_cell_of_room(c, 0);
  const Cell* east = only_cell_of_room(c, 1);
  ASSERT_TRUE(west && east);
  int doors = 0;
  for (const Portal& p : c.portals)
    if (p.kind == PortalKind::Door &&
        ((&c.cells[size_t(p.cell[0])] == west && &c.cells[size_t(p.cell[1])] == east) ||
         (&c.cells[size_t(p.cell[0])] == east && &c.cells[size_t(p.cell[1])] == west)))
      ++doors;
  EXPECT_EQ(doors, 1);
}

TEST(Cells, BoxRoomHasTwelveRealLinesAllCreases) {
  CellComplex c = build_cells(box_room());
  EXPECT_EQ(cells_are_valid(c), "");
  const Cell* box = only_cell_of_room(c, 0);
  ASSERT_NE(box, nullptr);
  // Four floor creases, four ceiling creases, four vertical corners: each a whole line.
  ASSERT_EQ(box->lines.size(), 12u);
  int vertical = 0;
  for (const CellLine& cl : box->lines) {
    const RealLine& l = c.lines[size_t(cl.line)];
    EXPECT_EQ(l.kind, LineKind::Concave);
    EXPECT_DOUBLE_EQ(cl.t0, 0);
    EXPECT_DOUBLE_EQ(cl.t1, 1);
    if (l.a.z != l.b.z) {
      ++vertical;
      EXPECT_NEAR(std::fabs(l.b.z - l.a.z), 2.5, 1e-12);
    } else {
      EXPECT_TRUE(l.a.z == 0 || l.a.z == 2.5);
    }
    // On the inner faces of the walls: x in {0.1, 3.9} or y in {0.1, 2.9}.
    for (Vec3 v : {l.a, l.b})
      EXPECT_TRUE(std::fabs(v.x - 0.1) < 1e-12 || std::fabs(v.x - 3.9) < 1e-12 || std::fabs(v.y - 0.1) < 1e-12 ||
                  std::fabs(v.y - 2.9) < 1e-12);
  }
  EXPECT_EQ(vertical, 4);
}

TEST(Cells, LShapedRoomIsSplitByATransparentPortalThatDrawsNoLine) {
  Plan p;
  p.name = "L-shaped room";
  p.far_margin = 2;
  p.storeys.push_back({"ground", 0, 2.5, 0.3, {}});
  p.walls.push_back(wall("L", {{0, 0}, {6, 0}, {6, 3}, {3, 3}, {3, 6}, {0, 6}, {0, 0}}, 0));
  p.rooms = {room("L", {1, 1})};
  CellComplex c = build_cells(p);
  EXPECT_EQ(cells_are_valid(c), "");
  std::vector<const Cell*> pieces;
  for (const Cell& cell : c.cells)
    if (cell.kind == CellKind::Room) pieces.push_back(&cell);
  ASSERT_EQ(pieces.size(), 2u);
  int transparent = 0;
  for (const Portal& pt : c.portals) transparent += pt.kind == PortalKind::Transparent;
  EXPECT_EQ(transparent, 1);
  // Six walls: six floor creases, six ceiling creases, six corners — and nothing on the cut.
  std::set<LineId> seen;
  for (const Cell* cell : pieces)
    for (const CellLine& cl : cell->lines) seen.insert(cl.line);
  EXPECT_EQ(seen.size(), 18u);
}

TEST(Cells, StairwellJoinsStoreysThroughHorizontalPortals) {
  Plan p;
  p.name = "two storeys, one stairwell";
  p.far_margin = 3;
  p.storeys.push_back({"ground", 0, 2.5, 0.3, {}});
  p.storeys.push_back({"upper", 2.8, 2.5, 0.3, {}});
  for (StoreyId s : {0, 1}) {
    Wall w = wall(s ? "upper box" : "ground box", {{0, 0}, {5, 0}, {5, 4}, {0, 4}, {0, 0}}, 0.2);
    w.storey = s;
    p.walls.push_back(w);
    p.rooms.push_back(room(s ? "landing" : "hall", {2.5, 2}, s));
  }
  FloorOpening hole;
  hole.name = "stairwell";
  hole.storey = 1;
  hole.outline = {{1, 1}, {3, 1}, {3, 2}, {1, 2}};
  p.floor_openings.push_back(hole);
  CellComplex c = build_cells(p);
  EXPECT_EQ(cells_are_valid(c), "");
  int stair_cells = 0, stair_portals = 0;
  for (const Cell& cell : c.cells) stair_cells += cell.kind == CellKind::Stairwell;
  for (const Portal& pt : c.portals) stair_portals += pt.kind == PortalKind::Stairwell;
  EXPECT_EQ(stair_cells, 1);
  EXPECT_GE(stair_portals, 2);
  // From the hall one can reach the landing through portals.
  Location hall = c.locate({2.5, 2, 1.5});
  Location landing = c.locate({2.5, 2, 4.0});
  ASSERT_EQ(hall.what, Location::What::Cell);
  ASSERT_EQ(landing.what, Location::What::Cell);
  std::set<CellId> reached{hall.cell};
  std::vector<CellId> todo{hall.cell};
  while (!todo.empty()) {
    CellId x = todo.back();
    todo.pop_back();
    for (PortalId pi : c.cells[size_t(x)].portals) {
      CellId y = c.portals[size_t(pi)].other(x);
      if (c.cells[size_t(y)].kind != CellKind::Outside && c.cells[size_t(y)].kind != CellKind::Sky &&
          reached.insert(y).second)
        todo.push_back(y);
    }
  }
  EXPECT_TRUE(reached.count(landing.cell));
}

TEST(Cells, LowWallLeavesTheSpaceAboveItOpen) {
  Plan p = two_rooms_one_door(0.2);
  p.walls[1].height = 1.0;  // the middle wall becomes a parapet
  p.walls[1].openings.clear();
  // Now west and east are one space: one room label must go.
  p.rooms.pop_back();
  CellComplex c = build_cells(p);
  EXPECT_EQ(cells_are_valid(c), "");
  int gaps = 0;
  for (const Portal& pt : c.portals) gaps += pt.kind == PortalKind::Gap;
  EXPECT_EQ(gaps, 2);  // one on each face of the wall, from 1.0 m to the ceiling
}

namespace {

/// A doorway cell's stretch along x and its floor.
struct DoorwaySpan {
  double x0, x1, z0;
};
/// The complex's doorway cells, after checking the complex.
std::vector<DoorwaySpan> doorways_of(const CellComplex& c) {
  EXPECT_EQ(cells_are_valid(c), "");
  std::vector<DoorwaySpan> out;
  for (const Cell& cell : c.cells) {
    if (cell.kind != CellKind::Doorway) continue;
    DoorwaySpan d{HUGE_VAL, -HUGE_VAL, cell.z0};
    for (Vec2 v : cell.footprint) d.x0 = std::min(d.x0, v.x), d.x1 = std::max(d.x1, v.x);
    out.push_back(d);
  }
  return out;
}

}  // namespace

TEST(Cells, LowWallsCarryingOnInOneLineMeetFlushEachAtItsOwnHeight) {
  // A sloped wall read as steps (a Sweet Home gable) is low walls end to end. An end that
  // touches another wall is capped by half the thickness so that L and T junctions close;
  // capped here, each step would lay its height over its neighbour's for 10 cm.
  Plan p = box_room();
  Wall low = wall("low", {{1, 0.8}, {2, 0.8}}, 0.2), higher = wall("higher", {{2, 0.8}, {3, 0.8}}, 0.2);
  low.height = 0.5;
  higher.height = 1.0;
  p.walls.push_back(low);
  p.walls.push_back(higher);
  const std::vector<DoorwaySpan> doorways = doorways_of(build_cells(p));
  for (const DoorwaySpan& d : doorways) {
    const bool over_low = std::fabs(d.z0 - 0.5) < 1e-9;
    EXPECT_TRUE(over_low || std::fabs(d.z0 - 1.0) < 1e-9) << d.z0;
    EXPECT_NEAR(d.x0, over_low ? 1.0 : 2.0, 1e-9) << "z0 " << d.z0;
    EXPECT_NEAR(d.x1, over_low ? 2.0 : 3.0, 1e-9) << "z0 " << d.z0;
  }
  EXPECT_EQ(doorways.size(), 2u) << "one over each wall";
}

TEST(Cells, OverlappingLowWallsOfOneHeightLeaveOneDoorwayOverThem) {
  // Two low walls of one height lying on one line and overlapping (a sloped wall's steps
  // read from two walls, a wall drawn twice): the space over them is one doorway, not one
  // per wall or per stretch of overlap.
  Plan p = box_room();
  Wall a = wall("a", {{1, 0.8}, {2.5, 0.8}}, 0.2), b = wall("b", {{1.5, 0.8}, {3, 0.8}}, 0.2);
  a.height = b.height = 0.5;
  p.walls.push_back(a);
  p.walls.push_back(b);
  const std::vector<DoorwaySpan> doorways = doorways_of(build_cells(p));
  ASSERT_EQ(doorways.size(), 1u);
  EXPECT_NEAR(doorways[0].z0, 0.5, 1e-9);
  EXPECT_NEAR(doorways[0].x0, 1.0, 1e-9);
  EXPECT_NEAR(doorways[0].x1, 3.0, 1e-9);
}

TEST(Cells, PointLocationAgreesWithBruteForce) {
  for (double thickness : {0.2, 0.0}) {
    CellComplex c = build_cells(two_rooms_one_door(thickness));
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> x(c.far_box.lo.x, c.far_box.hi.x), y(c.far_box.lo.y, c.far_box.hi.y),
        z(c.far_box.lo.z, c.far_box.hi.z);
    CellId hint = kNoCell;
    for (int i = 0; i < 2000; ++i) {
      Vec3 q{x(rng), y(rng), z(rng)};
      CellId brute = kNoCell;
      for (CellId k = 0; k < CellId(c.cells.size()); ++k)
        if (c.cells[size_t(k)].contains(q)) brute = k;
      Location loc = c.locate(q, hint);
      if (brute == kNoCell) {
        EXPECT_EQ(loc.what, Location::What::Solid) << q.x << "," << q.y << "," << q.z;
      } else {
        ASSERT_EQ(loc.what, Location::What::Cell);
        EXPECT_TRUE(c.cells[size_t(loc.cell)].contains(q));
        hint = loc.cell;
      }
    }
  }
}

TEST(Cells, APointInsideAWallIsReportedAsThatWall) {
  CellComplex c = build_cells(two_rooms_one_door(0.2));
  Location loc = c.locate({4.0, 3.5, 1.0});
  EXPECT_EQ(loc.what, Location::What::Solid);
  EXPECT_NE(loc.solid.find("wall 'mid'"), std::string::npos) << loc.solid;
  EXPECT_EQ(c.locate({4.0, 2.0, 2.3}).what, Location::What::Solid);  // above the inner door: lintel
  EXPECT_EQ(c.locate({4.0, 2.0, 1.0}).what, Location::What::Cell);   // in the doorway
}

TEST(Cells, RoomMistakesNameTheRoom) {
  Plan in_wall = two_rooms_one_door(0.2);
  in_wall.rooms[1].label = {8.05, 2};
  try {
    build_cells(in_wall);
    FAIL() << "a label inside a wall was accepted";
  } catch (const PlanError& e) {
    EXPECT_NE(std::string(e.what()).find("'east'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("inside a wall"), std::string::npos) << e.what();
  }
  Plan open = two_rooms_one_door(0.2);
  open.walls[0].centre = {{0, 0}, {8, 0}, {8, 4}, {0, 4}};  // the west wall is missing
  open.walls[0].from_arc.assign(3, false);
  open.walls[0].openings.clear();
  try {
    build_cells(open);
    FAIL() << "a room open to the outside was accepted";
  } catch (const PlanError& e) {
    EXPECT_NE(std::string(e.what()).find("'west'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("not enclosed"), std::string::npos) << e.what();
  }
  Plan twice = two_rooms_one_door(0.2);
  twice.rooms[1].label = {1, 1};
  EXPECT_THROW(build_cells(twice), PlanError);
}

TEST(Cells, ASheetMeetingAFlatWallDrawsTheCornerOnItsOwnSideOnly) {
  // Jones's house: the kitchen–dining wall meets the living room's east wall at (5, 3).
  // Kitchen and dining room see that corner; the living room sees a flat wall there.
  Plan p = two_rooms_one_door(0.0);
  p.walls.push_back(wall("shelf", {{4, 3}, {8, 3}}, 0.0));  // splits the east room, away from the door
  p.rooms.push_back(room("east north", {6, 3.5}));
  p.rooms[1].label = {6, 1};
  CellComplex c = build_cells(p);
  EXPECT_EQ(cells_are_valid(c), "");
  std::set<RoomId> seen_from;
  for (const Cell& cell : c.cells)
    for (const CellLine& cl : cell.lines) {
      const RealLine& l = c.lines[size_t(cl.line)];
      if (l.a.x == 4 && l.b.x == 4 && l.a.y == 3 && l.b.y == 3 && cell.kind == CellKind::Room) seen_from.insert(cell.room);
    }
  EXPECT_EQ(seen_from, (std::set<RoomId>{1, 2})) << "the west room's wall is flat at (4, 3)";
}

// --- Rooms with their own floor and ceiling, named by wall sides, a solid outside:
// what an imported Doom map needs (plans/formats/doom_map.h builds such plans from sectors).
namespace {

/// Two 4 m × 4 m "sectors" sharing the line x = 4, walls of no thickness, no labels:
/// the west one's floor at 0.5 m and ceiling at 2.0 m, the east one's 0 to 2.5 m (sky).
Plan two_sectors(bool east_sky) {
  Plan p;
  p.name = "two sectors";
  p.far_margin = 1;
  p.outside_solid = true;
  p.storeys.push_back({"map", 0, 3.0, 0, {}});
  Room west, east;
  west.name = "west";
  west.floor_at = 0.5;
  west.ceiling_at = 2.0;
  east.name = "east";
  east.ceiling_at = 2.5;
  east.sky = east_sky;
  p.rooms = {west, east};
  // Outer boundary counter-clockwise: the inside is on each line's left.
  auto line = [&](Vec2 a, Vec2 b, int left, int right) {
    Wall w = wall("line " + std::to_string(p.walls.size()), {a, b}, 0);
    w.left_room = left;
    w.right_room = right;
    return w;
  };
  p.walls = {line({0, 0}, {4, 0}, 0, -1), line({4, 0}, {8, 0}, 1, -1), line({8, 0}, {8, 4}, 1, -1),
             line({8, 4}, {4, 4}, 1, -1), line({4, 4}, {0, 4}, 0, -1), line({0, 4}, {0, 0}, 0, -1)};
  Wall shared = line({4, 0}, {4, 4}, 0, 1);  // west on its left walking north
  shared.openings.push_back(opening("step", OpeningKind::Gap, 0, 4, 0, 3.0));
  p.walls.push_back(shared);
  return p;
}

}  // namespace

TEST(Cells, SectorRoomsSpanTheirOwnHeightsAndMeetOverTheOverlap) {
  Plan p = two_sectors(false);
  CellComplex c = build_cells(p);
  ASSERT_EQ(cells_are_valid(c), "");
  EXPECT_TRUE(c.warnings.empty()) << c.warnings.front();
  double west_lo = 1e9, west_hi = -1e9;
  int outside = 0;
  for (const Cell& cell : c.cells) {
    outside += cell.kind == CellKind::Outside || cell.kind == CellKind::Sky;
    if (cell.kind == CellKind::Room && cell.room == 0) {
      west_lo = std::min(west_lo, cell.z0);
      west_hi = std::max(west_hi, cell.z1);
    }
  }
  EXPECT_EQ(outside, 0) << "the void around a map is solid";
  EXPECT_DOUBLE_EQ(west_lo, 0.5);
  EXPECT_DOUBLE_EQ(west_hi, 2.0);
  EXPECT_NEAR(c.rooms[0].area, 16, 1e-9);
  EXPECT_NEAR(c.rooms[1].area, 16, 1e-9);
  // The portal between them spans the overlap of 0.5..2.0 and 0..2.5.
  int between = 0;
  for (const Portal& po : c.portals) {
    const Cell &a = c.cells[size_t(po.cell[0])], &b = c.cells[size_t(po.cell[1])];
    if (a.room == b.room) continue;
    ++between;
    double lo = 1e9, hi = -1e9;
    for (Vec3 v : po.poly) lo = std::min(lo, v.z), hi = std::max(hi, v.z);
    EXPECT_DOUBLE_EQ(lo, 0.5);
    EXPECT_DOUBLE_EQ(hi, 2.0);
  }
  EXPECT_GE(between, 1);
  // Inside the raised floor is solid; above the west ceiling is solid.
  EXPECT_EQ(c.locate({2, 2, 0.25}).what, Location::What::Solid);
  EXPECT_EQ(c.locate({2, 2, 2.5}).what, Location::What::Solid);
  EXPECT_EQ(c.locate({2, 2, 1.0}).what, Location::What::Cell);
  EXPECT_EQ(c.locate({-0.5, 2, 1.0}).what, Location::What::Solid) << "outside the map";
}

TEST(Cells, ASkyRoomOpensToTheSkyAboveItOnly) {
  CellComplex c = build_cells(two_sectors(true));
  ASSERT_EQ(cells_are_valid(c), "");
  const Location above_east = c.locate({6, 2, 3.5}), above_west = c.locate({2, 2, 3.5});
  ASSERT_EQ(above_east.what, Location::What::Cell);
  EXPECT_EQ(c.cells[size_t(above_east.cell)].kind, CellKind::Sky);
  EXPECT_EQ(above_west.what, Location::What::Solid);
  // The east room reaches its storey's top (3 m) to meet the sky through a portal.
  const Location in_east = c.locate({6, 2, 2.8});
  ASSERT_EQ(in_east.what, Location::What::Cell);
  EXPECT_EQ(c.cells[size_t(in_east.cell)].room, 1);
}

TEST(Cells, UnclosedSectorsAndSpacesClaimedTwiceAreWarnedAbout) {
  Plan p = two_sectors(false);
  p.walls.back().right_room = 1;  // the shared line now says east on both sides
  p.walls.back().openings.clear();
  p.walls.back().left_room = 1;
  p.walls[0].left_room = 1;       // the west space: claimed by west (2 lines) and east (2 lines)
  p.walls[4].left_room = 1;
  CellComplex c = build_cells(p);
  ASSERT_EQ(cells_are_valid(c), "");
  bool claimed = false;
  for (const std::string& w : c.warnings) claimed |= w.find("claimed by room") != std::string::npos;
  EXPECT_TRUE(claimed);

  Plan leaky = two_sectors(false);
  leaky.walls.erase(leaky.walls.begin() + 5);  // the west side of the west sector is missing
  CellComplex d = build_cells(leaky);
  ASSERT_EQ(cells_are_valid(d), "");
  bool dropped = false;
  for (const std::string& w : d.warnings) dropped |= w.find("m² of unclosed rooms dropped") != std::string::npos;
  EXPECT_TRUE(dropped);
  EXPECT_EQ(d.locate({2, 2, 1.0}).what, Location::What::Solid) << "the leaking sector is dropped";
  EXPECT_EQ(d.locate({6, 2, 1.0}).what, Location::What::Cell);
}

TEST(Cells, ARoomWhoseFloorMeetsItsCeilingIsSolid) {
  Plan p = two_sectors(false);
  p.rooms[0].ceiling_at = 0.5;  // a closed door: floor and ceiling at 0.5 m
  CellComplex c = build_cells(p);
  ASSERT_EQ(cells_are_valid(c), "");
  for (const Cell& cell : c.cells) EXPECT_NE(cell.room, 0);
  EXPECT_EQ(c.locate({2, 2, 0.5}).what, Location::What::Solid);
}

TEST(Cells, LenientPlansTurnRoomLabelMistakesIntoWarnings) {
  Plan p = two_rooms_one_door(0.2);
  p.rooms.push_back(room("terrace", {10, 2}));   // outside the walls
  p.rooms.push_back(room("nook", {2.5, 2.5}));   // in the same space as 'west'
  EXPECT_THROW(build_cells(p), PlanError);
  p.lenient = true;
  CellComplex c = build_cells(p);
  ASSERT_EQ(cells_are_valid(c), "");
  ASSERT_EQ(c.warnings.size(), 2u);
  EXPECT_NE(c.warnings[0].find("terrace"), std::string::npos);
  EXPECT_NE(c.warnings[1].find("nook"), std::string::npos);
  EXPECT_EQ(c.rooms[0].name, "west + nook");
}

TEST(Cells, RaisedFloorsAndLoweredCeilingsInATomlPlan) {
  const std::string text = R"(
name = "platform"
[[storey]]
name = "ground"
height = 3.0
[[wall]]
name = "box"
thickness = 0.2
path = [[0, 0], [4, 0], [4, 4], [0, 4], [0, 0]]
[[room]]
name = "stage"
at = [2, 2]
floor_at = 0.4
ceiling_at = 2.6
)";
  CellComplex c = build_cells(parse_plan(text, "platform.toml"));
  ASSERT_EQ(cells_are_valid(c), "");
  for (const Cell& cell : c.cells)
    if (cell.kind == CellKind::Room) {
      EXPECT_DOUBLE_EQ(cell.z0, 0.4);
      EXPECT_DOUBLE_EQ(cell.z1, 2.6);
    }
  EXPECT_THROW(parse_plan(std::string(text).replace(text.find("0.4"), 3, "3.5"), "platform.toml"), PlanError);
}

// Pass 3b (cells/band_cuts.cpp): a storey's free space is cut as its own outline needs,
// whatever the storeys above and below it hold. An L-shaped upper floor over four rooms
// was cut along the walls of the rooms below it and at their corners (their points lie
// inside it in the one triangulation of every storey; merging takes a region whole only
// where its outline is convex): 6 cells. Its L needs 2, one diagonal from its reflex
// corner (Hertel–Mehlhorn merging of its own triangulation alone kept two there: 3). The
// same 5,400 km from the origin, where the cuts cross the walls below at points whose
// rounding is far larger.
TEST(Cells, AnLShapedUpperFloorOverRoomsIsCutAsItsOwnOutlineNeeds) {
  for (const Vec2 origin : {Vec2{0, 0}, Vec2{5.4e6, -3.1e6}}) {
    SCOPED_TRACE("origin " + std::to_string(origin.x) + ", " + std::to_string(origin.y));
    auto at = [&](std::vector<Vec2> pts) {
      for (Vec2& v : pts) v = v + origin;
      return pts;
    };
    Plan p;
    p.name = "L-shaped upper floor";
    p.far_margin = 4;
    p.storeys.push_back({"ground", 0, 2.5, 0.3, {}});
    p.storeys.push_back({"upper", 2.8, 2.4, 0.3, {}});
    p.walls.push_back(wall("ground box", at({{0, 0}, {8, 0}, {8, 6}, {0, 6}, {0, 0}}), 0.3));
    // Inner walls meeting off the middle, and one cranked: corners everywhere below.
    p.walls.push_back(wall("north-south", at({{3.1, 0}, {3.1, 2.7}, {3.6, 3.2}, {3.6, 6}}), 0.12));
    p.walls.push_back(wall("west", at({{0, 2.45}, {3.1, 2.45}}), 0.12));
    p.walls.push_back(wall("east", at({{3.6, 3.9}, {8, 3.9}}), 0.12));
    Wall upper = wall("upper L", at({{0, 0}, {8, 0}, {8, 6}, {5, 6}, {5, 3}, {0, 3}, {0, 0}}), 0.3);
    upper.storey = 1;
    p.walls.push_back(upper);
    p.rooms = {room("south-west", origin + Vec2{1.5, 1}), room("north-west", origin + Vec2{1.5, 4.5}),
               room("south-east", origin + Vec2{6, 1.5}), room("north-east", origin + Vec2{6, 5}),
               room("upper", origin + Vec2{2, 1.5}, 1)};
    const CellComplex c = build_cells(p);
    ASSERT_EQ(cells_are_valid(c), "");
    int upper_cells = 0;
    double upper_area = 0;
    for (const Cell& cell : c.cells) {
      if (cell.kind != CellKind::Room || cell.room != 4) continue;
      ++upper_cells;
      std::vector<Vec2> local = cell.footprint;
      for (Vec2& v : local) v = v - origin;
      upper_area += signed_area(local);
    }
    EXPECT_EQ(upper_cells, 2);
    EXPECT_NEAR(upper_area, 7.7 * 2.7 + 2.7 * 3.0, 1e-6);
    // Below, each room keeps its own few pieces: the north-south wall's crank makes two
    // of them notched, but none is cut by the floor above.
    int ground_room_cells = 0;
    for (const Cell& cell : c.cells) ground_room_cells += cell.kind == CellKind::Room && cell.room < 4;
    EXPECT_LE(ground_room_cells, 8);
  }
}

// A room's side may run along several walls in one line; each opaque piece of it takes the
// material of the wall behind it. (It took the side's commonest: once a band's free space
// was cut as its own outline needs, cells grew along whole rows of walls, and a bathroom's
// tiles ran on into the hall's plaster.)
TEST(Cells, ASideAlongTwoWallsInLineTakesEachWallsMaterial) {
  Plan p;
  p.name = "two walls in line";
  p.far_margin = 2;
  p.storeys.push_back({"ground", 0, 2.5, 0.3, {}});
  p.materials = {Material{"tiles", 0.6, {0.2, 0.6, 0.7}, {}}, Material{"plaster", 0.8, {0.9, 0.9, 0.85}, {}}};
  Wall tiles = wall("tiled", {{0, 0}, {3, 0}}, 0.2), plaster = wall("plastered", {{3, 0}, {8, 0}, {8, 4}, {0, 4}, {0, 0}}, 0.2);
  tiles.material = 0, plaster.material = 1;
  p.walls = {tiles, plaster};
  p.rooms = {room("room", {4, 2})};
  const CellComplex c = build_cells(p);
  ASSERT_EQ(cells_are_valid(c), "");
  double tiled = 0, plastered = 0;
  for (const Cell& cell : c.cells) {
    if (cell.kind != CellKind::Room) continue;
    for (const Face& f : cell.faces)
      for (const OpaquePoly& o : f.opaque) {
        if (!(std::fabs(f.plane.n.y + 1) < 1e-9)) continue;  // the south side: its normal points south, out of the room
        double x0 = HUGE_VAL, x1 = -HUGE_VAL;
        for (Vec3 v : o.poly) x0 = std::min(x0, v.x), x1 = std::max(x1, v.x);
        (o.material == 0 ? tiled : plastered) += x1 - x0;
        if (o.material == 0) {
          EXPECT_LE(x1, 3 + 1e-9) << "tiles beyond the tiled wall";
        } else {
          EXPECT_GE(x0, 3 - 1e-9) << "plaster on the tiled wall";
        }
      }
  }
  EXPECT_NEAR(tiled, 3 - 0.1, 1e-9);
  EXPECT_NEAR(plastered, 5 - 0.1, 1e-9);
}

// Tests of the Sweet Home 3D importer (plans/formats/sweet_home.cpp).
//
//   * the nine example homes Debian's sweethome3d ships (bare Home.xml) read and build
//     valid cells; every room they name owns cells or is accounted for by a warning;
//     every door gives a Door portal; the views the homes store (the observer camera and
//     the stored cameras, read here straight from the XML) agree with ray casting;
//   * a .sh3d zip made here reads as its bare Home.xml does;
//   * small hand-made homes: an arc wall, a sloped wall, a door and a window, levels;
//   * malformed files give a PlanError naming the file, the element and its line.
#include <gtest/gtest.h>
#include <pugixml.hpp>
#include <unistd.h>
#include <zip.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "cells/build_cells.h"
#include "plans/formats/sweet_home.h"
#include "plans/formats/svg_path.h"
#include "plans/java3d_materials.h"
#include "tests/test_files.h"
#include "plans/mesh.h"
#include "render/scene_objects.h"
#include "render/view_lines.h"
#include "ray_oracle.h"
#include "visibility/visible_set.h"

namespace avenues {
namespace {

namespace fs = std::filesystem;

const fs::path kExamples = AVENUES_SH3D_EXAMPLES;
const char* const kHomes[] = {"1BedroomApartmentWithRoundWall", "2BedroomApartment", "2BedroomApartmentWithBowWindow",
                              "2BedroomHouseWithBasement",      "3BedroomApartment", "3BedroomHouseWithAttic",
                              "3BedroomHouseWithMezzanine",     "4BedroomHouse",     "Studio"};

/// A scratch directory per test, removed afterwards.
class TempDir : public avenues::testing::TempDir {
 public:
  TempDir() : avenues::testing::TempDir("avenues-sh3d") {}
  /// A zip holding the given entries (name → bytes), written with libzip.
  std::string zip(const std::string& name, const std::map<std::string, std::string>& entries) const {
    const std::string path = (dir_ / name).string();
    int err = 0;
    zip_t* za = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &err);
    EXPECT_NE(za, nullptr) << "libzip error " << err;
    if (!za) return path;
    for (const auto& [entry, bytes] : entries) {
      zip_source_t* src = zip_source_buffer(za, bytes.data(), bytes.size(), 0);
      EXPECT_GE(zip_file_add(za, entry.c_str(), src, ZIP_FL_OVERWRITE), 0) << zip_strerror(za);
    }
    EXPECT_EQ(zip_close(za), 0);  // writes the entries (their buffers are still alive here)
    return path;
  }

};

/// A Sweet Home camera from its XML element: walks along (−sin yaw, cos yaw) on the
/// y-down screen, pitch > 0 looks down; (x, y, z) cm → (x, −y, z)/100 m.
Camera sweet_home_camera(pugi::xml_node n, int width, int height) {
  const double x = n.attribute("x").as_double(), y = n.attribute("y").as_double(), z = n.attribute("z").as_double();
  const double yaw = n.attribute("yaw").as_double(), pitch = n.attribute("pitch").as_double();
  const double fov = n.attribute("fieldOfView").as_double() * 180 / std::numbers::pi;
  const Vec3 eye{x / 100, -y / 100, z / 100};
  const Vec3 dir{-std::sin(yaw) * std::cos(pitch), -std::cos(yaw) * std::cos(pitch), -std::sin(pitch)};
  return Camera::look_at(eye, eye + dir, fov, width, height);
}

/// Plan-wide index of a wall opening, as cells/ numbers them (Portal::opening).
int opening_index(const Plan& p, size_t wall, size_t opening) {
  int id = 0;
  for (size_t w = 0; w < wall; ++w) id += int(p.walls[w].openings.size());
  return id + int(opening);
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

/// Does a complex room's name ("Hall + Bedroom + Kitchen", "Bathroom (2)") include `name`?
bool names(const std::string& joined, const std::string& name) {
  size_t from = 0;
  for (;;) {
    const size_t to = joined.find(" + ", from);
    std::string part = joined.substr(from, to == std::string::npos ? std::string::npos : to - from);
    if (part == name || (part.rfind(name + " (", 0) == 0 && part.back() == ')')) return true;
    if (to == std::string::npos) return false;
    from = to + 3;
  }
}

// A small home: a 6 m × 4 m box (walls joined end to end), a partition with a door, a
// window in the south wall, two named rooms. `extra` goes inside <home>.
std::string small_home(const std::string& extra = "", const std::string& partition_extra = "") {
  return R"(<?xml version='1.0'?>
<home version='5500' name='Small.sh3d' wallHeight='250.0'>
  <wall id='s' wallAtStart='w' wallAtEnd='e' xStart='0' yStart='400' xEnd='600' yEnd='400' height='250' thickness='20'/>
  <wall id='e' wallAtStart='s' wallAtEnd='n' xStart='600' yStart='400' xEnd='600' yEnd='0' height='250' thickness='20'/>
  <wall id='n' wallAtStart='e' wallAtEnd='w' xStart='600' yStart='0' xEnd='0' yEnd='0' height='250' thickness='20'/>
  <wall id='w' wallAtStart='n' wallAtEnd='s' xStart='0' yStart='0' xEnd='0' yEnd='400' height='250' thickness='20'/>
  <wall id='p' xStart='400' yStart='0' xEnd='400' yEnd='400' height='250' thickness='10' )" +
         partition_extra + R"(/>
  <doorOrWindow name='Door' x='400' y='250' angle='1.5707964' width='90' depth='10' height='210'/>
  <doorOrWindow name='Window' x='150' y='400' elevation='90' width='120' depth='20' height='120'/>
  <room name='Living'><point x='10' y='10'/><point x='395' y='10'/><point x='395' y='390'/><point x='10' y='390'/></room>
  <room name='Kitchen'><point x='405' y='10'/><point x='590' y='10'/><point x='590' y='390'/><point x='405' y='390'/></room>
  <observerCamera attribute='observerCamera' x='100' y='200' z='160' yaw='4.712389' pitch='0.0' fieldOfView='1.0995574'/>
)" + extra + "</home>\n";
}

const Wall* wall_named(const Plan& p, const std::string& name) {
  for (const Wall& w : p.walls)
    if (w.name == name) return &w;
  return nullptr;
}

}  // namespace

// ---------------------------------------------------------------------------------
// The example homes.

TEST(SweetHome, ExampleHomesBuildValidCellsWithTheirRoomsAndDoors) {
  if (!fs::exists(kExamples / "Studio.xml"))
    GTEST_SKIP() << "the Sweet Home 3D example homes are not in " << kExamples << " (run .ci/install-deps)";
  for (const char* home : kHomes) {
    SCOPED_TRACE(home);
    const std::string path = (kExamples / (std::string(home) + ".xml")).string();
    const Plan plan = read_sweet_home(path);
    const auto t0 = std::chrono::steady_clock::now();
    const CellComplex c = build_cells(plan);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_EQ(cells_are_valid(c), "");
    ASSERT_TRUE(plan.view.has_value());
    EXPECT_EQ(c.locate(plan.view->eye).what, Location::What::Cell) << "the observer stands in free space";

    // Every room the home names owns cells (under its name, or joined with the names of
    // rooms sharing its space), or a warning says why not (open to the outside, in a wall).
    std::vector<int> cells_of(c.rooms.size(), 0);
    for (const Cell& cell : c.cells)
      if (cell.room >= 0) ++cells_of[size_t(cell.room)];
    pugi::xml_document doc;
    ASSERT_TRUE(doc.load_file(path.c_str()));
    int named = 0, found = 0;
    std::string missing;
    for (pugi::xml_node r : doc.child("home").children("room")) {
      const std::string name = r.attribute("name").as_string();
      if (name.empty()) continue;
      ++named;
      bool owns = false;
      for (size_t k = 0; k < c.rooms.size(); ++k) owns |= cells_of[k] > 0 && names(c.rooms[k].name, name);
      if (owns) {
        ++found;
        continue;
      }
      bool explained = false;
      for (const std::string& w : c.warnings) explained |= contains(w, "'" + name + "'");
      EXPECT_TRUE(explained) << "room '" << name << "' owns no cells and no warning says why";
      missing += " '" + name + "'";
    }
    EXPECT_GE(2 * found, named) << "most named rooms own cells; missing:" << missing;

    // Every door of a full-height wall opens into a Door portal.
    std::set<int> door_portals;
    for (const Portal& p : c.portals)
      if (p.kind == PortalKind::Door) door_portals.insert(p.opening);
    int doors = 0;
    for (size_t w = 0; w < plan.walls.size(); ++w)
      for (size_t o = 0; o < plan.walls[w].openings.size(); ++o) {
        if (plan.walls[w].openings[o].kind != OpeningKind::Door || plan.walls[w].height >= 0) continue;
        ++doors;
        EXPECT_TRUE(door_portals.count(opening_index(plan, w, o)))
            << "door '" << plan.walls[w].openings[o].name << "' in wall '" << plan.walls[w].name << "' has no Door portal";
      }
    EXPECT_GT(doors, 0);
    std::printf("[ sh3d     ] %-32s %2zu storeys %3zu walls %4zu cells %4zu portals %2d/%2d named rooms own cells "
                "(missing:%s) %2zu warnings %.2f s\n",
                home, plan.storeys.size(), plan.walls.size(), c.cells.size(), c.portals.size(), found, named,
                missing.empty() ? " none" : missing.c_str(), c.warnings.size(), seconds);
  }
}

TEST(SweetHome, StoredViewsOfTheExampleHomesAgreeWithRayCasting) {
  if (!fs::exists(kExamples / "Studio.xml"))
    GTEST_SKIP() << "the Sweet Home 3D example homes are not in " << kExamples << " (run .ci/install-deps)";
  for (const char* home : kHomes) {
    SCOPED_TRACE(home);
    const std::string path = (kExamples / (std::string(home) + ".xml")).string();
    const CellComplex c = build_cells(read_sweet_home(path));
    pugi::xml_document doc;
    ASSERT_TRUE(doc.load_file(path.c_str()));
    int views = 0, in_walls = 0, seeing_beyond = 0;
    for (pugi::xml_node n : doc.child("home").children("observerCamera")) {
      const std::string name = n.attribute("name").as_string("observer");
      SCOPED_TRACE("camera '" + name + "'");
      const Camera cam = sweet_home_camera(n, 96, 64);
      const Location at = c.locate(cam.eye);
      if (at.what != Location::What::Cell) {
        // Sweet Home lets a stored camera stand inside a wall's thickness (its near plane
        // clips the wall away): 3BedroomHouseWithAttic's 'Living room', 5 cm into wall55.
        ++in_walls;
        continue;
      }
      const VisibleSet vs = find_visible(c, cam, at.cell, Kernel::Double);
      const avenues::testing::OracleResult r = avenues::testing::check_visible_set(c, cam, vs, 2);
      EXPECT_EQ(r.missing, 0);
      EXPECT_EQ(r.extra, 0);
      EXPECT_EQ(find_visible(c, cam, at.cell, Kernel::Exact).cells, vs.cells);
      seeing_beyond += vs.cells.size() > 1;
      ++views;
    }
    EXPECT_GE(views, 2);
    EXPECT_LE(in_walls, 1) << "cameras standing in walls";
    EXPECT_GT(seeing_beyond, 0) << "some stored view sees past the eye's own cell";
  }
}

// ---------------------------------------------------------------------------------
// The .sh3d zip.

TEST(SweetHome, Sh3dZipReadsAsItsBareHomeXml) {
  TempDir dir;
  const std::string xml = small_home();
  const Plan bare = read_sweet_home(dir.write("Home.xml", xml));
  const std::string sh3d = dir.zip("small.sh3d", {{"Home.xml", xml}, {"Home", "serialized Java, not read"}});
  const Plan zipped = read_sweet_home(sh3d);
  ASSERT_EQ(zipped.walls.size(), bare.walls.size());
  for (size_t w = 0; w < bare.walls.size(); ++w) {
    EXPECT_EQ(zipped.walls[w].name, bare.walls[w].name);
    ASSERT_EQ(zipped.walls[w].centre.size(), bare.walls[w].centre.size());
    for (size_t k = 0; k < bare.walls[w].centre.size(); ++k) EXPECT_EQ(zipped.walls[w].centre[k], bare.walls[w].centre[k]);
    ASSERT_EQ(zipped.walls[w].openings.size(), bare.walls[w].openings.size());
    for (size_t o = 0; o < bare.walls[w].openings.size(); ++o) {
      EXPECT_EQ(zipped.walls[w].openings[o].at, bare.walls[w].openings[o].at);
      EXPECT_EQ(zipped.walls[w].openings[o].where.line, bare.walls[w].openings[o].where.line);
    }
  }
  ASSERT_EQ(zipped.rooms.size(), bare.rooms.size());
  for (size_t r = 0; r < bare.rooms.size(); ++r) {
    EXPECT_EQ(zipped.rooms[r].name, bare.rooms[r].name);
    EXPECT_EQ(*zipped.rooms[r].label, *bare.rooms[r].label);
  }
  EXPECT_EQ(zipped.name, "Small");
  EXPECT_EQ(zipped.source, sh3d);
  // Both build the same cells.
  EXPECT_EQ(build_cells(zipped).cells.size(), build_cells(bare).cells.size());
}

// ---------------------------------------------------------------------------------
// Small hand-made homes.

TEST(SweetHome, SmallHomeJoinsItsWallsAndCutsTheDoorAndWindowWhereTheyStand) {
  TempDir dir;
  const Plan p = read_sweet_home(dir.write("Home.xml", small_home()));
  ASSERT_EQ(p.storeys.size(), 1u);
  EXPECT_NEAR(p.storeys[0].height, 2.5, 1e-12);
  EXPECT_TRUE(p.lenient);
  // The four outer walls name each other at their ends: one closed, mitred ring.
  ASSERT_EQ(p.walls.size(), 2u);
  const Wall* ring = wall_named(p, "s+e+n+1 more");
  const Wall* part = wall_named(p, "p");
  ASSERT_NE(ring, nullptr);
  ASSERT_NE(part, nullptr);
  EXPECT_EQ(ring->centre.front(), ring->centre.back());
  // y is flipped: the south wall (y = 400 cm on screen) runs along y = −4 m, east.
  EXPECT_EQ(ring->centre.front(), (Vec2{0, -4}));
  EXPECT_EQ(ring->height, -1);  // as tall as the storey: up to the ceiling
  EXPECT_NEAR(ring->thickness, 0.2, 1e-12);
  // The window (centre x = 1.5 m, 1.2 m wide) in the south wall, 0.9 m above the floor.
  ASSERT_EQ(ring->openings.size(), 1u);
  const Opening& win = ring->openings[0];
  EXPECT_EQ(win.kind, OpeningKind::Window);
  EXPECT_NEAR(win.at, 0.9, 1e-6);
  EXPECT_NEAR(win.width, 1.2, 1e-6);
  EXPECT_NEAR(win.sill, 0.9, 1e-9);
  EXPECT_NEAR(win.head, 2.1, 1e-9);
  // The door (centre y = 2.5 m down the partition drawn from y = 0) in the partition.
  ASSERT_EQ(part->openings.size(), 1u);
  const Opening& door = part->openings[0];
  EXPECT_EQ(door.kind, OpeningKind::Door);
  EXPECT_NEAR(door.at, 2.5 - 0.45, 1e-6);
  EXPECT_NEAR(door.width, 0.9, 1e-6);
  EXPECT_NEAR(door.head, 2.1, 1e-9);
  EXPECT_EQ(door.name, "Door");
  EXPECT_GT(door.where.line, 0);
  // Labels well inside their rooms, and the rooms come out as two spaces joined by a door.
  ASSERT_EQ(p.rooms.size(), 2u);
  EXPECT_GT(p.rooms[0].label->x, 0.5);
  EXPECT_LT(p.rooms[0].label->x, 3.5);
  EXPECT_GT(p.rooms[1].label->x, 4.3);
  const CellComplex c = build_cells(p);
  EXPECT_EQ(cells_are_valid(c), "");
  EXPECT_TRUE(c.warnings.empty()) << c.warnings.front();
  int doors = 0, windows = 0;
  for (const Portal& q : c.portals) doors += q.kind == PortalKind::Door, windows += q.kind == PortalKind::Window;
  EXPECT_GT(doors, 0);
  EXPECT_GT(windows, 0);
  // The observer at (1, −2) looks along yaw 3π/2: (−sin, −cos) = (1, 0), east, into the kitchen.
  ASSERT_TRUE(p.view.has_value());
  EXPECT_NEAR(p.view->eye.z, 1.6, 1e-12);
  EXPECT_NEAR(p.view->look.x - p.view->eye.x, 1, 1e-6);
  EXPECT_NEAR(p.view->look.y - p.view->eye.y, 0, 1e-6);
  EXPECT_NEAR(p.view->fov_deg, 63, 1e-3);
}

TEST(SweetHome, ArcWallIsTessellatedWithinTheTolerance) {
  TempDir dir;
  // A half circle from (0, 0) to (200, 0) cm: positive arcExtent bulges towards −y on
  // the screen (Wall.java), +y in plan: centre (1, 0) m, radius 1 m, top at (1, 1).
  const Plan p = read_sweet_home(dir.write("Home.xml", R"(<home wallHeight='250'>
  <wall id='arc' xStart='0' yStart='0' xEnd='200' yEnd='0' thickness='10' arcExtent='3.1415927'/>
</home>)"));
  ASSERT_EQ(p.walls.size(), 1u);
  const Wall& w = p.walls[0];
  ASSERT_GT(w.centre.size(), 10u);
  EXPECT_EQ(w.from_arc, std::vector<bool>(w.centre.size() - 1, true));
  EXPECT_EQ(w.centre.front(), (Vec2{0, 0}));
  EXPECT_EQ(w.centre.back(), (Vec2{2, 0}));
  double top = -HUGE_VAL;
  for (size_t k = 0; k < w.centre.size(); ++k) {
    EXPECT_NEAR(length(w.centre[k] - Vec2{1, 0}), 1, 1e-6);
    top = std::max(top, w.centre[k].y);
    if (k == 0) continue;
    // Sagitta of each straight piece within the plan's arc tolerance.
    const double chord = length(w.centre[k] - w.centre[k - 1]);
    EXPECT_LE(1 - std::sqrt(1 - chord * chord / 4), p.arc_tolerance + 1e-9);
  }
  EXPECT_NEAR(top, 1, p.arc_tolerance);
  // The negative extent bulges the other way.
  const Plan q = read_sweet_home(dir.write("Home2.xml", R"(<home wallHeight='250'>
  <wall id='arc' xStart='0' yStart='0' xEnd='200' yEnd='0' thickness='10' arcExtent='-1.5707964'/>
</home>)"));
  double bottom = HUGE_VAL;
  for (Vec2 v : q.walls[0].centre) bottom = std::min(bottom, v.y);
  // Quarter circle on a 2 m chord: sagitta (chord/2)·tan(extent/4) = tan(π/8).
  EXPECT_NEAR(bottom, -std::tan(std::numbers::pi / 8), p.arc_tolerance);
}

// Doors and windows that are not rectangles (cutOutShape, as Sweet Home 3D's arched and round
// windows give it): the wall is cut in strips across the window, each open over what the
// shape opens all across it. No strip opens the wall where the shape leaves it standing,
// and together they open most of the shape; free space under the crown, wall in
// the rectangle's corners beside it. A round window likewise, and an arched door drawn
// against the wall's direction (angle π) the same.
TEST(SweetHome, ArchedAndRoundWindowsCutTheirShapeInStrips) {
  TempDir dir;
  const std::string arch = "M0,1 v-0.788 a0.5,0.2 0 1,1 1,0 v0.788 z";
  const std::string round = "M0,0.5 a0.5,0.5 0 1,0 1,0 a0.5,0.5 0 1,0 -1,0 z";
  const Plan p = read_sweet_home(dir.write("Home.xml", small_home(
      "<doorOrWindow name='Arched' x='200' y='0' elevation='80' width='100' depth='20' height='150' cutOutShape='" + arch +
      "'/>\n<doorOrWindow name='Round' x='600' y='200' angle='1.5707964' elevation='100' width='60' depth='20' height='60' "
      "cutOutShape='" + round + "'/>\n<doorOrWindow name='Arched door' x='500' y='400' angle='3.1415927' width='80' "
      "depth='20' height='200' cutOutShape='" + arch + "'/>\n")));
  const CellComplex c = build_cells(p);
  ASSERT_EQ(cells_are_valid(c), "");
  const auto shape_of = [&](const std::string& path) { return *svg_path_polygons(path); };
  struct Case {
    const char* name;
    std::string path;
    double bottom, height, width;
    Vec2 centre;  // [m] in plan
  };
  // Along a wall's centre line (a polyline, the box's walls joined into one): the distance
  // to the point nearest p, and the point at a distance.
  auto along_of = [](const Wall& w, Vec2 q) {
    double best = HUGE_VAL, at = 0, cum = 0;
    for (size_t i = 0; i + 1 < w.centre.size(); ++i) {
      const Vec2 a = w.centre[i], b = w.centre[i + 1];
      const double len = length(b - a), t = std::clamp(dot(q - a, b - a) / (len * len), 0.0, 1.0);
      if (const double dd = length(a + t * (b - a) - q); dd < best) best = dd, at = cum + t * len;
      cum += len;
    }
    return at;
  };
  auto point_at = [](const Wall& w, double at) {
    for (size_t i = 0; i + 1 < w.centre.size(); ++i) {
      const double len = length(w.centre[i + 1] - w.centre[i]);
      if (at <= len) return w.centre[i] + (at / len) * (w.centre[i + 1] - w.centre[i]);
      at -= len;
    }
    return w.centre.back();
  };
  for (const Case& k : {Case{"Arched", arch, 0.8, 1.5, 1.0, {2, 0}}, Case{"Round", round, 1.0, 0.6, 0.6, {6, -2}},
                        Case{"Arched door", arch, 0.0, 2.0, 0.8, {5, -4}}}) {
    SCOPED_TRACE(k.name);
    const std::vector<Vec2> shape = shape_of(k.path).front();
    std::vector<const Opening*> strips;
    const Wall* in = nullptr;
    for (const Wall& w : p.walls)
      for (const Opening& o : w.openings)
        if (o.name.rfind(std::string(k.name) + " (strip", 0) == 0) strips.push_back(&o), in = &w;
    ASSERT_GE(strips.size(), 3u);
    ASSERT_LE(strips.size(), 12u);
    const double left = along_of(*in, k.centre) - k.width / 2, right = left + k.width;
    double opened = 0;
    for (const Opening* o : strips) {
      EXPECT_GE(o->at, left - 1e-6);
      EXPECT_LE(o->at + o->width, right + 1e-6);
    }
    for (const Opening* o : strips) {
      opened += o->width * (o->head - o->sill);
      // Each strip's corners (a hair inside) lie in the shape (x along the wall; the shape
      // is symmetric, so either way along).
      for (double fx : {0.001, 0.999})
        for (double fz : {0.001, 0.999}) {
          const double x = (o->at + fx * o->width - left) / (right - left);
          const double y = 1 - (o->sill + fz * (o->head - o->sill) - k.bottom) / k.height;
          EXPECT_TRUE(inside_polygon(shape, {x, y})) << o->name << " opens the wall outside its shape at " << x << "," << y;
        }
    }
    const double shape_area = std::fabs(signed_area(shape)) * k.width * k.height;
    EXPECT_GT(opened, 0.8 * shape_area);  // (a 60 cm circle in 4 cm steps: 82 %)
    EXPECT_LE(opened, shape_area + 1e-9);
    // Under the crown free, in the square's top corners wall (in the wall's middle plane).
    const Vec2 mid = point_at(*in, 0.5 * (left + right)), corner = point_at(*in, left + 0.02 * k.width);
    EXPECT_EQ(c.locate({mid.x, mid.y, k.bottom + 0.9 * k.height}).what, Location::What::Cell);
    EXPECT_EQ(c.locate({corner.x, corner.y, k.bottom + 0.98 * k.height}).what, Location::What::Solid);
  }
}

// A door under a half-round fanlight (a window drawn into it, just above it): one opening
// is cut for both, their union, not the rectangle around them: the door's full width up to
// its head, and the fanlight's arch above, in strips.
TEST(SweetHome, ADoorUnderAFanlightCutsTheirUnion) {
  TempDir dir;
  const Plan p = read_sweet_home(dir.write("Home.xml", small_home(
      "<doorOrWindow name='Front door' x='500' y='0' width='80' depth='20' height='200'/>\n"
      "<doorOrWindow name='Fanlight' x='500' y='0' elevation='200' width='80' depth='20' height='30' "
      "cutOutShape='M0,1 a0.5,1 0 1,1 1,0 z'/>\n")));
  const CellComplex c = build_cells(p);
  ASSERT_EQ(cells_are_valid(c), "");
  std::vector<const Opening*> strips;
  for (const Wall& w : p.walls)
    for (const Opening& o : w.openings)
      if (o.name.rfind("Front door + Fanlight (strip", 0) == 0) strips.push_back(&o);
  ASSERT_GE(strips.size(), 3u);
  double width = 0, highest = 0;
  for (const Opening* o : strips) {
    EXPECT_EQ(o->sill, 0);
    EXPECT_GE(o->head, 2.0 - 1e-9);  // the door's head all across
    EXPECT_LE(o->head, 2.3 + 1e-9);  // the fanlight's crown at most
    width += o->width;
    highest = std::max(highest, o->head);
  }
  EXPECT_NEAR(width, 0.8, 1e-6);
  EXPECT_GT(highest, 2.25);
  // The door is 4.6 … 5.4 m along the north wall, at y = 0: free under the crown, wall in
  // the fanlight square's corner, free in the door's corner below it.
  EXPECT_EQ(c.locate({5.0, 0, 2.2}).what, Location::What::Cell);
  EXPECT_EQ(c.locate({4.61, 0, 2.25}).what, Location::What::Solid);
  EXPECT_EQ(c.locate({4.61, 0, 1.95}).what, Location::What::Cell);
}

TEST(SweetHome, SlopedWallKeepsItsSlopeAndSlopesUnderTheCellsAboveIt) {
  TempDir dir;
  // 4 m long, 2.5 m high at its start (the ceiling), 0.5 m at its end; a door 1 m from the start.
  const Plan p = read_sweet_home(dir.write("Home.xml", R"(<home wallHeight='250'>
  <wall id='slope' xStart='0' yStart='0' xEnd='400' yEnd='0' height='250' heightAtEnd='50' thickness='10'/>
  <doorOrWindow name='Low door' x='145' y='0' width='90' depth='10' height='150'/>
</home>)"));
  ASSERT_EQ(p.walls.size(), 1u);
  const Wall& w = p.walls[0];
  EXPECT_NEAR(w.height, 2.5, 1e-9);
  EXPECT_NEAR(w.height_at_end, 0.5, 1e-9);
  ASSERT_EQ(w.openings.size(), 1u);
  EXPECT_NEAR(w.openings[0].at, 1.0, 1e-6);
  for (const std::string& warning : p.warnings) EXPECT_FALSE(contains(warning, "stepped")) << warning;
  const CellComplex c = build_cells(p);
  ASSERT_EQ(cells_are_valid(c), "");
  // Over the wall, cells whose floor is its top: they fill the wall's footprint from its
  // top up to the ceiling, 0.1 m × ∫(2.5 − top) along it (the door is lower than the top
  // everywhere along it: its cell is another, a prism).
  double volume = 0;
  int sloped = 0;
  for (const Cell& cell : c.cells) {
    if (cell.kind != CellKind::Doorway || cell.prism) continue;  // (the door's cell is a prism)
    ++sloped;
    volume += cell.volume();
  }
  EXPECT_GE(sloped, 1);
  EXPECT_NEAR(volume, 0.1 * (2.0 * 4 / 2), 1e-9);  // the wall's top falls 2 m along 4 m: a triangle
  // A wall of no thickness has no top to slope: it is stepped, and says so.
  const Plan sheet = read_sweet_home(dir.write("Home.xml", R"(<home wallHeight='250'>
  <wall id='slope' xStart='0' yStart='0' xEnd='400' yEnd='0' height='250' heightAtEnd='50' thickness='0'/>
</home>)"));
  EXPECT_GT(sheet.walls.size(), 10u);
  bool said = false;
  for (const std::string& warning : sheet.warnings) said |= contains(warning, "of no thickness (heightAtEnd) stepped into");
  EXPECT_TRUE(said);
  EXPECT_EQ(cells_are_valid(build_cells(sheet)), "");
}

TEST(SweetHome, LevelsStackAsStoreysAndAStaircaseCutsTheFloorAbove) {
  TempDir dir;
  const std::string box = R"(
  <wall id='s$' level='$' wallAtStart='w$' wallAtEnd='e$' xStart='0' yStart='400' xEnd='600' yEnd='400' thickness='20'/>
  <wall id='e$' level='$' wallAtStart='s$' wallAtEnd='n$' xStart='600' yStart='400' xEnd='600' yEnd='0' thickness='20'/>
  <wall id='n$' level='$' wallAtStart='e$' wallAtEnd='w$' xStart='600' yStart='0' xEnd='0' yEnd='0' thickness='20'/>
  <wall id='w$' level='$' wallAtStart='n$' wallAtEnd='s$' xStart='0' yStart='0' xEnd='0' yEnd='400' thickness='20'/>
  <room level='$' name='Room $'><point x='10' y='10'/><point x='590' y='10'/><point x='590' y='390'/><point x='10' y='390'/></room>)";
  auto on = [&](const std::string& level) {
    std::string s = box;
    for (size_t k; (k = s.find('$')) != std::string::npos;) s.replace(k, 1, level);
    return s;
  };
  const Plan p = read_sweet_home(dir.write("Home.xml", R"(<home wallHeight='250'>
  <level id='up' name='Upper' elevation='262' floorThickness='12' height='250' elevationIndex='0'/>
  <level id='down' name='Ground' elevation='0' floorThickness='12' height='250' elevationIndex='0'/>
  <level id='loft' name='Loft' elevation='262' floorThickness='12' height='200' elevationIndex='1'/>
  <pieceOfFurniture level='down' name='Staircase' x='300' y='200' width='90' depth='200' height='262'
      staircaseCutOutShape='M0,0 v1 h1 v-1 z'/>)" + on("down") + on("up") + "\n</home>"));
  // Sorted by elevation; the loft at the upper level's elevation is merged into it.
  ASSERT_EQ(p.storeys.size(), 2u);
  EXPECT_EQ(p.storeys[0].name, "Ground");
  EXPECT_EQ(p.storeys[1].name, "Upper + Loft");
  EXPECT_NEAR(p.storeys[0].slab, 0.12, 1e-9);
  EXPECT_NEAR(p.storeys[1].elevation, p.storeys[0].elevation + p.storeys[0].height + p.storeys[0].slab, 1e-12);
  EXPECT_NEAR(p.storeys[1].elevation, 2.62, 1e-9);
  bool merged = false;
  for (const std::string& w : p.warnings) merged |= contains(w, "merged into one storey");
  EXPECT_TRUE(merged);
  // The staircase: a box object, and a hole in the upper floor of its footprint.
  ASSERT_EQ(p.objects.size(), 1u);
  EXPECT_NEAR(p.objects[0].box.x, 0.9, 1e-12);
  EXPECT_NEAR(p.objects[0].position.y, -2.0, 1e-12);
  ASSERT_EQ(p.floor_openings.size(), 1u);
  EXPECT_EQ(p.floor_openings[0].storey, 1);
  EXPECT_NEAR(std::fabs(signed_area(p.floor_openings[0].outline)), 0.9 * 2.0, 1e-9);
  EXPECT_GT(signed_area(p.floor_openings[0].outline), 0);
  const CellComplex c = build_cells(p);
  EXPECT_EQ(cells_are_valid(c), "");
  int stair_portals = 0;
  for (const Portal& q : c.portals) stair_portals += q.kind == PortalKind::Stairwell;
  EXPECT_GT(stair_portals, 0);
}

// ---------------------------------------------------------------------------------
// Odd data is repaired with a warning; what cannot be read is a PlanError naming the
// file, the element and its line.

TEST(SweetHome, LevelsReachingIntoTheFloorAboveAreCut) {
  TempDir dir;
  const Plan p = read_sweet_home(dir.write("Home.xml", R"(<home>
  <level id='a' name='Ground' elevation='0' floorThickness='12' height='300'/>
  <level id='b' name='Upper' elevation='262' floorThickness='12' height='250'/>
  <wall id='w' level='a' xStart='0' yStart='0' xEnd='100' yEnd='0' thickness='10'/>
  <wall id='v' level='b' xStart='0' yStart='0' xEnd='100' yEnd='0' thickness='10' height='400'/>
</home>)"));
  ASSERT_EQ(p.storeys.size(), 2u);
  // 3 m high, but the upper floor (12 cm thick) starts at 2.62 m: 2.5 m high.
  EXPECT_NEAR(p.storeys[0].height, 2.5, 1e-9);
  EXPECT_NEAR(p.storeys[0].slab, 0.12, 1e-9);
  EXPECT_NEAR(p.storeys[1].elevation, 2.62, 1e-9);
  EXPECT_NEAR(p.storeys[1].slab, 0.12, 1e-9);  // the top level: its own floor thickness
  bool cut = false, taller = false;
  for (const std::string& w : p.warnings) {
    cut |= contains(w, "level 'Ground' (3 m high) reaches into the floor of level 'Upper' at 2.62 m: cut to 2.5 m");
    taller |= contains(w, "1 wall(s) taller than their storey cut to its ceiling");  // v, 4 m high
  }
  EXPECT_TRUE(cut);
  EXPECT_TRUE(taller);
  for (const Wall& w : p.walls) EXPECT_EQ(w.height, -1) << w.name;
}

TEST(SweetHome, FurnitureBecomesBoxesTurnedTheWayTheyStand) {
  TempDir dir;
  const Plan p = read_sweet_home(dir.write("Home.xml", small_home(R"(
  <pieceOfFurniture name='Bed' x='150' y='100' elevation='10' angle='1.5707964' width='160' depth='200' height='50'/>
  <furnitureGroup name='Set' x='500' y='200' width='100' depth='100' height='80'>
    <pieceOfFurniture name='Chair' x='480' y='200' width='40' depth='40' height='80'/>
    <doorOrWindow name='Back door' x='600' y='200' angle='4.712389' width='80' depth='20' height='200'/>
  </furnitureGroup>
  <pieceOfFurniture name='Hidden' x='100' y='100' width='10' depth='10' height='10' visible='false'/>
)")));
  ASSERT_EQ(p.objects.size(), 2u);
  const Object& bed = p.objects[0];
  EXPECT_EQ(bed.name, "Bed");
  EXPECT_TRUE(bed.mesh.empty());
  EXPECT_NEAR(bed.position.x, 1.5, 1e-12);
  EXPECT_NEAR(bed.position.y, -1.0, 1e-12);
  EXPECT_NEAR(bed.position.z, 0.1, 1e-12);
  EXPECT_NEAR(bed.box.x, 1.6, 1e-12);
  EXPECT_NEAR(bed.box.y, 2.0, 1e-12);
  EXPECT_NEAR(bed.box.z, 0.5, 1e-12);
  // A quarter turn clockwise on the y-down screen is a quarter turn clockwise in plan too.
  EXPECT_NEAR(bed.rotation_deg.z, -90, 1e-5);
  EXPECT_EQ(p.objects[1].name, "Chair");  // from inside the group
  // The group's door is cut into the east wall (x = 6 m, drawn northwards from y = −4 m).
  const Wall* ring = wall_named(p, "s+e+n+1 more");
  ASSERT_NE(ring, nullptr);
  bool back_door = false;
  for (const Opening& o : ring->openings)
    if (o.name == "Back door") {
      back_door = true;
      EXPECT_NEAR(o.at, 6 + 2 - 0.4, 1e-6);  // the south side is 6 m long
      EXPECT_EQ(o.kind, OpeningKind::Door);
    }
  EXPECT_TRUE(back_door);
}

// Light pieces become the plan's point lights where Sweet Home's 3D view puts them: each
// source at fractions (x, y, z) of the piece's box, (x − ½)·width across and (½ − y)·depth
// along it before its angle (clockwise on the y-down screen) turns it, z·height above its
// floor; the source's colour's hue, and 2 × power × its brightest channel as intensity.
TEST(SweetHomeLights, LightPiecesBecomePointLightsWhereSweetHomePutsThem) {
  TempDir dir;
  const Plan p = read_sweet_home(dir.write("Home.xml", small_home(R"(
  <light name='Pendant' x='200' y='200' elevation='200' width='40' depth='40' height='50' power='0.5'>
    <lightSource x='0.5' y='0.5' z='0.5' color='00FFFFFF'/>
  </light>
  <light name='Spot' x='100' y='100' elevation='100' angle='1.5707964' width='20' depth='10' height='10' power='0.25'>
    <lightSource x='0' y='0' z='1' color='00808080'/>
    <lightSource x='1' y='1' z='0' color='FFFF0000'/>
  </light>
  <light name='Pendant' x='300' y='300' elevation='200' width='40' depth='40' height='50'>
    <lightSource x='0.5' y='0.5' z='0.5' color='00FFFFFF'/>
  </light>
  <light name='Off' x='300' y='100' width='10' depth='10' height='10' power='0'>
    <lightSource x='0.5' y='0.5' z='0.5' color='00FFFFFF'/>
  </light>
  <light name='Broken' x='300' y='150' width='10' depth='10' height='10'>
    <lightSource x='NaN' y='0.5' z='0.5' color='00FFFFFF'/>
    <lightSource x='0.5' y='0.5' z='0.5' color='not a colour'/>
  </light>
)")));
  std::map<std::string, const Light*> by_name;
  for (const Light& l : p.lights) by_name[l.name] = &l;
  ASSERT_EQ(p.lights.size(), 5u) << "Pendant, two Spot sources, the second Pendant, Broken's second source";
  auto expect_at = [](const Light* l, Vec3 at, double intensity, std::array<double, 3> colour) {
    ASSERT_NE(l, nullptr);
    SCOPED_TRACE(l->name);
    EXPECT_EQ(l->kind, LightKind::Point);
    EXPECT_NEAR(l->position.x, at.x, 1e-6);
    EXPECT_NEAR(l->position.y, at.y, 1e-6);
    EXPECT_NEAR(l->position.z, at.z, 1e-6);
    EXPECT_NEAR(l->intensity, intensity, 1e-9);
    for (size_t k = 0; k < 3; ++k) EXPECT_NEAR(l->colour[k], colour[k], 1e-9);
  };
  // (200, 200) cm on screen is (2, −2) m in plan; the source halfway up the 50 cm piece.
  expect_at(by_name["Pendant"], {2.0, -2.0, 2.25}, 1.0, {1, 1, 1});
  // Turned a quarter clockwise: the first source's (−10, +5) cm becomes (−5, −10) on screen.
  expect_at(by_name["Spot, source 1"], {0.95, -0.90, 1.1}, 2 * 0.25 * (128 / 255.0), {1, 1, 1});
  expect_at(by_name["Spot, source 2"], {1.05, -1.10, 1.0}, 0.5, {1, 0, 0});
  expect_at(by_name["Pendant (2)"], {3.0, -3.0, 2.25}, 1.0, {1, 1, 1});
  expect_at(by_name["Broken"], {3.0, -1.5, 0.05}, 1.0, {1, 1, 1});
  EXPECT_EQ(by_name.count("Off"), 0u) << "power 0: off";
  int dropped = 0, white = 0;
  for (const std::string& w : p.warnings) {
    dropped += contains(w, "light 'Broken', light source 1") && contains(w, "light source dropped");
    white += contains(w, "light source 2") && contains(w, "is not a colour: white used");
  }
  EXPECT_EQ(dropped, 1);
  EXPECT_EQ(white, 1);
  // The lamps stay pieces of furniture too.
  EXPECT_EQ(p.objects.size(), 5u);
}

// Debian's example homes: every light piece is lit, each source in free space.
TEST(SweetHomeLights, TheExampleHomesLightsStandInTheirRooms) {
  for (const char* name : kHomes) {
    SCOPED_TRACE(name);
    const fs::path file = kExamples / (std::string(name) + ".xml");
    pugi::xml_document doc;
    ASSERT_TRUE(doc.load_file(file.c_str()));
    size_t sources = 0;
    for (pugi::xpath_node n : doc.select_nodes("//light"))
      if (n.node().attribute("power").as_double(0.5) > 0)
        sources += size_t(std::distance(n.node().children("lightSource").begin(), n.node().children("lightSource").end()));
    const Plan p = read_sweet_home(file.string());
    EXPECT_EQ(p.lights.size(), sources);
    EXPECT_GT(sources, 0u);
    const CellComplex c = build_cells(p);
    for (const Light& l : c.lights) {
      const Location at = c.locate(l.position);
      EXPECT_EQ(at.what, Location::What::Cell) << l.name << " at " << l.position.x << ", " << l.position.y << ", " << l.position.z;
    }
  }
}

/// An L-shaped block as an OBJ file, in Sweet Home's model axes (y up, z towards the
/// front), 2 × 1 × 3 units and off the origin: 8 + 4 vertices, every face a quad.
std::string l_block_obj() {
  // The L in the x–y plane (a 2-wide foot, a 1-wide upright 3 high), extruded along z 1 deep.
  const double xy[6][2] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 3}, {0, 3}};
  std::string obj = "# an L\nmtllib missing.mtl\nusemtl nowhere\n";
  for (double z : {10.0, 11.0})
    for (const auto& p : xy) obj += "v " + std::to_string(p[0] + 5) + " " + std::to_string(p[1] - 2) + " " + std::to_string(z) + "\n";
  // Front (z = 11, facing +z) and back (z = 10) as two quads each, then the six sides.
  obj += "f 7 8 9 10\nf 7 10 11 12\nf 1 4 3 2\nf 1 6 5 4\n";
  for (int k = 0; k < 6; ++k) {
    const int a = k + 1, b = (k + 1) % 6 + 1;
    obj += "f " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(b + 6) + " " + std::to_string(a + 6) + "\n";
  }
  return obj;
}

/// Signed volume of a closed mesh: positive when its triangles face outwards.
double signed_volume(const Mesh& m) {
  double v = 0;
  for (const auto& t : m.triangles)
    v += dot(m.vertices[size_t(t[0])], cross(m.vertices[size_t(t[1])], m.vertices[size_t(t[2])])) / 6;
  return v;
}

// A piece's model, inside the .sh3d or beside a bare Home.xml, is read and fitted to the
// piece as Sweet Home fits it: its bounds scaled to width × depth × height, its front
// (Sweet Home's +z) towards the plan's −y before the piece's angle turns it; mirrored, it
// is still closed and faces outwards. A model that is not at hand leaves a box and a warning.
TEST(SweetHome, FurnitureModelsAreReadAndFittedToTheirPieces) {
  TempDir dir;
  const std::string pieces = R"(
  <pieceOfFurniture name='L' model='1/l.obj' x='100' y='100' width='80' depth='40' height='120'/>
  <pieceOfFurniture name='Mirrored L' model='1/l.obj' modelMirrored='true' x='200' y='100' width='80' depth='40' height='120'/>
  <pieceOfFurniture name='Turned L' model='1/l.obj' x='300' y='300' angle='1.5707964' width='80' depth='40' height='120'/>
  <pieceOfFurniture name='Lost' model='2/lost.obj' x='100' y='300' width='50' depth='50' height='50'/>
)";
  const std::string sh3d = dir.zip("models.sh3d", {{"Home.xml", small_home(pieces)}, {"1/l.obj", l_block_obj()}});
  const Plan p = read_sweet_home(sh3d);
  std::map<std::string, const Object*> by_name;
  for (const Object& o : p.objects) by_name[o.name] = &o;
  ASSERT_EQ(by_name.size(), 4u);
  for (const char* name : {"L", "Mirrored L", "Turned L"}) {
    SCOPED_TRACE(name);
    const Object& o = *by_name[name];
    ASSERT_TRUE(o.model);
    const Mesh& m = *o.model;
    EXPECT_TRUE(m.closed);
    EXPECT_EQ(m.vertices.size(), 12u);
    Vec3 lo{1e9, 1e9, 1e9}, hi{-1e9, -1e9, -1e9};
    for (const Vec3& v : m.vertices) {
      lo = {std::min(lo.x, v.x), std::min(lo.y, v.y), std::min(lo.z, v.z)};
      hi = {std::max(hi.x, v.x), std::max(hi.y, v.y), std::max(hi.z, v.z)};
    }
    EXPECT_NEAR(lo.x, -0.4, 1e-9);
    EXPECT_NEAR(hi.x, 0.4, 1e-9);
    EXPECT_NEAR(lo.y, -0.2, 1e-9);
    EXPECT_NEAR(hi.y, 0.2, 1e-9);
    EXPECT_NEAR(lo.z, 0, 1e-9);
    EXPECT_NEAR(hi.z, 1.2, 1e-9);
    // An L of 4 of its 6 unit squares: 4/6 of the box's volume, facing outwards.
    EXPECT_NEAR(signed_volume(m), 0.8 * 0.4 * 1.2 * 4 / 6, 1e-9);
    // The foot (model x from 0 to 2, y below 1) lies along the plan's x; mirrored, to the other side.
    const bool mirrored = std::string(name) == "Mirrored L";
    int foot_far_side = 0;
    for (const Vec3& v : m.vertices)
      if (v.z < 0.5 && std::fabs(std::fabs(v.x) - 0.4) < 1e-9) foot_far_side += (v.x > 0) != mirrored;
    EXPECT_EQ(foot_far_side, 4);
    // Sweet Home's front (+z) is the plan's −y: the vertices of the front face are at y = −0.2.
    EXPECT_NEAR(o.rotation_deg.z, std::string(name) == "Turned L" ? -90.0 : 0.0, 1e-4);
  }
  // The same model is read once and shared.
  EXPECT_EQ(by_name["L"]->model->triangles.size(), by_name["Turned L"]->model->triangles.size());
  EXPECT_FALSE(by_name["Lost"]->model);
  EXPECT_NEAR(by_name["Lost"]->box.x, 0.5, 1e-12);
  int lost = 0;
  for (const std::string& w : p.warnings) lost += contains(w, "(pieceOfFurniture 'Lost'): model 2/lost.obj is not at hand");
  EXPECT_EQ(lost, 1);
  // Beside a bare Home.xml, the model is found at the path the piece names.
  fs::create_directories(fs::path(dir.write("x", "")).parent_path() / "1");
  const std::string model_file = dir.write("1/l.obj", l_block_obj());
  const Plan bare = read_sweet_home(dir.write("Home.xml", small_home(pieces)));
  for (const Object& o : bare.objects) {
    EXPECT_TRUE(o.name == "Lost" || o.model) << o.name;
  }
  // But only below the home's folder: a home names no file elsewhere on the machine.
  const Plan elsewhere = read_sweet_home(dir.write(
      "Elsewhere.xml", small_home("<pieceOfFurniture name='Far' model='" + model_file +
                                  "' x='100' y='100' width='80' depth='40' height='120'/>\n"
                                  "<pieceOfFurniture name='Up' model='../" + fs::path(model_file).parent_path().parent_path().filename().string() +
                                  "/1/l.obj' x='200' y='100' width='80' depth='40' height='120'/>\n")));
  ASSERT_EQ(elsewhere.objects.size(), 2u);
  EXPECT_FALSE(elsewhere.objects[0].model);
  EXPECT_FALSE(elsewhere.objects[1].model);
  // A drawing of them: the models' silhouettes and creases are drawn.
  const CellComplex c = build_cells(p);
  const Camera cam = Camera::look_at({2, -3.5, 1.6}, {1.5, -1, 0.5}, 70, 320, 180);
  const VisibleSet vs = find_visible(c, cam, c.locate(cam.eye).cell);
  int furniture = 0;
  for (const Stroke& st : draw_view(c, prepare_line_scene(c), cam, vs).strokes) furniture += st.layer == Layer::Furniture;
  EXPECT_GT(furniture, 12);
}

// The example homes' furniture comes from Sweet Home's catalogue; .ci/install-deps puts
// those models beside the homes. Every piece of every home then has its model.
TEST(SweetHome, TheExampleHomesFurnitureHasItsModels) {
  if (!fs::exists(kExamples / "com/eteks/sweethome3d/io/resources/armchair.obj"))
    GTEST_SKIP() << "the catalogue's models are not in " << kExamples << " (run .ci/install-deps as root)";
  for (const char* home : kHomes) {
    SCOPED_TRACE(home);
    const Plan p = read_sweet_home((kExamples / (std::string(home) + ".xml")).string());
    size_t with_model = 0;
    for (const Object& o : p.objects) with_model += o.model != nullptr;
    EXPECT_EQ(with_model, p.objects.size());
    for (const std::string& w : p.warnings) EXPECT_FALSE(contains(w, "not at hand")) << w;
  }
}

// Debian's example homes colour many pieces part by part (25 to 108 <material> elements
// each, named after the Java 3D materials their catalogue models use): every piece that has
// a colour of its own, a modelMaterials colour (opaque) for a material its model's OBJ
// uses, a model whose MTL gives one of its materials a Kd, or a model using a material no
// MTL of its defines but Java 3D's built-in table does (as most catalogue models do, with
// no MTL at all), is no longer Avenues' default grey, and no other is. The oracle reads the
// XML, the OBJ's usemtl, f and mtllib lines and the MTL's newmtl and Kd lines itself.
TEST(SweetHome, TheExampleHomesPiecesTakeTheirModelMaterialsColours) {
  if (!fs::exists(kExamples / "com/eteks/sweethome3d/io/resources/armchair.obj"))
    GTEST_SKIP() << "the catalogue's models are not in " << kExamples << " (run .ci/install-deps as root)";
  int before_total = 0, after_total = 0;
  for (const char* home : kHomes) {
    SCOPED_TRACE(home);
    const fs::path file = kExamples / (std::string(home) + ".xml");
    pugi::xml_document doc;
    ASSERT_TRUE(doc.load_file(file.c_str()));
    const std::string text = avenues::testing::slurp(file);
    std::vector<int> line_starts{0};
    for (size_t i = 0; i < text.size(); ++i)
      if (text[i] == '\n') line_starts.push_back(int(i) + 1);
    auto line_of = [&](const pugi::xml_node& n) {
      const int at = int(n.offset_debug()) - 1;  // pugixml points at the name, after '<'
      return int(std::upper_bound(line_starts.begin(), line_starts.end(), at) - line_starts.begin());
    };
    // A model's material names (its usemtl lines), and those of them that the MTL libraries
    // beside it (its mtllib lines) give a Kd.
    struct ModelNames {
      std::set<std::string> used, coloured;
    };
    std::map<std::string, ModelNames> models;
    auto lines_of = [](const fs::path& f, const std::string& key, auto&& take) {
      std::ifstream in(f);
      for (std::string l; std::getline(in, l);) {
        if (!l.empty() && l.back() == '\r') l.pop_back();
        if (l.rfind(key, 0) == 0) take(l.substr(key.size()));
      }
    };
    auto names_of = [&](const std::string& model) -> const ModelNames& {
      auto [it, fresh] = models.try_emplace(model);
      if (fresh) {
        const fs::path obj = kExamples / model;
        lines_of(obj, "usemtl ", [&](const std::string& n) { it->second.used.insert(n); });
        // Faces before the first usemtl are "default" (one of Java 3D's names), in a file that
        // uses materials at all.
        bool named = false, face_before = false;
        {
          std::ifstream in(obj);
          for (std::string l; std::getline(in, l);) {
            named |= l.rfind("usemtl ", 0) == 0;
            face_before |= !named && l.rfind("f ", 0) == 0;
          }
        }
        if (named && face_before) it->second.used.insert("default");
        std::set<std::string> defined;  // by an MTL library of the model
        lines_of(obj, "mtllib ", [&](const std::string& lib) {
          std::string current;
          std::ifstream in(obj.parent_path() / lib);
          for (std::string l; std::getline(in, l);) {
            if (!l.empty() && l.back() == '\r') l.pop_back();
            if (l.rfind("newmtl ", 0) == 0) defined.insert(current = l.substr(7));
            if (l.rfind("Kd ", 0) == 0 && it->second.used.count(current)) it->second.coloured.insert(current);
          }
        });
        for (const std::string& n : it->second.used)
          if (!defined.count(n) && java3d_material_colour(n)) it->second.coloured.insert(n);
      }
      return it->second;
    };
    std::map<int, bool> expected;  // by the piece's line: coloured
    int own = 0;
    for (const pugi::xpath_node& xn : doc.select_nodes("//pieceOfFurniture | //light")) {
      const pugi::xml_node n = xn.node();
      if (std::string(n.attribute("visible").value()) == "false") continue;
      bool coloured = !std::string(n.attribute("color").value()).empty();
      own += coloured;
      const ModelNames& names_used = names_of(n.attribute("model").value());
      coloured |= !names_used.coloured.empty();
      for (const pugi::xml_node m : n.children("material")) {
        const std::string colour = m.attribute("color").value();
        const std::string names = m.attribute("key") ? m.attribute("key").value() : m.attribute("name").value();
        coloured |= colour.size() == 8 && colour.compare(0, 2, "00") != 0 && names_used.used.count(names) > 0;
      }
      expected[line_of(n)] = coloured;
    }
    const Plan p = read_sweet_home(file.string());
    const std::vector<PlacedObject> placed = place_objects(build_cells(p));
    ASSERT_EQ(placed.size(), p.objects.size());
    int after = 0;
    for (size_t i = 0; i < placed.size(); ++i) {
      bool coloured = false;
      for (const Material& m : placed[i].paint.materials) coloured |= m.colour != Material().colour;
      ASSERT_TRUE(expected.count(p.objects[i].where.line)) << p.objects[i].where.str();
      EXPECT_EQ(coloured, expected[p.objects[i].where.line]) << p.objects[i].where.str();
      after += coloured;
    }
    EXPECT_GT(after, own) << "pieces coloured by their modelMaterials as well as by their own colour";
    before_total += own;
    after_total += after;
  }
  std::printf("example homes: %d pieces in colours of their own (their color), %d with their modelMaterials\n",
              before_total, after_total);
}

TEST(SweetHome, OddDataIsDroppedWithAWarning) {
  TempDir dir;
  const Plan p = read_sweet_home(dir.write("Home.xml", small_home(R"(
  <wall id='nan' xStart='NaN' yStart='0' xEnd='100' yEnd='0' thickness='10'/>
  <wall id='dot' xStart='50' yStart='50' xEnd='50' yEnd='50' thickness='10'/>
  <doorOrWindow name='Floating' x='200' y='200' width='80' depth='10' height='200'/>
)")));
  auto warned = [&](const std::string& what) {
    for (const std::string& w : p.warnings)
      if (contains(w, what)) return true;
    return false;
  };
  EXPECT_TRUE(warned("(wall 'nan'): a coordinate"));
  EXPECT_TRUE(warned("(wall 'dot'): the wall has length 0"));
  EXPECT_TRUE(warned("(doorOrWindow 'Floating'): lies in no wall"));
  EXPECT_EQ(p.walls.size(), 2u);
}

TEST(SweetHome, MalformedHomesGiveAPlanErrorNamingFileElementAndLine) {
  TempDir dir;
  auto error_of = [](const std::string& path) -> std::string {
    try {
      read_sweet_home(path);
    } catch (const PlanError& e) {
      return e.what();
    }
    return "(no error)";
  };
  // Not a zip.
  const std::string fake = dir.write("fake.sh3d", "this is not a zip archive at all");
  EXPECT_TRUE(contains(error_of(fake), fake + ": not a Sweet Home 3D .sh3d file: not a zip archive"))
      << error_of(fake);
  // A zip without Home.xml: one whose "Home" is not a Java stream, one holding nothing of a home.
  const std::string old = dir.zip("old.sh3d", {{"Home", "serialized"}});
  EXPECT_TRUE(contains(error_of(old), old + ":Home: not a readable serialized Java home: byte 0: not a Java "
                                            "serialization stream")) << error_of(old);
  const std::string other = dir.zip("other.sh3d", {{"readme.txt", "hello"}});
  EXPECT_TRUE(contains(error_of(other), other + ": the archive holds neither a Home.xml nor a serialized Home entry"))
      << error_of(other);
  // XML syntax error: its line.
  const std::string broken = dir.write("broken.xml", "<home>\n  <wall id='a'\n  <room/>\n</home>\n");
  EXPECT_TRUE(contains(error_of(broken), broken + ":3:")) << error_of(broken);
  EXPECT_TRUE(contains(error_of(broken), "XML syntax error")) << error_of(broken);
  // ... also inside a .sh3d, where the file is the archive's entry.
  const std::string broken_zip = dir.zip("broken.sh3d", {{"Home.xml", "<home>\n<wall\n"}});
  EXPECT_TRUE(contains(error_of(broken_zip), broken_zip + ":Home.xml:")) << error_of(broken_zip);
  // Not a home.
  EXPECT_TRUE(contains(error_of(dir.write("svg.xml", "<svg/>")), "root element is <svg>, not <home>"));
  // A home whose only wall has no xStart: the wall is dropped (its id and line said), and
  // then the home has no walls.
  try {
    read_sweet_home(dir.write("nox.xml", "<home>\n\n  <wall id='w7' yStart='0' xEnd='100' yEnd='0' thickness='10'/>\n</home>"));
    ADD_FAILURE() << "no error";
  } catch (const PlanError& e) {
    EXPECT_TRUE(contains(e.what(), "the home has no walls: all 1 were dropped")) << e.what();
    EXPECT_TRUE(contains(e.what(), "nox.xml:3:3 (wall 'w7'): wall 'w7' has no 'xStart' attribute")) << e.what();
  }
  // A door whose width is not a number.
  const std::string bad_door = dir.write("door.xml", small_home(
      "  <doorOrWindow name='Garage door' x='10' y='200' width='wide' depth='10' height='200'/>\n"));
  EXPECT_TRUE(contains(error_of(bad_door), "(doorOrWindow 'Garage door'): attribute 'width' of doorOrWindow "
                                           "'Garage door' is not a number: \"wide\""))
      << error_of(bad_door);
  EXPECT_TRUE(contains(error_of(bad_door), "door.xml:13:3")) << error_of(bad_door);
  // A wall on a level the home does not define.
  const std::string no_level = dir.write("level.xml", R"(<home>
  <level id='l0' name='Ground' elevation='0' floorThickness='12' height='250'/>
  <wall id='w1' level='l9' xStart='0' yStart='0' xEnd='100' yEnd='0' thickness='10'/>
</home>)");
  EXPECT_TRUE(contains(error_of(no_level), "level.xml:3:3 (wall 'w1'): wall 'w1' is on level 'l9', which the home "
                                           "does not define"))
      << error_of(no_level);
  // No file at all.
  EXPECT_TRUE(contains(error_of(dir.write("x", "") + "-missing.sh3d"), "cannot open home"));
}

}  // namespace avenues

// Avenues — serialized Sweet Home homes (the Java `Home` entry) and the Java object stream
// reader beneath them (plans/formats/java_stream.h); homes from outside that must open.
#include <gtest/gtest.h>
#include <zip.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include <jpeglib.h>  // after <cstdio>: it needs FILE and size_t

#include "cells/build_cells.h"
#include "render/scene_objects.h"
#include "core/number_format.h"
#include "core/srgb.h"
#include "render/raster.h"
#include "plans/formats/java_stream.h"
#include "plans/formats/sweet_home.h"
#include "plans/plan_writer.h"
#include "ray_oracle.h"
#include "visibility/visible_set.h"
#include "tests/avenues_run.h"
#include "tests/picture_checks.h"
#include "tests/test_files.h"

namespace avenues {
namespace {

namespace fs = std::filesystem;
using java::JavaStreamError;
using java::Stream;

const fs::path kOutside = fs::path(AVENUES_OUTSIDE_DIR) / "sweethome";

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// --- the stream, byte by byte ---------------------------------------------------------

/// Bytes of a stream, written as ObjectOutputStream writes them.
struct Bytes {
  std::string b = std::string("\xAC\xED\x00\x05", 4);
  Bytes& u8(int v) { b += char(v); return *this; }
  Bytes& u16(int v) { return u8(v >> 8).u8(v & 0xFF); }
  Bytes& u32(uint32_t v) { return u16(int(v >> 16)).u16(int(v & 0xFFFF)); }
  Bytes& utf(const std::string& s) { u16(int(s.size())); b += s; return *this; }
  Bytes& uid() { for (int i = 0; i < 8; ++i) u8(0); return *this; }
};

/// `new ArrayList<>(List.of("wall", <the same string again>))`.
Bytes array_list_of_one_string_twice() {
  Bytes s;
  s.u8(0x73).u8(0x72).utf("java.util.ArrayList").uid().u8(0x03).u16(1).u8('I').utf("size").u8(0x78).u8(0x70);
  s.u32(2);                                 // size
  s.u8(0x77).u8(4).u32(2);                  // block data: capacity
  s.u8(0x74).utf("wall");                   // handle 0x7E0002 (0: class, 1: the list)
  s.u8(0x71).u32(0x7E0002);                 // the same string
  s.u8(0x78);
  return s;
}

TEST(JavaStream, ReadsAListItsFieldsAndItsAnnotation) {
  const Stream s = Stream::parse(array_list_of_one_string_twice().b);
  ASSERT_EQ(s.contents.size(), 1u);
  const java::Object* list = s.object(s.contents[0]);
  ASSERT_NE(list, nullptr);
  EXPECT_EQ(s.class_name(*list), "java.util.ArrayList");
  ASSERT_NE(s.field(*list, "size"), nullptr);
  EXPECT_EQ(s.field(*list, "size")->integer, 2);
  const std::vector<java::Value> elements = s.annotation_objects(*list);
  ASSERT_EQ(elements.size(), 2u);
  EXPECT_EQ(elements[0].object, elements[1].object) << "a reference is the object it refers to";
  EXPECT_EQ(s.object(elements[0])->text, "wall");
}

TEST(JavaStream, MalformedStreamsAreRefusedNamingTheByte) {
  auto error_of = [](const std::string& bytes) -> std::string {
    try {
      Stream::parse(bytes);
    } catch (const JavaStreamError& e) {
      return e.what();
    }
    return "(no error)";
  };
  const std::string good = array_list_of_one_string_twice().b;
  EXPECT_TRUE(contains(error_of("PK\x03\x04"), "byte 0: not a Java serialization stream")) << error_of("PK");
  // Cut short anywhere: an error, never a crash or a partial tree.
  for (size_t n = 5; n < good.size(); ++n)  // 4: the header alone, an empty stream
    EXPECT_TRUE(contains(error_of(good.substr(0, n)), "the stream ends")) << n << ": " << error_of(good.substr(0, n));
  // A reference to a handle never assigned.
  std::string bad_ref = good;
  bad_ref[bad_ref.size() - 2] = '\x09';
  EXPECT_TRUE(contains(error_of(bad_ref), "reference to handle 0x7E0009")) << error_of(bad_ref);
  // An array claiming 2^31−1 elements: refused before anything is allocated.
  Bytes huge;
  huge.u8(0x75).u8(0x72).utf("[I").uid().u8(0x02).u16(0).u8(0x78).u8(0x70).u32(0x7FFFFFFF);
  EXPECT_TRUE(contains(error_of(huge.b), "byte 4: an array of 2147483647 elements")) << error_of(huge.b);
  // Arrays of arrays 10,000 deep: refused at the depth cap, no stack overflow.
  Bytes deep;
  deep.u8(0x75).u8(0x72).utf("[Ljava.lang.Object;").uid().u8(0x02).u16(0).u8(0x78).u8(0x70).u32(1);
  for (int i = 0; i < 10000; ++i) deep.u8(0x75).u8(0x71).u32(0x7E0000).u32(1);
  EXPECT_TRUE(contains(error_of(deep.b), "nested deeper than")) << error_of(deep.b);
  // An unknown type code, and an exception recorded in the stream.
  EXPECT_TRUE(contains(error_of(std::string("\xAC\xED\x00\x05\x42", 5)), "byte 4: unknown type code 0x42"));
  EXPECT_TRUE(contains(error_of(std::string("\xAC\xED\x00\x05\x7B", 5)), "records an exception"));
}

// --- homes ----------------------------------------------------------------------------

/// Homes drawn as rooms alone, without a wall: their rooms stand in the open.
const char* const kWithoutWalls[] = {"casa_3_stanze.sh3d", "myHome6Rooms.sh3d", "myHomeHas2RoomsAndADoor.sh3d"};
const char* const kOpenable[] = {"casa-both-formats.sh3d", "home1.sh3d", "holes.sh3d", "beispielhaus.sh3d",
                                 kWithoutWalls[0], kWithoutWalls[1], kWithoutWalls[2]};

#define SKIP_WITHOUT_OUTSIDE()                   \
  if (!fs::exists(kOutside / "casa-both-formats.sh3d")) \
  GTEST_SKIP() << "the homes from outside are not in " << kOutside

void expect_near(Vec2 a, Vec2 b, const std::string& what) {
  EXPECT_NEAR(a.x, b.x, 1e-6) << what;
  EXPECT_NEAR(a.y, b.y, 1e-6) << what;
}

TEST(SweetHomeSerialized, BothEntriesOfCasaGiveTheSamePlan) {
  SKIP_WITHOUT_OUTSIDE();
  const std::string path = (kOutside / "casa-both-formats.sh3d").string();
  const Plan x = read_sweet_home(path, HomeEntry::Xml);
  const Plan s = read_sweet_home(path, HomeEntry::Serialized);
  ASSERT_EQ(x.storeys.size(), 4u);
  ASSERT_EQ(s.storeys.size(), x.storeys.size());
  for (size_t i = 0; i < x.storeys.size(); ++i) {
    EXPECT_EQ(s.storeys[i].name, x.storeys[i].name);
    EXPECT_NEAR(s.storeys[i].elevation, x.storeys[i].elevation, 1e-6);
    EXPECT_NEAR(s.storeys[i].height, x.storeys[i].height, 1e-6);
    EXPECT_NEAR(s.storeys[i].slab, x.storeys[i].slab, 1e-6);
  }
  ASSERT_GT(x.walls.size(), 10u);
  ASSERT_EQ(s.walls.size(), x.walls.size());
  size_t openings = 0;
  for (size_t i = 0; i < x.walls.size(); ++i) {
    const Wall &a = x.walls[i], &b = s.walls[i];
    SCOPED_TRACE("wall " + a.name);
    EXPECT_EQ(b.name, a.name);
    EXPECT_EQ(b.storey, a.storey);
    EXPECT_NEAR(b.thickness, a.thickness, 1e-6);
    EXPECT_NEAR(b.height, a.height, 1e-6);
    ASSERT_EQ(b.centre.size(), a.centre.size());
    for (size_t k = 0; k < a.centre.size(); ++k) expect_near(b.centre[k], a.centre[k], "centre point");
    ASSERT_EQ(b.material >= 0, a.material >= 0);
    if (a.material >= 0) {
      EXPECT_EQ(s.materials[size_t(b.material)].colour, x.materials[size_t(a.material)].colour);
    }
    ASSERT_EQ(b.openings.size(), a.openings.size());
    for (size_t k = 0; k < a.openings.size(); ++k) {
      EXPECT_EQ(b.openings[k].name, a.openings[k].name);
      EXPECT_EQ(b.openings[k].kind, a.openings[k].kind);
      EXPECT_NEAR(b.openings[k].at, a.openings[k].at, 1e-6);
      EXPECT_NEAR(b.openings[k].width, a.openings[k].width, 1e-6);
      EXPECT_NEAR(b.openings[k].sill, a.openings[k].sill, 1e-6);
      EXPECT_NEAR(b.openings[k].head, a.openings[k].head, 1e-6);
    }
    openings += a.openings.size();
  }
  // Of the 64 doors and windows, 24 are shutters on the façade that cut no hole (20 lie
  // in no wall, 4 only reach a little into one: niches); of the other 40, frames and the
  // windows they frame overlap in 14 pairs, one opening each.
  EXPECT_EQ(openings, 26u);
  ASSERT_EQ(s.rooms.size(), x.rooms.size());
  for (size_t i = 0; i < x.rooms.size(); ++i) {
    EXPECT_EQ(s.rooms[i].name, x.rooms[i].name);
    EXPECT_EQ(s.rooms[i].storey, x.rooms[i].storey);
    ASSERT_EQ(s.rooms[i].label.has_value(), x.rooms[i].label.has_value());
    if (x.rooms[i].label) expect_near(*s.rooms[i].label, *x.rooms[i].label, "room label " + x.rooms[i].name);
  }
  ASSERT_EQ(s.objects.size(), x.objects.size());
  for (size_t i = 0; i < x.objects.size(); ++i) {
    const Object &a = x.objects[i], &b = s.objects[i];
    SCOPED_TRACE("piece " + a.name);
    EXPECT_EQ(b.name, a.name);
    EXPECT_EQ(b.storey, a.storey);
    EXPECT_LT(length(b.position - a.position), 1e-6);
    EXPECT_LT(length(b.box - a.box), 1e-6);
    EXPECT_LT(length(b.rotation_deg - a.rotation_deg), 1e-4);
    EXPECT_EQ(b.model != nullptr, a.model != nullptr);
  }
  ASSERT_EQ(s.floor_openings.size(), x.floor_openings.size());
  ASSERT_EQ(s.view.has_value(), x.view.has_value());
  // With both entries, Home.xml is the one read.
  EXPECT_EQ(read_sweet_home(path).walls.front().where.file, path + ":Home.xml");
  EXPECT_EQ(s.walls.front().where.file, path + ":Home");
}

/// The plan as TOML (every object listed with a mesh file of its own), without comments:
/// what the two readers of a home must agree on, line for line.
std::string plan_text(const Plan& p) {
  std::vector<std::string> meshes;
  for (size_t i = 0; i < p.objects.size(); ++i) meshes.push_back(std::to_string(i).append(".obj"));
  std::istringstream in(plan_as_toml(p, meshes));
  std::string out, line;
  while (std::getline(in, line))
    if (!line.starts_with("#")) out.append(line).push_back('\n');
  return out;
}

// A home saved by Sweet Home 3D 7.0.2 itself (tests/sweet_home_3d/SavedBySweetHome3D.java
// says how): its serialized Home and its Home.xml give the same plan, line for line. It
// holds what the examples lack: furniture groups (one inside another, one holding a door,
// their lists serialized as java.util.Arrays$ArrayList), walls named by the ids Sweet Home
// 6.4 and later give them, a curved and a sloped wall, a level sharing another's
// elevation, and a level that is not viewable, left out with its wall.
TEST(SweetHomeSerialized, BothEntriesOfAHomeSavedBySweetHome3D7GiveTheSamePlan) {
  const std::string path = std::string(AVENUES_SOURCE_DIR) + "/tests/sweet_home_3d/saved-by-sweet-home-3d-7.sh3d";
  const Plan x = read_sweet_home(path, HomeEntry::Xml);
  const Plan s = read_sweet_home(path, HomeEntry::Serialized);
  ASSERT_EQ(s.objects.size(), x.objects.size());
  EXPECT_EQ(plan_text(s), plan_text(x));
  for (const Plan* p : {&x, &s}) {
    SCOPED_TRACE(p == &x ? "Home.xml" : "Home");
    // Four levels, one of them hidden and one sharing the basement's elevation: three storeys.
    ASSERT_EQ(p->storeys.size(), 3u);
    EXPECT_EQ(p->storeys[0].name, "Basement + same elevation");
    int hidden_said = 0;
    for (const std::string& w : p->warnings) hidden_said += w.find("level 'hidden' is not viewable") != std::string::npos;
    EXPECT_EQ(hidden_said, 1);
    // The walls beside the house, 30–34 m along: the one on the level at the basement's
    // elevation stands; the one on the hidden level does not.
    int far = 0;
    for (const Wall& w : p->walls) far += w.centre.front().x > 29.9 && w.centre.front().x < 34.1;
    EXPECT_EQ(far, 1);
    // Walls are named by their ids, which Sweet Home makes UUIDs.
    int by_uuid = 0;
    for (const Wall& w : p->walls) by_uuid += w.name.starts_with("wall-") && w.name.size() > 30;
    EXPECT_GE(by_uuid, 3);  // the curved, the sloped and the one on the level at the basement's elevation
    // Every piece of both groups is there, the nested ones too: as many pieces as Home.xml
    // has pieceOfFurniture, doorOrWindow and light elements outside walls' openings.
    EXPECT_GT(p->objects.size(), 100u);
  }
}

TEST(SweetHomeSerialized, EveryHomeFromOutsideOpensWithSoundCells) {
  SKIP_WITHOUT_OUTSIDE();
  for (const char* name : kOpenable) {
    SCOPED_TRACE(name);
    const Plan p = read_sweet_home((kOutside / name).string());
    EXPECT_FALSE(p.walls.empty());
    const CellComplex c = build_cells(p);
    EXPECT_EQ(cells_are_valid(c), "");
    // Sampled views: from each room's label (the first few), 1.6 m above its floor,
    // looking along +x and −y, and the home's own viewpoint where it stands in a cell.
    std::vector<Camera> cams;
    for (size_t r = 0; r < p.rooms.size() && r < 4; ++r) {
      if (!p.rooms[r].label) continue;
      const Vec2 l = *p.rooms[r].label;
      const Vec3 eye{l.x, l.y, p.storeys[size_t(p.rooms[r].storey)].elevation + 1.6};
      cams.push_back(Camera::look_at(eye, eye + Vec3{1, 0, -0.1}, 70, 48, 32));
      cams.push_back(Camera::look_at(eye, eye + Vec3{0, -1, 0.1}, 70, 48, 32));
    }
    if (p.view) cams.push_back(Camera::look_at(p.view->eye, p.view->look, p.view->fov_deg, 48, 32));
    int views = 0;
    for (const Camera& cam : cams) {
      const Location at = c.locate(cam.eye);
      if (at.what != Location::What::Cell) continue;
      const VisibleSet vs = find_visible(c, cam, at.cell, Kernel::Double);
      const avenues::testing::OracleResult r = avenues::testing::check_visible_set(c, cam, vs, 2);
      EXPECT_EQ(r.missing, 0) << "eye " << cam.eye.x << ", " << cam.eye.y << ", " << cam.eye.z;
      EXPECT_EQ(r.extra, 0) << "eye " << cam.eye.x << ", " << cam.eye.y << ", " << cam.eye.z;
      ++views;
    }
    EXPECT_GE(views, 1);
  }
}

// Issue 15's view of casa upstairs, where a ray cast on an export was said to meet a face
// from behind through a crack: on the complex itself every pixel's first opaque hit is a
// face seen from its cell's side, and the search finds every cell the rays cross.
TEST(SweetHomeSerialized, CasaUpstairsViewHasNoCrack) {
  SKIP_WITHOUT_OUTSIDE();
  const CellComplex c = build_cells(read_sweet_home((kOutside / "casa-both-formats.sh3d").string()));
  const Camera cam = Camera::look_at({7.4015, -2.0818, 5.7922}, {5.3072, -6.9461, 5.6373}, 40, 320, 180);
  const Location at = c.locate(cam.eye);
  ASSERT_EQ(at.what, Location::What::Cell);
  int from_behind = 0;
  for (int j = 1; j < cam.height; j += 3)  // every third pixel each way, (60, 112) of the issue among them
    for (int i = 0; i < cam.width; i += 3) {
      const Vec3 dir = cam.ray_through_raster({i + 0.5, j + 0.5});
      double best = HUGE_VAL, facing = 0;
      for (const Cell& cell : c.cells)
        for (const Face& f : cell.faces) {
          const double den = dot(f.plane.n, dir);
          const double t = den == 0 ? -1 : -f.plane.eval(cam.eye) / den;
          if (!(t > 0) || t >= best) continue;
          const Vec3 p = cam.eye + t * dir;
          for (const OpaquePoly& op : f.opaque) {
            bool in = true;
            for (size_t k = 0; k < op.poly.size() && in; ++k)
              in = dot(cross(op.poly[(k + 1) % op.poly.size()] - op.poly[k], p - op.poly[k]), f.plane.n) <= 1e-12;
            if (in) {
              best = t, facing = den;
              break;
            }
          }
        }
      from_behind += facing < 0;  // entering a cell through its opaque face: a crack in front
    }
  EXPECT_EQ(from_behind, 0);
  const VisibleSet vs = find_visible(c, cam, at.cell, Kernel::Double);
  const avenues::testing::OracleResult r = avenues::testing::check_visible_set(c, cam, vs, 3);
  EXPECT_EQ(r.missing, 0);
  EXPECT_EQ(r.extra, 0);
}

/// Runs the real `avenues` with these arguments (by argv, no shell: tests/avenues_run.h);
/// its exit status and stderr.
std::pair<int, std::string> run_avenues(const std::vector<std::string>& args) {
  const avenues::testing::Outcome r = avenues::testing::run_argv(avenues::testing::avenues_argv(args));
  return {r.status, r.err};
}

// Sweet Home 3D opens a damaged home (DefaultHomeInputStream): an archive cut short is read
// from the entries whole before the damage, and content the home names but the archive
// lacks is reported and left out. So does Avenues, saying what was lost; the walls, rooms
// and furniture read are those of the undamaged home, the pieces whose models were lost
// boxes of their size.
TEST(SweetHomeSerialized, DamagedHomesOpenWithWhatIsWholeAndSayWhatWasLost) {
  SKIP_WITHOUT_OUTSIDE();
  auto said = [](const Plan& p, const std::string& what) {
    return std::any_of(p.warnings.begin(), p.warnings.end(), [&](const std::string& w) { return contains(w, what); });
  };
  const Plan cut = read_sweet_home((kOutside / "damagedHome.sh3d").string());
  EXPECT_TRUE(said(cut, "damagedHome.sh3d: the archive is damaged")) << cut.warnings.front();
  EXPECT_TRUE(said(cut, "read from the 7 entries whole before the damage, the rest lost from '4' on"));
  const Plan digests = read_sweet_home((kOutside / "damagedHomeWithContentDigests.sh3d").string());
  EXPECT_TRUE(said(digests, "read from the 4 entries whole before the damage"));
  EXPECT_TRUE(said(digests, "its ContentDigests names 7 entr(ies) the archive does not hold"));
  const Plan no_content = read_sweet_home((kOutside / "damagedHomeInValidZipWithContentDigestsAndNoContent.sh3d").string());
  EXPECT_TRUE(said(no_content, "its ContentDigests names 9 entr(ies) the archive does not hold (0, 1, 2,"));
  EXPECT_FALSE(said(no_content, "the archive is damaged")) << "its zip is whole";
  for (const Plan* p : {&cut, &digests, &no_content}) {
    SCOPED_TRACE(p->source);
    EXPECT_GE(p->walls.size(), 1u);
    EXPECT_GE(p->rooms.size(), 1u);
    EXPECT_GE(p->objects.size(), 2u);
    EXPECT_TRUE(said(*p, "a box of the piece's size stands in"));
    const CellComplex c = build_cells(*p);
    EXPECT_EQ(cells_are_valid(c), "");
  }
  // The same home cut inside its Home entry, or before its first entry ends: refused.
  const std::string bytes = avenues::testing::slurp((kOutside / "damagedHome.sh3d").string());
  avenues::testing::TempDir dir("avenues-damaged");
  for (size_t keep : {size_t(3000), size_t(40)}) {
    const std::string path = dir.write("cut" + std::to_string(keep) + ".sh3d", bytes.substr(0, keep));
    try {
      read_sweet_home(path);
      ADD_FAILURE() << keep << " bytes: no error";
    } catch (const PlanError& e) {
      EXPECT_TRUE(contains(e.what(), "the archive is damaged")) << e.what();
      EXPECT_TRUE(contains(e.what(), "not even its first entry is whole")) << e.what();
    }
  }
}

// Sweet Home 3D shows a home of rooms without walls as floors and ceilings in the open:
// each room edge is a wall of no thickness open its whole length and height, so every room
// is a cell of its own, joined to the outside and its neighbours by gaps all round.
TEST(SweetHomeSerialized, RoomsWithoutWallsStandInTheOpen) {
  SKIP_WITHOUT_OUTSIDE();
  const size_t rooms[] = {3, 6, 2};
  for (size_t i = 0; i < std::size(kWithoutWalls); ++i) {
    SCOPED_TRACE(kWithoutWalls[i]);
    const Plan p = read_sweet_home((kOutside / kWithoutWalls[i]).string());
    EXPECT_EQ(p.rooms.size(), rooms[i]);
    for (const Wall& w : p.walls) {
      EXPECT_EQ(w.thickness, 0) << w.name;
      ASSERT_EQ(w.openings.size(), 1u) << w.name;
      EXPECT_EQ(w.openings[0].kind, OpeningKind::Gap);
      EXPECT_NEAR(w.openings[0].width, length(w.centre.back() - w.centre.front()), 1e-12) << w.name;
      EXPECT_EQ(w.openings[0].sill, 0);
      EXPECT_EQ(w.openings[0].head, p.storeys[size_t(w.storey)].height);
    }
    bool said = false;
    for (const std::string& w : p.warnings) said |= contains(w, "the home has no walls: its ");
    EXPECT_TRUE(said);
    const CellComplex c = build_cells(p);
    ASSERT_EQ(cells_are_valid(c), "");
    // Each room's label is in a cell of that room, with its floor under it and open sides.
    for (size_t r = 0; r < p.rooms.size(); ++r) {
      const Vec2 l = *p.rooms[r].label;
      const Location at = c.locate({l.x, l.y, 1.0});
      ASSERT_EQ(at.what, Location::What::Cell) << p.rooms[r].name;
      EXPECT_EQ(c.cells[size_t(at.cell)].kind, CellKind::Room) << p.rooms[r].name;
      EXPECT_EQ(c.rooms[size_t(c.cells[size_t(at.cell)].room)].name, p.rooms[r].name);
    }
    // From outside, 4 m off the rooms and 1.6 m up, looking at them: the rays agree.
    Vec2 lo{HUGE_VAL, HUGE_VAL};
    for (const Room& r : p.rooms) lo = {std::min(lo.x, r.label->x), std::min(lo.y, r.label->y)};
    const Camera cam = Camera::look_at({lo.x - 4, lo.y - 4, 1.6}, {p.rooms[0].label->x, p.rooms[0].label->y, 0.5}, 70, 64, 40);
    const Location at = c.locate(cam.eye);
    ASSERT_EQ(at.what, Location::What::Cell);
    const VisibleSet vs = find_visible(c, cam, at.cell, Kernel::Double);
    const avenues::testing::OracleResult r = avenues::testing::check_visible_set(c, cam, vs, 2);
    EXPECT_EQ(r.missing, 0);
    EXPECT_EQ(r.extra, 0);
    EXPECT_GE(vs.cells.size(), p.rooms.size() + 1) << "every room is seen from outside, across the open";
  }
  const auto [status, err] = run_avenues({"cells", (kOutside / kWithoutWalls[0]).string()});
  EXPECT_EQ(status, 0) << err;
}


TEST(SweetHomeSerialized, TheExecutableOpensDamagedHomesSayingSo) {
  SKIP_WITHOUT_OUTSIDE();
  for (const char* name : {"damagedHome.sh3d", "damagedHomeWithContentDigests.sh3d",
                           "damagedHomeInValidZipWithContentDigestsAndNoContent.sh3d"}) {
    const auto [status, err] = run_avenues({"cells", (kOutside / name).string()});
    EXPECT_EQ(status, 0) << name << ": " << err;
    EXPECT_TRUE(contains(err, std::string(name) + ": warning: the ")) << err;
    EXPECT_TRUE(contains(err, "damaged")) << err;
  }
  avenues::testing::TempDir dir("avenues-damaged-cli");
  const std::string cut = dir.write("cut.sh3d", avenues::testing::slurp((kOutside / "damagedHome.sh3d").string()).substr(0, 3000));
  const auto [status, err] = run_avenues({"cells", cut});
  EXPECT_EQ(status, 2) << err;
  EXPECT_TRUE(contains(err, "cut.sh3d: the archive is damaged")) << err;
}

// --- hostile homes (issue 13) -----------------------------------------------------------

class ScratchDir : public avenues::testing::TempDir {
 public:
  ScratchDir() : avenues::testing::TempDir("avenues-sh3ds") {}
  /// A zip `name` in the folder holding these entries, in order (libzip: sizes in the local
  /// headers, a central directory at the end); its path.
  std::string zip(const std::string& name, const std::vector<std::pair<std::string, std::string>>& entries) const {
    const std::string file = (path() / name).string();
    int err = 0;
    zip_t* za = zip_open(file.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &err);
    EXPECT_NE(za, nullptr) << "libzip error " << err;
    if (!za) return file;
    for (const auto& [entry, bytes] : entries)
      EXPECT_GE(zip_file_add(za, entry.c_str(), zip_source_buffer(za, bytes.data(), bytes.size(), 0), 0), 0);
    EXPECT_EQ(zip_close(za), 0);  // writes the entries (their bytes are alive till here)
    return file;
  }
  /// A 2 x 1 PNG, its left pixel red and its right blue (mean (0.5, 0, 0.5) in linear light).
  std::string red_blue_png(const std::string& name) {
    Image png;
    png.resize(2, 1, 3);
    png.data = {255, 0, 0, 0, 0, 255};
    const std::string path = write(name, "");
    write_image(png, path);
    return path;
  }
};

const std::string kBox =
    "  <wall id='s' wallAtStart='w' wallAtEnd='e' xStart='0' yStart='400' xEnd='600' yEnd='400' thickness='20'/>\n"
    "  <wall id='e' wallAtStart='s' wallAtEnd='n' xStart='600' yStart='400' xEnd='600' yEnd='0' thickness='20'/>\n"
    "  <wall id='n' wallAtStart='e' wallAtEnd='w' xStart='600' yStart='0' xEnd='0' yEnd='0' thickness='20'/>\n"
    "  <wall id='w' wallAtStart='n' wallAtEnd='s' xStart='0' yStart='0' xEnd='0' yEnd='400' thickness='20'/>\n";

TEST(SweetHomeHostile, EightThousandNestedGroupsAreReadWithoutRecursion) {
  ScratchDir dir;
  std::string xml = "<home>\n" + kBox;
  for (int i = 0; i < 8000; ++i) xml += "<furnitureGroup name='g'>";
  xml += "<pieceOfFurniture name='Chair' x='100' y='100' width='40' depth='40' height='90'/>";
  for (int i = 0; i < 8000; ++i) xml += "</furnitureGroup>";
  xml += "\n</home>\n";
  const Plan p = read_sweet_home(dir.write("deep.xml", xml));
  ASSERT_EQ(p.objects.size(), 1u);
  EXPECT_EQ(p.objects[0].name, "Chair");
}

TEST(SweetHomeHostile, AHomeWhoseWallsAreAllDroppedSaysWhyForEach) {
  ScratchDir dir;
  std::string xml = "<home>\n";
  for (int i = 0; i < 12; ++i)
    xml += "  <wall id='w" + std::to_string(i) + "' xStart='0' yStart='" + std::to_string(i * 100) +
           "' xEnd='500' yEnd='" + std::to_string(i * 100) + "' thickness='-10'/>\n";
  xml += "</home>\n";
  try {
    read_sweet_home(dir.write("negative.xml", xml));
    ADD_FAILURE() << "no error";
  } catch (const PlanError& e) {
    const std::string what = e.what();
    EXPECT_TRUE(contains(what, "the home has no walls: all 12 were dropped")) << what;
    EXPECT_TRUE(contains(what, "(wall 'w0'): negative thickness -10 cm: wall dropped")) << what;
    EXPECT_TRUE(contains(what, "(wall 'w4'): negative thickness")) << what;
    EXPECT_FALSE(contains(what, "(wall 'w5')")) << what;
    EXPECT_TRUE(contains(what, "... and 7 more")) << what;
  }
}

TEST(SweetHomeHostile, APieceOrWallMissingWhatItCannotDoWithoutIsDroppedNotTheHome) {
  ScratchDir dir;
  const Plan p = read_sweet_home(dir.write("lenient.xml", "<home>\n" + kBox +
      "  <wall id='half' xStart='0' yStart='0' thickness='10'/>\n"
      "  <pieceOfFurniture name='Table' x='300' y='200' depth='80' height='75'/>\n"
      "  <room name='Hall'><point x='10' y='10'/><point x='590'/><point x='590' y='390'/></room>\n"
      "  <pieceOfFurniture name='Chair' x='100' y='100' width='40' depth='40' height='90'/>\n</home>\n"));
  EXPECT_EQ(p.walls.size(), 1u) << "the four joined walls";
  ASSERT_EQ(p.objects.size(), 1u);
  EXPECT_EQ(p.objects[0].name, "Chair");
  EXPECT_TRUE(p.rooms.empty());
  auto warned = [&](const std::string& what) {
    for (const std::string& w : p.warnings)
      if (contains(w, what)) return true;
    return false;
  };
  EXPECT_TRUE(warned("(wall 'half'): wall 'half' has no 'xEnd' attribute: wall dropped"));
  EXPECT_TRUE(warned("(pieceOfFurniture 'Table'): pieceOfFurniture 'Table' has no 'width' attribute"));
  EXPECT_TRUE(warned("(room 'Hall'): a point has no x or y"));
}


TEST(SweetHomeHostile, AModelIsToldByItsContentWhateverItsEntryIsCalled) {
  ScratchDir dir;
  const std::string obj = "# a box\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                          "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
  const std::string xml = "<home>\n" + kBox +
                          "  <pieceOfFurniture name='Cupboard' model='28' x='100' y='100' width='40' depth='40' height='90'/>\n"
                          "  <pieceOfFurniture name='Shelf' model='3/shelf.obj' x='300' y='100' width='40' depth='40' height='90'/>\n"
                          "  <pieceOfFurniture name='Picture' model='9' x='400' y='100' width='40' depth='40' height='90'/>\n"
                          "</home>\n";
  const std::string png = std::string("\x89PNG\r\n\x1a\n", 8) + std::string(32, '\0');
  const std::string path = dir.zip("kitchen.sh3d", {{"Home.xml", xml}, {"28", obj}, {"3/shelf.obj", obj}, {"9", png}});
  const Plan p = read_sweet_home(path);
  ASSERT_EQ(p.objects.size(), 3u);
  EXPECT_NE(p.objects[0].model, nullptr) << "model='28' is an OBJ file";
  EXPECT_NE(p.objects[1].model, nullptr) << "a model in a folder of the archive";
  EXPECT_EQ(p.objects[2].model, nullptr) << "a PNG is no model";
  bool warned = false;
  for (const std::string& w : p.warnings) warned |= contains(w, "model 9 is not an OBJ file");
  EXPECT_TRUE(warned);
}

// A home whose central directory was never written (sizes in the local headers, as libzip
// writes them; Sweet Home 3D's own are in data descriptors, see DamagedHomesOpen...) opens
// from its entries; cut inside its model, the piece is a box and the warning says from
// which entry on the rest was lost.
TEST(SweetHomeHostile, AHomeCutBeforeItsCentralDirectoryOpensFromItsEntries) {
  ScratchDir dir;
  std::string obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 2 3 4\nf 3 1 4\n# ";
  for (uint32_t x = 1, i = 0; i < 4000; ++i) obj += char('a' + (x = x * 1664525u + 1013904223u) % 26);  // not to be deflated away
  obj += "\n";
  const std::string xml = "<home>\n" + kBox +
                          "  <pieceOfFurniture name='Cupboard' model='28' x='100' y='100' width='40' depth='40' height='90'/>\n"
                          "</home>\n";
  const std::string whole = dir.zip("whole.sh3d", {{"Home.xml", xml}, {"28", obj}});
  const std::string bytes = avenues::testing::slurp(whole);
  const size_t directory = bytes.find("PK\x01\x02");
  ASSERT_NE(directory, std::string::npos);
  const Plan p = read_sweet_home(dir.write("no-directory.sh3d", bytes.substr(0, directory)));
  ASSERT_EQ(p.objects.size(), 1u);
  EXPECT_NE(p.objects[0].model, nullptr);
  ASSERT_FALSE(p.warnings.empty());
  EXPECT_TRUE(contains(p.warnings[0], "read from the 2 entries whole before the damage")) << p.warnings[0];
  EXPECT_FALSE(contains(p.warnings[0], "lost")) << p.warnings[0];
  const Plan cut = read_sweet_home(dir.write("cut.sh3d", bytes.substr(0, directory - 100)));
  ASSERT_EQ(cut.objects.size(), 1u);
  EXPECT_EQ(cut.objects[0].model, nullptr) << "a box of its size";
  EXPECT_TRUE(contains(cut.warnings[0], "read from the 1 entries whole before the damage, the rest lost from '28' on"))
      << cut.warnings[0];
}

TEST(SweetHomeColours, WallRoomAndPieceColoursBecomeMaterialsInLinearLight) {
  ScratchDir dir;
  const std::string xml =
      "<home>\n"
      "  <wall id='s' wallAtStart='w' wallAtEnd='e' xStart='0' yStart='400' xEnd='600' yEnd='400' thickness='20' leftSideColor='FF3366CC'/>\n"
      "  <wall id='e' wallAtStart='s' wallAtEnd='n' xStart='600' yStart='400' xEnd='600' yEnd='0' thickness='20' leftSideColor='FF3366CC'/>\n"
      "  <wall id='n' wallAtStart='e' wallAtEnd='w' xStart='600' yStart='0' xEnd='0' yEnd='0' thickness='20' leftSideColor='FF3366CC'/>\n"
      "  <wall id='w' wallAtStart='n' wallAtEnd='s' xStart='0' yStart='0' xEnd='0' yEnd='400' thickness='20' leftSideColor='FF3366CC'/>\n"
      "  <room name='Hall' floorColor='FF808080' ceilingColor='FFFFFFFF'><point x='10' y='10'/><point x='590' y='10'/>"
      "<point x='590' y='390'/><point x='10' y='390'/></room>\n"
      "  <pieceOfFurniture name='Chair' x='100' y='100' width='40' depth='40' height='90' color='FF000000'/>\n"
      "</home>\n";
  const Plan p = read_sweet_home(dir.write("colours.xml", xml));
  auto linear = [](int v) { const double e = v / 255.0; return e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4); };
  ASSERT_EQ(p.walls.size(), 1u);
  ASSERT_GE(p.walls[0].material, 0);
  const Material& wall = p.materials[size_t(p.walls[0].material)];
  EXPECT_NEAR(wall.colour[0], linear(0x33), 1e-12);
  EXPECT_NEAR(wall.colour[1], linear(0x66), 1e-12);
  EXPECT_NEAR(wall.colour[2], linear(0xCC), 1e-12);
  ASSERT_EQ(p.rooms.size(), 1u);
  ASSERT_GE(p.rooms[0].floor, 0);
  ASSERT_GE(p.rooms[0].ceiling, 0);
  EXPECT_NEAR(p.materials[size_t(p.rooms[0].floor)].colour[1], linear(0x80), 1e-12);
  EXPECT_NEAR(p.materials[size_t(p.rooms[0].ceiling)].colour[2], 1.0, 1e-12);
  ASSERT_EQ(p.objects.size(), 1u);
  ASSERT_GE(p.objects[0].material, 0);
  EXPECT_EQ(p.materials[size_t(p.objects[0].material)].colour[0], 0.0);
  // One material a colour, and Sweet Home's default for the walls' right sides, which have none.
  EXPECT_EQ(p.materials.size(), 5u);
  ASSERT_GE(p.walls[0].right_material, 0);
  EXPECT_EQ(p.materials[size_t(p.walls[0].right_material)].colour, Material().colour);
}


// A door or window is a hole through its wall where it crosses the wall's whole thickness,
// or where Sweet Home cuts both sides anyway; a shutter on the façade that only reaches a
// little into the wall is a niche (no hole), and one that only touches the face lies in no
// wall: neither widens the window beside it.
TEST(SweetHomeOpenings, OnlyWhatCrossesAWallOrIsCutThroughBecomesAHole) {
  ScratchDir dir;
  const std::string xml =
      "<home>\n" + kBox +
      // South wall y = 400 cm, 20 cm thick: faces at y = 390 and 410.
      "  <doorOrWindow name='Window' x='200' y='400' width='100' depth='30' height='120' elevation='90'/>\n"
      "  <doorOrWindow name='Shutter touching' x='275' y='417.5' width='50' depth='15' height='120' elevation='90'/>\n"
      "  <doorOrWindow name='Shutter niche' x='125' y='415' width='50' depth='15' height='120' elevation='90'/>\n"
      "  <doorOrWindow name='Thin door' x='450' y='400' width='80' depth='8' height='200' wallCutOutOnBothSides='true'/>\n"
      "  <doorOrWindow name='Thin window' x='400' y='0' width='80' depth='8' height='100' elevation='100'/>\n"
      "</home>\n";
  const Plan p = read_sweet_home(dir.write("openings.xml", xml));
  ASSERT_EQ(p.walls.size(), 1u);
  std::vector<std::string> names;
  for (const Opening& o : p.walls[0].openings) {
    names.push_back(o.name);
    if (o.name == "Window") {
      EXPECT_NEAR(o.width, 1.0, 1e-6) << "no shutter widens it";
    }
  }
  EXPECT_EQ(names.size(), 2u);
  EXPECT_NE(std::find(names.begin(), names.end(), "Window"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "Thin door"), names.end()) << "cut through both sides";
  auto warned = [&](const std::string& piece, const std::string& what) {
    for (const std::string& w : p.warnings)
      if (contains(w, "'" + piece + "'") && contains(w, what)) return true;
    return false;
  };
  EXPECT_TRUE(warned("Shutter touching", "lies in no wall"));
  EXPECT_TRUE(warned("Shutter niche", "reaches only 2.5 cm into wall"));
  EXPECT_TRUE(warned("Thin window", "reaches only 8.0 cm into wall"));
  const CellComplex c = build_cells(p);
  EXPECT_EQ(cells_are_valid(c), "");
}

// Casa's façade shutters stand beside its windows on the outer face: the windows keep
// their own widths (D7 is 120 cm wide; with its shutter S7B taken for a hole it was 180).
TEST(SweetHomeOpenings, CasaWindowsKeepTheirWidths) {
  SKIP_WITHOUT_OUTSIDE();
  for (HomeEntry which : {HomeEntry::Xml, HomeEntry::Serialized}) {
    const Plan p = read_sweet_home((kOutside / "casa-both-formats.sh3d").string(), which);
    int found = 0, shutters = 0;
    for (const Wall& w : p.walls)
      for (const Opening& o : w.openings) {
        for (size_t k = 0; (k = o.name.find('S', k)) != std::string::npos; ++k)  // shutters are S<digit>...
          shutters += (k == 0 || o.name[k - 1] == ' ') && k + 1 < o.name.size() && std::isdigit(static_cast<unsigned char>(o.name[k + 1]));
        if (o.name.rfind("D7", 0) == 0 || o.name.rfind("F7", 0) == 0) {
          ++found;
          EXPECT_NEAR(o.width, 1.20, 0.01) << o.name;
        }
      }
    EXPECT_EQ(found, 1);
    EXPECT_EQ(shutters, 0) << "no shutter is a hole";
  }
}


// --- textures and the two sides of a wall -----------------------------------------------

/// A .sh3d in `dir` named `file` holding these entries.
std::string write_sh3d(const ScratchDir& dir, const std::string& file,
                       const std::vector<std::pair<std::string, std::string>>& entries) {
  const std::string path = (fs::path(dir.write("x", "")).parent_path() / file).string();
  int err = 0;
  zip_t* za = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &err);
  EXPECT_NE(za, nullptr);
  for (const auto& [name, bytes] : entries)
    EXPECT_GE(zip_file_add(za, name.c_str(), zip_source_buffer(za, bytes.data(), bytes.size(), 0), 0), 0);
  EXPECT_EQ(zip_close(za), 0);
  return path;
}

/// A w × h JPEG of one colour, written by libjpeg.
std::string flat_jpeg(int w, int h, const unsigned char rgb[3]) {
  jpeg_compress_struct c;
  jpeg_error_mgr err;
  c.err = jpeg_std_error(&err);
  jpeg_create_compress(&c);
  unsigned char* out = nullptr;
  unsigned long size = 0;
  jpeg_mem_dest(&c, &out, &size);
  c.image_width = JDIMENSION(w), c.image_height = JDIMENSION(h), c.input_components = 3, c.in_color_space = JCS_RGB;
  jpeg_set_defaults(&c);
  jpeg_set_quality(&c, 95, TRUE);
  jpeg_start_compress(&c, TRUE);
  std::vector<unsigned char> row(size_t(w) * 3);
  for (int x = 0; x < w; ++x) std::copy(rgb, rgb + 3, row.begin() + 3 * x);
  while (c.next_scanline < c.image_height) {
    JSAMPROW r = row.data();
    jpeg_write_scanlines(&c, &r, 1);
  }
  jpeg_finish_compress(&c);
  jpeg_destroy_compress(&c);
  std::string bytes(reinterpret_cast<const char*>(out), size);
  std::free(out);
  return bytes;
}

using avenues::testing::linear8;
using avenues::testing::expect_pixel_shows;

// A texture is its image's mean colour in linear light: a PNG half red, half blue is
// (0.5, 0, 0.5) however it is encoded; a JPEG of one colour is that colour (to the
// rounding of its DCT). Each side of a wall keeps its own: texture on the left, colour on
// the right, and the picture shows each from its own side.
TEST(SweetHomeColours, TexturesAreTheirImagesMeanAndEachWallSideItsOwn) {
  ScratchDir dir;
  dir.red_blue_png("t.png");
  const unsigned char ochre[3] = {200, 120, 40};
  const std::string xml =
      "<home>\n"
      "  <wall id='s' wallAtStart='w' wallAtEnd='e' xStart='0' yStart='400' xEnd='600' yEnd='400' thickness='20'/>\n"
      "  <wall id='e' wallAtStart='s' wallAtEnd='n' xStart='600' yStart='400' xEnd='600' yEnd='0' thickness='20'/>\n"
      "  <wall id='n' wallAtStart='e' wallAtEnd='w' xStart='600' yStart='0' xEnd='0' yEnd='0' thickness='20'"
      " rightSideColor='FF00FF00'><texture attribute='leftSideTexture' name='Purple' image='7' width='50' height='50'/></wall>\n"
      "  <wall id='w' wallAtStart='n' wallAtEnd='s' xStart='0' yStart='0' xEnd='0' yEnd='400' thickness='20'/>\n"
      "  <room name='Hall'><texture attribute='floorTexture' name='Ochre' image='8' width='50' height='50'/>"
      "<point x='10' y='10'/><point x='590' y='10'/><point x='590' y='390'/><point x='10' y='390'/></room>\n"
      "  <pieceOfFurniture name='Chest' x='100' y='300' width='40' depth='40' height='90'>"
      "<texture name='Missing' image='9' width='10' height='10'/></pieceOfFurniture>\n"
      "</home>\n";
  const std::string path = write_sh3d(dir, "textures.sh3d",
                                      {{"Home.xml", xml}, {"7", avenues::testing::slurp(dir.path() / "t.png")},
                                       {"8", flat_jpeg(16, 16, ochre)}});
  const Plan p = read_sweet_home(path);
  const Wall* n = nullptr;
  for (const Wall& w : p.walls)
    if (w.name == "n") n = &w;
  ASSERT_NE(n, nullptr) << "a wall whose sides differ from its neighbours' is not joined to them";
  ASSERT_GE(n->material, 0);
  ASSERT_GE(n->right_material, 0);
  const Material& left = p.materials[size_t(n->material)];
  EXPECT_EQ(left.name, "texture 'Purple' (7)");
  EXPECT_NEAR(left.colour[0], 0.5, 1e-12);
  EXPECT_NEAR(left.colour[1], 0.0, 1e-12);
  EXPECT_NEAR(left.colour[2], 0.5, 1e-12);
  EXPECT_EQ(p.materials[size_t(n->right_material)].colour, (std::array<double, 3>{0, 1, 0}));
  ASSERT_EQ(p.rooms.size(), 1u);
  ASSERT_GE(p.rooms[0].floor, 0);
  const Material& floor = p.materials[size_t(p.rooms[0].floor)];
  for (size_t k = 0; k < 3; ++k)
    EXPECT_NEAR(floor.colour[k], linear8(ochre[k]), linear8(ochre[k] + 2) - linear8(ochre[k])) << k;
  bool missing = false;
  for (const std::string& w : p.warnings) missing |= contains(w, "texture 'Missing' (image 9) is not at hand");
  EXPECT_TRUE(missing);
  ASSERT_EQ(p.objects.size(), 1u);
  EXPECT_EQ(p.objects[0].material, -1);
  ASSERT_EQ(cells_are_valid(build_cells(p)), "");
  // Written as Avenues' TOML (--save-plan) and read back, each side keeps its material.
  const Plan back = parse_plan(plan_as_toml(p), "textures.toml");
  const Wall* bn = nullptr;
  for (const Wall& w : back.walls)
    if (w.name == "n") bn = &w;
  ASSERT_NE(bn, nullptr);
  ASSERT_GE(bn->right_material, 0);
  EXPECT_EQ(back.materials[size_t(bn->material)].colour, left.colour);
  EXPECT_EQ(back.materials[size_t(bn->right_material)].colour, (std::array<double, 3>{0, 1, 0}));

  // The picture: wall n from inside the room is the purple texture, from outside green,
  // each under the light at the eye (the same factor in every channel).
  struct Look { Vec3 eye; std::array<double, 3> colour; };
  for (const Look& look : {Look{{3, -2, 1.2}, left.colour}, Look{{3, 3, 1.2}, {0, 1, 0}}}) {
    const std::string out = (dir.path() / "wall.ppm").string();
    const auto [status, err] =
        run_avenues({"view", path, "--eye", format_number(look.eye.x) + "," + format_number(look.eye.y) + ",1.2",
                     "--look", "3,0,1.2", "--fov", "20", "--size", "32x18", "--lights", "eye", "-o", out});
    ASSERT_EQ(status, 0) << err;
    const Image pic = read_image(out);
    ASSERT_EQ(pic.channels, 3);
    const uint8_t* px = pic.row(9) + 16 * 3;
    double light = 0;  // the light on the wall: the brightest channel over its colour
    for (size_t k = 0; k < 3; ++k)
      if (look.colour[k] > 0) light = std::max(light, linear8(px[k]) / look.colour[k]);
    ASSERT_GT(light, 0.05) << "the wall is lit";
    for (size_t k = 0; k < 3; ++k) {
      const double want = look.colour[k] * light;
      const double step = linear8(std::min(255, px[k] + 1)) - linear8(std::max(0, px[k] - 1));  // 8-bit rounding
      EXPECT_NEAR(linear8(px[k]), want, step) << "eye y " << look.eye.y << ", channel " << k << ": " << int(px[k]);
    }
  }
}

// Casa's stone walls are textured by a JPEG: both entries give them its mean colour, a
// stone's (neither Avenues' grey nor black), on the left side only.
TEST(SweetHomeColours, CasaStoneWallsTakeTheirJpegTexturesMeanColour) {
  SKIP_WITHOUT_OUTSIDE();
  std::optional<std::array<double, 3>> stone;
  for (HomeEntry which : {HomeEntry::Xml, HomeEntry::Serialized}) {
    const Plan p = read_sweet_home((kOutside / "casa-both-formats.sh3d").string(), which);
    int textured = 0;
    for (const Wall& w : p.walls)
      if (w.material >= 0 && p.materials[size_t(w.material)].name == "texture 'Stone' (33)") {
        ++textured;
        const std::array<double, 3> c = p.materials[size_t(w.material)].colour;
        if (!stone) stone = c;
        EXPECT_EQ(c, *stone);
        for (double v : c) EXPECT_TRUE(v > 0.02 && v < 0.9) << v;
        EXPECT_NE(c, Material().colour);
      }
    EXPECT_GE(textured, 1) << (which == HomeEntry::Xml ? "Home.xml" : "Home");
  }
}

// --- furniture in its model's colours ----------------------------------------------------

/// A unit cube in Sweet Home's model axes (y up, +z the front), four materials: "Body" on
/// the back and the two sides, "Front", "Top", "Ghost" underneath; its MTL in cube.mtl.
const std::string kCubeObj =
    "mtllib cube.mtl\n"
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "usemtl Body\nf 1 4 3 2\nf 1 5 8 4\nf 2 3 7 6\n"
    "usemtl Front\nf 5 6 7 8\n"
    "usemtl Top\nf 4 8 7 3\n"
    "usemtl Ghost\nf 1 2 6 5\n";
const std::string kCubeMtl =
    "newmtl Body\nKd 0.5 0.5 0.5\n"
    "newmtl Front\nKa 0.2 0.2 0.2\nKd 0.8 0.4 0.2\n"
    "newmtl Top\nKd 0 0 0\nmap_Kd tex.png\n"
    "newmtl Ghost\nKd 0.2 0.6 0.4\nmap_Kd -s 2 2 1 missing.png\n";

/// The cube's materials in linear light, by the plan direction its face looks: MTL Kd made
/// linear (Kd is sRGB-encoded, as Sweet Home reads it), the PNG's mean (half red, half blue).
struct CubeColours {
  std::array<double, 3> body, front, top, ghost;
};
CubeColours cube_colours_from_mtl() {
  auto kd = [](double r, double g, double b) {
    return std::array<double, 3>{linear_from_srgb(r), linear_from_srgb(g), linear_from_srgb(b)};
  };
  return {kd(0.5, 0.5, 0.5), kd(0.8, 0.4, 0.2), {0.5, 0.0, 0.5}, kd(0.2, 0.6, 0.4)};
}

/// The colour each polygon of a placed cube is painted, by the way its face looks in plan
/// (Sweet Home's front, +z, is the plan's −y; its up, +y, the plan's +z).
void expect_cube_painted(const PlacedObject& o, const CubeColours& want) {
  ASSERT_EQ(o.mesh.triangles.size(), 12u);
  for (size_t t = 0; t < o.mesh.triangles.size(); ++t) {
    const auto& tr = o.mesh.triangles[t];
    const Vec3 a = o.mesh.vertices[size_t(tr[0])], b = o.mesh.vertices[size_t(tr[1])], c = o.mesh.vertices[size_t(tr[2])];
    const Vec3 n = cross(b - a, c - a);
    const std::array<double, 3>& expected = n.y < -1e-9 ? want.front : n.z > 1e-9 ? want.top : n.z < -1e-9 ? want.ghost : want.body;
    const std::array<double, 3> got = o.paint.of_polygon(o.mesh.polygon_of[t]).colour;
    for (size_t k = 0; k < 3; ++k) EXPECT_NEAR(got[k], expected[k], 1e-15) << o.name << ", triangle " << t << ", channel " << k;
  }
}

// A piece whose author coloured only parts of it is drawn in its model's own colours, part
// by part, as Sweet Home draws it: its OBJ's usemtl groups take their MTL's Kd, or their
// map_Kd image's mean; a piece's modelMaterials replace the model's material they name
// (by key where they have one, else by name), an opaque colour only (a transparent one, or
// none, leaves the model's own); the piece's color paints it whole. A zipped model finds its
// MTL and images inside its own zip. What cannot be read
// (a library, an image) is a warning naming the piece, never the home lost.
TEST(SweetHomeColours, FurnitureTakesItsModelsMaterialsAndThePiecesOverrides) {
  ScratchDir dir;
  dir.red_blue_png("tex.png");
  const std::string xml =
      "<home>\n" + kBox +
      "  <room name='Hall'><point x='10' y='10'/><point x='590' y='10'/><point x='590' y='390'/><point x='10' y='390'/></room>\n"
      "  <pieceOfFurniture name='Own' model='1/cube.obj' x='150' y='200' width='100' depth='100' height='100'/>\n"
      "  <pieceOfFurniture name='Override' model='1/cube.obj' x='400' y='200' width='100' depth='100' height='100'>\n"
      "    <material name='Front' color='FF4080C0'/>\n"
      "    <material name='Body' key='Other' color='FFFF00FF'/>\n"
      "    <material name='Body' color='00123456'/>\n"
      "    <material name='Anything' key='Top' color='FF00FF00'/>\n"
      "    <material name='Top' color='FFFF0000'/>\n"
      "    <material name='Ghost'/>\n"
      "  </pieceOfFurniture>\n"
      "  <pieceOfFurniture name='Whole' model='1/cube.obj' x='150' y='350' width='50' depth='50' height='50' color='FF0000FF'>\n"
      "    <material name='Front' color='FF4080C0'/>\n"
      "  </pieceOfFurniture>\n"
      "  <pieceOfFurniture name='Unlisted' model='2/cube.obj' x='450' y='350' width='50' depth='50' height='50'/>\n"
      "  <pieceOfFurniture name='Zipped' model='3!/cube.obj' x='300' y='350' width='50' depth='50' height='50'/>\n"
      "</home>\n";
  // A model of several files saved as a zip entry of its own: its MTL and image inside it.
  const std::string png = avenues::testing::slurp(dir.path() / "tex.png");
  const std::string zipped =
      avenues::testing::slurp(write_sh3d(dir, "zipped.zip", {{"cube.obj", kCubeObj}, {"cube.mtl", kCubeMtl}, {"tex.png", png}}));
  const std::string path = write_sh3d(dir, "cubes.sh3d",
                                      {{"Home.xml", xml},
                                       {"1/cube.obj", kCubeObj},
                                       {"1/cube.mtl", kCubeMtl},
                                       {"1/tex.png", png},
                                       {"2/cube.obj", kCubeObj},
                                       {"3", zipped}});
  const Plan p = read_sweet_home(path);
  auto warned = [&](const std::string& what) {
    int n = 0;
    for (const std::string& w : p.warnings) n += contains(w, what);
    return n;
  };
  // The model is read once: its missing image is said once, by the first piece that uses it.
  EXPECT_EQ(warned("(pieceOfFurniture 'Own'): model 1/cube.obj: material 'Ghost': its image -s 2 2 1 missing.png "
                   "(map_Kd) is not at hand: its Kd colour is used instead"),
            1);
  EXPECT_EQ(warned("(pieceOfFurniture 'Unlisted'): model 2/cube.obj: its material library 'cube.mtl' is not at hand"), 1);
  EXPECT_EQ(warned("4 material(s) that models use are defined in no MTL library at hand nor among Java 3D's built-in "
                   "materials ('Body', 'Front', 'Ghost', 'Top')"), 1);
  ASSERT_EQ(p.objects.size(), 5u);

  const CubeColours own = cube_colours_from_mtl();
  CubeColours overridden = own;
  overridden.front = {linear8(0x40), linear8(0x80), linear8(0xC0)};
  overridden.top = {0, 1, 0};
  const CellComplex c = build_cells(p);
  const std::vector<PlacedObject> placed = place_objects(c);
  ASSERT_EQ(placed.size(), 5u);
  expect_cube_painted(placed[0], own);
  expect_cube_painted(placed[4], own);
  expect_cube_painted(placed[1], overridden);
  // The piece's colour paints it whole, whatever its materials say.
  ASSERT_EQ(placed[2].paint.materials.size(), 1u);
  EXPECT_EQ(placed[2].paint.materials[0].colour, (std::array<double, 3>{0, 0, 1}));
  // A model whose library is not at hand keeps its materials' names, in the default colour.
  const std::array<double, 3> grey = Material().colour;
  expect_cube_painted(placed[3], {grey, grey, grey, grey});
  // The two pieces of one model and size but other materials are told apart.
  EXPECT_NE(mesh_key(p.objects[0]), mesh_key(p.objects[1]));
  EXPECT_NE(p.objects[1].model->path.find(", materials Front #4080C0, Top #00FF00"), std::string::npos)
      << p.objects[1].model->path;

  // Saved as cells and loaded, the pieces keep their materials.
  const std::string cells = (dir.path() / "cubes.cells").string();
  save_cells(c, cells);
  const std::vector<PlacedObject> reloaded = place_objects(load_cells(cells));
  ASSERT_EQ(reloaded.size(), 5u);
  expect_cube_painted(reloaded[1], overridden);

  // The picture shows them: each piece's front from the room, under the light at the eye.
  struct Look {
    double x;
    std::array<double, 3> colour;
    const char* what;
  };
  for (const Look& look : {Look{1.5, own.front, "Own's front (MTL Kd)"}, Look{4, overridden.front, "Override's front"}}) {
    const std::string out = (dir.path() / "piece.ppm").string();
    const std::string x = format_number(look.x);
    const auto [status, err] = run_avenues({"view", path, "--eye", x + ",-3.6,0.5", "--look", x + ",-2,0.5", "--fov", "20",
                                            "--size", "32x18", "--lights", "eye", "-o", out});
    ASSERT_EQ(status, 0) << err;
    expect_pixel_shows(read_image(out), look.colour, look.what);
  }
}

// --save-plan: furniture whose model came inside the home, and furniture that is a box,
// is written as OBJ and MTL files beside the TOML, so that the plan reopens with the same
// objects: as many, in the same places (bounds within 1e-6 m), in the same colours.
TEST(SweetHomeColours, SavedAsTomlThePiecesModelsAreWrittenBesideIt) {
  ScratchDir dir;
  dir.red_blue_png("tex.png");
  const std::string xml =
      "<home>\n" + kBox +
      "  <room name='Hall'><point x='10' y='10'/><point x='590' y='10'/><point x='590' y='390'/><point x='10' y='390'/></room>\n"
      "  <pieceOfFurniture name='Cube' model='1/cube.obj' x='150' y='200' width='100' depth='100' height='100'/>\n"
      "  <pieceOfFurniture name='Cube' model='1/cube.obj' x='150' y='320' width='60' depth='60' height='60' angle='0.5'/>\n"
      "  <pieceOfFurniture name='Override' model='1/cube.obj' x='400' y='200' width='100' depth='80' height='120'>\n"
      "    <material name='Front' color='FF4080C0'/>\n"
      "  </pieceOfFurniture>\n"
      "  <pieceOfFurniture name='Chest #1' x='450' y='330' width='40' depth='30' height='70' elevation='10'/>\n"
      "</home>\n";
  const std::string png = avenues::testing::slurp(dir.path() / "tex.png");
  const std::string home = write_sh3d(dir, "cubes.sh3d",
                                      {{"Home.xml", xml}, {"1/cube.obj", kCubeObj}, {"1/cube.mtl", kCubeMtl}, {"1/tex.png", png}});
  const Plan p = read_sweet_home(home);
  ASSERT_EQ(p.objects.size(), 4u);
  const std::string saved = (dir.path() / "saved.toml").string();
  write_plan(p, saved);
  // One OBJ per mesh (the two cubes of other sizes are two meshes), named from the first
  // piece that uses it, with its MTL when it has materials (the box has none); nothing left
  // over beside them.
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(dir.path() / "saved.models")) names.insert(e.path().filename().string());
  EXPECT_EQ(names, (std::set<std::string>{"chest-1.obj", "cube.obj", "cube.mtl", "cube-2.obj", "cube-2.mtl",
                                          "override.obj", "override.mtl"}));
  for (const auto& e : fs::directory_iterator(dir.path()))
    EXPECT_NE(e.path().filename().string().front(), '.') << "a temporary left: " << e.path();

  const Plan back = read_plan(saved);
  ASSERT_EQ(back.objects.size(), p.objects.size());
  const std::vector<PlacedObject> before = place_objects(build_cells(p));
  std::vector<std::string> warnings;
  const std::vector<PlacedObject> after = place_objects(build_cells(back), &warnings);
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  ASSERT_EQ(after.size(), before.size());
  for (size_t i = 0; i < before.size(); ++i) {
    const PlacedObject &a = before[i], &b = after[i];
    EXPECT_NEAR(length(b.bounds.lo - a.bounds.lo), 0, 1e-6) << a.name;
    EXPECT_NEAR(length(b.bounds.hi - a.bounds.hi), 0, 1e-6) << a.name;
    EXPECT_EQ(b.cell, a.cell) << a.name;
    ASSERT_EQ(b.mesh.triangles.size(), a.mesh.triangles.size()) << a.name;
    for (size_t t = 0; t < a.mesh.triangles.size(); ++t) {
      const auto ca = a.paint.of_polygon(a.mesh.polygon_of[t]).colour, cb = b.paint.of_polygon(b.mesh.polygon_of[t]).colour;
      for (size_t k = 0; k < 3; ++k) EXPECT_NEAR(cb[k], ca[k], 1e-12) << a.name << ", triangle " << t << ", channel " << k;
    }
  }
  // The cube's own materials come back by name, the piece's override in the saved MTL.
  expect_cube_painted(after[0], cube_colours_from_mtl());
  EXPECT_EQ(back.objects[1].name, "Cube 2") << "names are unique in a plan";

  // All or nothing: where the models' folder cannot be made, neither it nor the plan is written.
  const std::string blocked = (dir.path() / "blocked.toml").string();
  dir.write("blocked.models", "a file where the folder would be");
  EXPECT_THROW(write_plan(p, blocked), std::runtime_error);
  EXPECT_FALSE(fs::exists(blocked));
  EXPECT_TRUE(fs::is_regular_file(dir.path() / "blocked.models"));
  // Saved again over itself, the folder is replaced whole.
  write_plan(p, saved);
  EXPECT_EQ(read_plan(saved).objects.size(), p.objects.size());
}

/// A class as ObjectOutputStream describes it: its fields in stream order (type code,
/// name, and for an object field its JVM type), and its superclass.
struct JavaClass {
  std::string name;
  std::vector<std::tuple<char, std::string, std::string>> fields;
  const JavaClass* super = nullptr;
  int flags = 0x02;  // SC_SERIALIZABLE
};

/// Writes class descriptors and objects (never a back reference: every one is new).
struct JavaWriter {
  Bytes s;
  void desc(const JavaClass& c) {
    s.u8(0x72).utf(c.name).uid().u8(c.flags).u16(int(c.fields.size()));
    for (const auto& [code, name, type] : c.fields) {
      s.u8(code).utf(name);
      if (code == 'L' || code == '[') s.u8(0x74).utf(type);
    }
    s.u8(0x78);  // end of the class's annotation
    if (c.super) desc(*c.super);
    else s.u8(0x70);
  }
  void f32(float v) {
    uint32_t u;
    std::memcpy(&u, &v, 4);
    s.u32(u);
  }
  void string(const std::string& v) { s.u8(0x74).utf(v); }
  /// An ArrayList of the objects `write_each` writes (`count` of them).
  template <class F>
  void list(int count, F write_each) {
    s.u8(0x73).u8(0x72).utf("java.util.ArrayList").uid().u8(0x03).u16(1).u8('I').utf("size").u8(0x78).u8(0x70);
    s.u32(uint32_t(count));
    s.u8(0x77).u8(4).u32(uint32_t(count));
    for (int k = 0; k < count; ++k) write_each(k);
    s.u8(0x78);
  }
};

// Lights from a serialized Home (homes saved before Sweet Home 3D 5.3): a HomeLight's power
// and its LightSource[] give the same point lights as the same lights in Home.xml. No home
// from outside has one, so the stream is written here as ObjectOutputStream writes it.
TEST(SweetHomeSerialized, LightsAreTheSameFromEitherEntry) {
  const std::string m = "com.eteks.sweethome3d.model.";
  const JavaClass wall{m + "Wall",
                       {{'F', "thickness", ""}, {'F', "xEnd", ""}, {'F', "xStart", ""}, {'F', "yEnd", ""}, {'F', "yStart", ""}}};
  const JavaClass piece{m + "HomePieceOfFurniture",
                        {{'F', "angle", ""}, {'F', "depth", ""}, {'F', "elevation", ""}, {'F', "height", ""},
                         {'F', "width", ""}, {'F', "x", ""}, {'F', "y", ""}, {'L', "name", "Ljava/lang/String;"}}};
  const JavaClass light{m + "HomeLight", {{'F', "power", ""}, {'[', "lightSources", "[L" + m + "LightSource;"}}, &piece};
  const JavaClass source{m + "LightSource", {{'I', "color", ""}, {'F', "x", ""}, {'F', "y", ""}, {'F', "z", ""}}};
  const JavaClass sources{"[L" + m + "LightSource;", {}};
  const JavaClass home{m + "Home", {{'L', "furniture", "Ljava/util/List;"}, {'L', "walls", "Ljava/util/List;"}}};
  struct Src { float x, y, z; uint32_t colour; };
  struct Lamp { std::string name; float x, y, elevation, angle, width, depth, height, power; std::vector<Src> sources; };
  const std::vector<Lamp> lamps = {
      {"Pendant", 200, 200, 200, 0, 40, 40, 50, 0.5f, {{0.5f, 0.5f, 0.5f, 0x00FFFFFF}}},
      {"Spot", 100, 100, 100, 1.5707964f, 20, 10, 10, 0.25f, {{0, 0, 1, 0x00808080}, {1, 1, 0, 0xFFFF0000}}},
  };
  JavaWriter w;
  w.s.u8(0x73);
  w.desc(home);
  w.list(int(lamps.size()), [&](int k) {
    const Lamp& l = lamps[size_t(k)];
    w.s.u8(0x73);
    w.desc(light);
    for (float v : {l.angle, l.depth, l.elevation, l.height, l.width, l.x, l.y}) w.f32(v);  // HomePieceOfFurniture's
    w.string(l.name);
    w.f32(l.power);  // HomeLight's
    w.s.u8(0x75);
    w.desc(sources);
    w.s.u32(uint32_t(l.sources.size()));
    for (const Src& src : l.sources) {
      w.s.u8(0x73);
      w.desc(source);
      w.s.u32(src.colour);
      for (float v : {src.x, src.y, src.z}) w.f32(v);
    }
  });
  w.list(1, [&](int) {
    w.s.u8(0x73);
    w.desc(wall);
    for (float v : {10.0f, 500.0f, 0.0f, 0.0f, 0.0f}) w.f32(v);
  });

  std::string xml = "<home>\n  <wall id='w' xStart='0' yStart='0' xEnd='500' yEnd='0' thickness='10'/>\n";
  char buf[512];
  for (const Lamp& l : lamps) {
    std::snprintf(buf, sizeof buf,
                  "  <light name='%s' x='%g' y='%g' elevation='%g' angle='%.9g' width='%g' depth='%g' height='%g' "
                  "power='%g'>\n",
                  l.name.c_str(), l.x, l.y, l.elevation, l.angle, l.width, l.depth, l.height, l.power);
    xml += buf;
    for (const Src& src : l.sources) {
      std::snprintf(buf, sizeof buf, "    <lightSource x='%g' y='%g' z='%g' color='%08X'/>\n", src.x, src.y, src.z,
                    unsigned(src.colour));
      xml += buf;
    }
    xml += "  </light>\n";
  }
  xml += "</home>\n";
  ScratchDir dir;
  const Plan from_home = read_sweet_home(write_sh3d(dir, "serialized.sh3d", {{"Home", w.s.b}}));
  const Plan from_xml = read_sweet_home(write_sh3d(dir, "xml.sh3d", {{"Home.xml", xml}}));
  ASSERT_EQ(from_xml.lights.size(), 3u) << "Pendant, and Spot's two sources";
  ASSERT_EQ(from_home.lights.size(), from_xml.lights.size());
  for (size_t i = 0; i < from_xml.lights.size(); ++i) {
    const Light &a = from_home.lights[i], &b = from_xml.lights[i];
    SCOPED_TRACE(b.name);
    EXPECT_EQ(a.name, b.name);
    EXPECT_NEAR(length(a.position - b.position), 0, 1e-6);
    EXPECT_NEAR(a.intensity, b.intensity, 1e-9);
    for (size_t k = 0; k < 3; ++k) EXPECT_NEAR(a.colour[k], b.colour[k], 1e-9);
  }
  // Where Sweet Home puts them (as SweetHomeLights.LightPiecesBecomePointLightsWhereSweetHomePutsThem):
  // (200, 200) cm on screen is (2, −2) m in plan, the source halfway up the 50 cm piece.
  EXPECT_NEAR(length(from_home.lights[0].position - Vec3{2.0, -2.0, 2.25}), 0, 1e-6);
  EXPECT_NEAR(from_home.lights[0].intensity, 1.0, 1e-9);
  EXPECT_EQ(from_home.objects.size(), 2u) << "the lamps stay pieces of furniture";
}

// --save-plan of a real home reads back as it was read: the importer's leniency travels
// with it (two rooms labelling one space: Studio), two openings of one name in a wall are
// numbered (the Mezzanine house's 'Fixed window'), and walls Sweet Home joined are chained
// only while their centre line does not cross itself (casa). The same walls, rooms, cells,
// portals and objects come back.
TEST(SweetHomeSaved, RealHomesReadBackAsTheyWereRead) {
  SKIP_WITHOUT_OUTSIDE();
  std::vector<std::string> homes;
  for (const char* h : kOpenable) homes.push_back((kOutside / h).string());
  const fs::path examples = AVENUES_SH3D_EXAMPLES;
  for (const char* h : {"Studio.xml", "3BedroomHouseWithMezzanine.xml"})
    if (fs::exists(examples / h)) homes.push_back((examples / h).string());
  ScratchDir dir;
  for (const std::string& home : homes) {
    SCOPED_TRACE(home);
    const Plan p = read_sweet_home(home);
    const std::string saved = (dir.path() / (fs::path(home).stem().string() + ".toml")).string();
    write_plan(p, saved);
    Plan back;
    ASSERT_NO_THROW(back = read_plan(saved));
    EXPECT_TRUE(back.lenient);
    EXPECT_EQ(back.walls.size(), p.walls.size());
    EXPECT_EQ(back.rooms.size(), p.rooms.size());
    EXPECT_EQ(back.objects.size(), p.objects.size());
    const CellComplex a = build_cells(p), b = build_cells(back);
    EXPECT_EQ(b.rooms.size(), a.rooms.size());
    EXPECT_EQ(b.cells.size(), a.cells.size());
    EXPECT_EQ(b.portals.size(), a.portals.size());
  }
}

// Casa's pieces read from Home.xml and from the serialized Home are coloured alike, their
// modelMaterials (HomeMaterial objects in the serialized entry) included: its open-stringer
// staircase has a Tread of D3D3D3 and a Baluster and Handrail of transparent colour
// (their MTL's own stay).
TEST(SweetHomeColours, CasaPiecesHaveTheSameMaterialsFromBothEntries) {
  SKIP_WITHOUT_OUTSIDE();
  const Plan xml = read_sweet_home((kOutside / "casa-both-formats.sh3d").string(), HomeEntry::Xml);
  const Plan home = read_sweet_home((kOutside / "casa-both-formats.sh3d").string(), HomeEntry::Serialized);
  ASSERT_EQ(xml.objects.size(), home.objects.size());
  int coloured = 0;
  for (size_t i = 0; i < xml.objects.size(); ++i) {
    const Object& a = xml.objects[i];
    const Object& b = home.objects[i];
    SCOPED_TRACE(a.name);
    EXPECT_EQ(a.name, b.name);
    ASSERT_EQ(bool(a.model), bool(b.model));
    if (!a.model) continue;
    ASSERT_EQ(a.model->materials.size(), b.model->materials.size());
    EXPECT_EQ(a.model->material_of, b.model->material_of);
    bool any = false;
    for (size_t m = 0; m < a.model->materials.size(); ++m) {
      EXPECT_EQ(a.model->materials[m].name, b.model->materials[m].name);
      EXPECT_EQ(a.model->materials[m].colour, b.model->materials[m].colour) << a.model->materials[m].name;
      any |= a.model->materials[m].colour != Material().colour;
    }
    coloured += any;
    if (a.name != "Staircase with open stringer") continue;
    for (const Material& m : a.model->materials) {
      if (m.name == "Tread") {
        EXPECT_EQ(m.colour, (std::array<double, 3>{linear8(0xD3), linear8(0xD3), linear8(0xD3)}));
      } else if (m.name == "Baluster") {
        const double kd = linear_from_srgb(0.68);
        EXPECT_EQ(m.colour, (std::array<double, 3>{kd, kd, kd}));
      } else if (m.name == "Handrail") {
        EXPECT_NE(m.colour, Material().colour) << "its texture.png's mean";
      }
    }
  }
  EXPECT_EQ(coloured, int(xml.objects.size())) << "every piece of Casa has a model with an MTL";
  for (const std::string& w : xml.warnings) EXPECT_FALSE(contains(w, "material")) << w;
}

}  // namespace
}  // namespace avenues

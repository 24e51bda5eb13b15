// Tests of plans/formats/doom_map: Doom maps as plans. A hand-written WAD (bytes laid out here)
// shows the heights — a portal spans exactly the overlap of two sectors' heights, a
// sky sector has the sky above it, a closed door is solid — and each malformed input
// gives a PlanError naming the file and the lump or element. Then every map of Debian's
// Freedoom WADs decomposes into valid cells, and views of a few of them agree with the
// ray-casting oracle.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

#include "cells/build_cells.h"
#include "plans/formats/doom_map.h"
#include "ray_oracle.h"
#include "visibility/visible_set.h"

using namespace avenues;
using avenues::testing::check_visible_set;
using avenues::testing::OracleResult;

namespace {

// --- writing WADs -------------------------------------------------------------------

using Lump = std::pair<std::string, std::vector<uint8_t>>;

struct Bytes {
  std::vector<uint8_t> b;
  Bytes& u16(int v) {
    b.push_back(uint8_t(v & 0xFF));
    b.push_back(uint8_t((v >> 8) & 0xFF));
    return *this;
  }
  Bytes& u32(int64_t v) {
    for (int k = 0; k < 4; ++k) b.push_back(uint8_t((v >> (8 * k)) & 0xFF));
    return *this;
  }
  Bytes& u8(int v) {
    b.push_back(uint8_t(v));
    return *this;
  }
  Bytes& name8(const std::string& s) {
    for (size_t k = 0; k < 8; ++k) b.push_back(k < s.size() ? uint8_t(s[k]) : 0);
    return *this;
  }
};

/// Lays out a WAD: header, the lumps' bytes, then the directory.
std::vector<uint8_t> wad_bytes(const std::vector<Lump>& lumps, const std::string& magic = "PWAD") {
  Bytes data;
  std::vector<int64_t> offset;
  for (const Lump& l : lumps) {
    offset.push_back(12 + int64_t(data.b.size()));
    data.b.insert(data.b.end(), l.second.begin(), l.second.end());
  }
  Bytes out;
  for (char ch : magic) out.u8(ch);
  out.u32(int64_t(lumps.size())).u32(12 + int64_t(data.b.size()));
  out.b.insert(out.b.end(), data.b.begin(), data.b.end());
  for (size_t i = 0; i < lumps.size(); ++i) out.u32(offset[i]).u32(int64_t(lumps[i].second.size())).name8(lumps[i].first);
  return out.b;
}

/// A file in the temporary directory, removed at the end of the test.
class TempFile {
 public:
  explicit TempFile(const std::string& name)
      : path_((std::filesystem::temp_directory_path() /
               ("avenues_doom_" + std::to_string(::getpid()) + "_" + name))
                  .string()) {}
  ~TempFile() { std::filesystem::remove(path_); }
  const std::string& write(const std::vector<uint8_t>& bytes) const {
    std::ofstream(path_, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    return path_;
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

/// A tiny map, in map units (32 to the metre). Five sectors, x east, y north:
///
///   y 256 +------+
///         |  E   |  floor 24, ceiling 100
///   y 128 +------+------+----+------+
///         |  A   |  B   | C  |  D   |  A: 0..128; B: 32..192, sky; C: closed door (0..0); D: 0..128
///   y   0 +------+------+----+------+
///         x 0   128    256  320    448
///
/// Two-sided lines join A–E, A–B, B–C and C–D; the player starts in A facing north.
struct TinyMap {
  struct Linedef { int v1, v2, flags, front, back; };
  struct Sector { int floor, ceiling; std::string ceiling_flat; };
  std::vector<std::pair<int, int>> vertices{{0, 0},     {128, 0},   {256, 0}, {320, 0}, {448, 0},  {0, 128},
                                            {128, 128}, {256, 128}, {320, 128}, {448, 128}, {0, 256}, {128, 256}};
  std::vector<Sector> sectors{{0, 128, "CEIL1"}, {32, 192, "F_SKY1"}, {0, 0, "CEIL1"}, {0, 128, "CEIL1"}, {24, 100, "CEIL1"}};
  std::vector<int> sides;  ///< each sidedef's sector
  std::vector<Linedef> lines;
  struct Thing { int x, y, angle, type; };
  std::vector<Thing> things{{64, 64, 90, 1}, {300, 64, 0, 3001}};

  TinyMap() {
    auto one = [&](int a, int b, int s) {
      sides.push_back(s);
      lines.push_back({a, b, 0x0001, int(sides.size()) - 1, 0xFFFF});
    };
    auto two = [&](int a, int b, int front, int back) {
      sides.push_back(front);
      sides.push_back(back);
      lines.push_back({a, b, 0x0004, int(sides.size()) - 2, int(sides.size()) - 1});
    };
    const int A = 0, B = 1, C = 2, D = 3, E = 4;
    one(0, 5, A), one(1, 0, A);
    one(5, 10, E), one(10, 11, E), one(11, 6, E);
    one(2, 1, B), one(6, 7, B);
    one(3, 2, C), one(7, 8, C);
    one(4, 3, D), one(8, 9, D), one(9, 4, D);
    two(5, 6, A, E), two(6, 1, A, B), two(7, 2, B, C), two(8, 3, C, D);
  }

  /// The map's lumps after its marker, in Doom's binary format or Hexen's.
  std::vector<Lump> lumps(const std::string& marker, bool hexen = false) const {
    Bytes th, ld, sd, vx, sc;
    for (const Thing& t : things) {
      if (hexen) th.u16(0).u16(t.x).u16(t.y).u16(0).u16(t.angle).u16(t.type).u16(7).u8(0).u8(0).u8(0).u8(0).u8(0).u8(0);
      else th.u16(t.x).u16(t.y).u16(t.angle).u16(t.type).u16(7);
    }
    for (const Linedef& l : lines) {
      ld.u16(l.v1).u16(l.v2).u16(l.flags);
      if (hexen) ld.u8(0).u8(0).u8(0).u8(0).u8(0).u8(0);
      else ld.u16(0).u16(0);
      ld.u16(l.front).u16(l.back);
    }
    for (int s : sides) sd.u16(0).u16(0).name8("-").name8("-").name8("STARTAN3").u16(s);
    for (auto [x, y] : vertices) vx.u16(x).u16(y);
    for (const Sector& s : sectors) sc.u16(s.floor).u16(s.ceiling).name8("FLOOR4_8").name8(s.ceiling_flat).u16(160).u16(0).u16(0);
    std::vector<Lump> out{{marker, {}}, {"THINGS", th.b}, {"LINEDEFS", ld.b}, {"SIDEDEFS", sd.b}, {"VERTEXES", vx.b},
                          {"SEGS", {}},  {"SSECTORS", {}}, {"NODES", {}},       {"SECTORS", sc.b},  {"REJECT", {}},
                          {"BLOCKMAP", {}}};
    if (hexen) out.push_back({"BEHAVIOR", std::vector<uint8_t>(16, 0)});
    return out;
  }
};

std::vector<Lump> operator+(std::vector<Lump> a, const std::vector<Lump>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

/// The message of the PlanError `f` throws ("" if it throws none).
template <class F>
std::string plan_error(F f) {
  try {
    f();
  } catch (const PlanError& e) {
    return e.what();
  }
  return "";
}

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

/// The [z0, z1] range of the portals joining a cell of room a to a cell of room b.
std::pair<double, double> portal_heights(const CellComplex& c, RoomId a, RoomId b) {
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (const Portal& p : c.portals) {
    const RoomId r0 = c.cells[size_t(p.cell[0])].room, r1 = c.cells[size_t(p.cell[1])].room;
    if (!((r0 == a && r1 == b) || (r0 == b && r1 == a))) continue;
    for (const Vec3& v : p.poly) lo = std::min(lo, v.z), hi = std::max(hi, v.z);
  }
  return {lo, hi};
}

bool is_cell_of_room(const CellComplex& c, Vec3 p, RoomId room) {
  const Location l = c.locate(p);
  return l.what == Location::What::Cell && c.cells[size_t(l.cell)].kind == CellKind::Room &&
         c.cells[size_t(l.cell)].room == room;
}

}  // namespace

// --- the tiny map --------------------------------------------------------------------

TEST(DoomMap, TwoSectorsOfDifferentHeightsSeeEachOtherOverTheOverlapOfTheirHeights) {
  TempFile f("heights.wad");
  const std::string& wad = f.write(wad_bytes(TinyMap().lumps("MAP01")));
  const Plan plan = read_doom_map(wad, "MAP01");
  EXPECT_TRUE(plan.warnings.empty()) << plan.warnings.front();
  ASSERT_EQ(plan.storeys.size(), 1u);
  EXPECT_DOUBLE_EQ(plan.storeys[0].elevation, 0);
  EXPECT_DOUBLE_EQ(plan.storeys[0].height, 192.0 / 32);  // lowest floor 0 to highest ceiling 192
  ASSERT_EQ(plan.rooms.size(), 5u);
  EXPECT_EQ(plan.rooms[4].name, "sector 4");
  EXPECT_FALSE(plan.rooms[4].label.has_value());
  EXPECT_DOUBLE_EQ(plan.rooms[4].floor_at, 24.0 / 32);
  EXPECT_DOUBLE_EQ(plan.rooms[4].ceiling_at, 100.0 / 32);
  EXPECT_TRUE(plan.rooms[1].sky);
  EXPECT_EQ(plan.walls.size(), 16u);

  const CellComplex c = build_cells(plan);
  EXPECT_EQ(cells_are_valid(c), "");
  EXPECT_TRUE(c.warnings.empty()) << c.warnings.front();
  // A (floor 0, ceiling 128) and E (24, 100): the portal is E's span, 0.75 m to 3.125 m.
  auto [lo, hi] = portal_heights(c, 0, 4);
  EXPECT_NEAR(lo, 24.0 / 32, 1e-9);
  EXPECT_NEAR(hi, 100.0 / 32, 1e-9);
  // A (0, 128) and the sky sector B (32, up to the sky): 1 m to 4 m.
  std::tie(lo, hi) = portal_heights(c, 0, 1);
  EXPECT_NEAR(lo, 32.0 / 32, 1e-9);
  EXPECT_NEAR(hi, 128.0 / 32, 1e-9);
  // Each sector's space is its own, between its floor and ceiling.
  EXPECT_TRUE(is_cell_of_room(c, {2, 6, 2}, 4));
  EXPECT_FALSE(is_cell_of_room(c, {2, 6, 0.5}, 4));  // under E's raised floor: solid
  EXPECT_TRUE(is_cell_of_room(c, {6, 2, 5.5}, 1));   // the sky sector is free to the storey's top
  // The sky above B, not above A.
  const Location above_b = c.locate({6, 2, 6.5});
  ASSERT_EQ(above_b.what, Location::What::Cell);
  EXPECT_EQ(c.cells[size_t(above_b.cell)].kind, CellKind::Sky);
  EXPECT_NE(c.locate({2, 2, 6.5}).what, Location::What::Cell);
  EXPECT_NE(c.locate({2, 2, 4.5}).what, Location::What::Cell);
  // The closed door C gives no cell, and so nothing joins B to D.
  EXPECT_NE(c.locate({9, 2, 0.5}).what, Location::What::Cell);
  for (const Cell& cell : c.cells) EXPECT_NE(cell.room, 2);
  EXPECT_TRUE(is_cell_of_room(c, {12, 2, 2}, 3));
  EXPECT_EQ(portal_heights(c, 1, 3).first, HUGE_VAL);
  // The player's eye: 41 units above A's floor, looking north.
  ASSERT_TRUE(plan.view.has_value());
  EXPECT_NEAR(plan.view->eye.x, 2, 1e-12);
  EXPECT_NEAR(plan.view->eye.y, 2, 1e-12);
  EXPECT_NEAR(plan.view->eye.z, 41.0 / 32, 1e-12);
  EXPECT_NEAR(plan.view->look.y - plan.view->eye.y, 1, 1e-12);
  EXPECT_NEAR(plan.view->look.x - plan.view->eye.x, 0, 1e-12);
  EXPECT_TRUE(is_cell_of_room(c, plan.view->eye, 0));
}

TEST(DoomMap, AClosedDoorUnderTheSkyIsSolidToo) {
  TinyMap m;
  m.sectors[2].ceiling_flat = "F_SKY1";
  TempFile f("sky_door.wad");
  const Plan plan = read_doom_map(f.write(wad_bytes(m.lumps("MAP01"))), "MAP01");
  const CellComplex c = build_cells(plan);
  EXPECT_EQ(cells_are_valid(c), "");
  for (double z : {0.5, 3.0, 5.5}) EXPECT_NE(c.locate({9, 2, z}).what, Location::What::Cell) << z;
  EXPECT_EQ(portal_heights(c, 1, 3).first, HUGE_VAL);
}

TEST(DoomMap, PlayerStartInARaisedSectorStandsOnItsFloor) {
  TinyMap m;
  m.things[0] = {64, 192, 180, 1};  // in E (floor 24), facing west
  TempFile f("start.wad");
  const Plan plan = read_doom_map(f.write(wad_bytes(m.lumps("MAP01"))), "MAP01");
  ASSERT_TRUE(plan.view.has_value());
  EXPECT_NEAR(plan.view->eye.z, (24.0 + 41) / 32, 1e-12);
  EXPECT_NEAR(plan.view->look.x - plan.view->eye.x, -1, 1e-12);
}

TEST(DoomMap, HexenMapsReadLikeDoomMaps) {
  TempFile f("hexen.wad");
  const std::string& wad = f.write(wad_bytes(TinyMap().lumps("MAP01", true)));
  const Plan hexen = read_doom_map(wad, "MAP01");
  TempFile g("doom.wad");
  const Plan doom = read_doom_map(g.write(wad_bytes(TinyMap().lumps("MAP01"))), "MAP01");
  EXPECT_EQ(hexen.walls.size(), doom.walls.size());
  EXPECT_EQ(hexen.rooms.size(), doom.rooms.size());
  ASSERT_TRUE(hexen.view.has_value());
  EXPECT_NEAR(hexen.view->eye.z, doom.view->eye.z, 1e-12);
  EXPECT_EQ(build_cells(hexen).cells.size(), build_cells(doom).cells.size());
}

TEST(DoomMap, MapNamesAreListedInDirectoryOrder) {
  TempFile f("names.wad");
  const std::string& wad = f.write(wad_bytes(TinyMap().lumps("MAP02") + TinyMap().lumps("MAP01") +
                                             std::vector<Lump>{{"PLAYPAL", std::vector<uint8_t>(768, 0)}}));
  EXPECT_EQ(doom_map_names(wad), (std::vector<std::string>{"MAP02", "MAP01"}));
  EXPECT_EQ(read_doom_map(wad, "map01").walls.size(), 16u);  // names are matched in upper case
}

// --- repairs: warnings naming the element ---------------------------------------------

TEST(DoomMap, RepairableErrorsAreWarningsNamingTheElement) {
  TinyMap m;
  m.lines[11] = {4, 9, 0x0001, 0xFFFF, 11};  // D's east side, given as a back side only: flipped
  m.lines[1].flags |= 0x0004;                // A's south side, flagged two-sided with no back side
  const int first_extra = int(m.lines.size());
  m.lines.push_back({0, 999, 0x0001, 0, 0xFFFF});         // vertex out of range: dropped
  m.lines.push_back({1, 1, 0x0001, 0, 0xFFFF});           // zero length: dropped
  m.lines.push_back({0, 5, 0x0001, 500, 0xFFFF});         // sidedef out of range, no other: dropped
  m.sides.push_back(77);                                   // a sidedef naming no sector ...
  m.lines.push_back({10, 11, 0x0001, int(m.sides.size()) - 1, 0xFFFF});  // ... leaves its line no side
  TempFile f("repairs.wad");
  const std::string& wad = f.write(wad_bytes(m.lumps("MAP01")));
  const Plan plan = read_doom_map(wad, "MAP01");
  const std::string where = wad + ":MAP01 (";
  auto warned = [&](const std::string& element, const std::string& what) {
    for (const std::string& w : plan.warnings)
      if (has(w, where + element + "): ") && has(w, what)) return true;
    return false;
  };
  auto extra = [&](int k) { return "linedef " + std::to_string(first_extra + k); };
  EXPECT_TRUE(warned("linedef 11", "only a back side"));
  EXPECT_TRUE(warned("linedef 1", "two-sided"));
  EXPECT_TRUE(warned(extra(0), "vertex 999 out of range"));
  EXPECT_TRUE(warned(extra(1), "zero length"));
  EXPECT_TRUE(warned(extra(2), "sidedef 500 out of range"));
  EXPECT_TRUE(warned("sidedef " + std::to_string(m.sides.size() - 1), "sector 77, out of range"));
  EXPECT_TRUE(warned(extra(3), "no usable side"));
  EXPECT_EQ(plan.warnings.size(), 8u) << plan.warnings.front();  // extra(2) also has no usable side
  // The flipped line has its only side on the right, walking (448,128) -> (448,0).
  const auto flipped = std::find_if(plan.walls.begin(), plan.walls.end(), [&](const Wall& w) { return w.name == "linedef 11"; });
  ASSERT_NE(flipped, plan.walls.end());
  EXPECT_EQ(flipped->right_room, 3);
  EXPECT_EQ(flipped->left_room, -1);
  EXPECT_NEAR(flipped->centre[0].y, 4, 1e-12);
  EXPECT_EQ(plan.walls.size(), 16u);
  // The map still decomposes, as if nothing had been wrong.
  const CellComplex c = build_cells(plan);
  EXPECT_EQ(cells_are_valid(c), "");
  TempFile g("clean.wad");
  EXPECT_EQ(c.cells.size(), build_cells(read_doom_map(g.write(wad_bytes(TinyMap().lumps("MAP01"))), "MAP01")).cells.size());
}

TEST(DoomMap, ASectorOfNoAreaBetweenTwoCoincidentLinesIsMergedAway) {
  // Between A and E, sector 5 drawn as two lines on the same two points (as in
  // freedoom1.wad:E3M6, sector 110): A | 5 | E, with no room for 5.
  TinyMap m;
  m.sectors.push_back({0, 64, "CEIL1"});
  m.sides.push_back(5);
  m.sides.push_back(4);
  m.lines[12].back = int(m.sides.size()) - 2;  // 5 -> 6: A on the right, 5 on the left
  m.lines.push_back({6, 5, 0x0004, int(m.sides.size()) - 1, int(m.sides.size()) - 2});  // 6 -> 5: E on the right, 5 on the left
  TempFile f("sliver.wad");
  const Plan plan = read_doom_map(f.write(wad_bytes(m.lumps("MAP01"))), "MAP01");
  ASSERT_EQ(plan.warnings.size(), 1u);
  EXPECT_TRUE(has(plan.warnings[0], ":MAP01 (linedef 12): coincides with linedef 16: merged (sector 5 between them has no area)"))
      << plan.warnings[0];
  EXPECT_EQ(plan.walls.size(), 16u);
  const CellComplex c = build_cells(plan);
  EXPECT_EQ(cells_are_valid(c), "");
  // A sees E as if sector 5 were not there.
  auto [lo, hi] = portal_heights(c, 0, 4);
  EXPECT_NEAR(lo, 24.0 / 32, 1e-9);
  EXPECT_NEAR(hi, 100.0 / 32, 1e-9);
}

// --- what cannot be read: PlanErrors naming the file and the lump ---------------------

TEST(DoomMap, NotAWadIsAnErrorNamingTheFile) {
  TempFile f("text.wad");
  std::string text = "this is not a WAD file\n";
  const std::string& path = f.write(std::vector<uint8_t>(text.begin(), text.end()));
  const std::string e = plan_error([&] { read_doom_map(path, "MAP01"); });
  EXPECT_TRUE(has(e, path) && has(e, "not a WAD")) << e;
  EXPECT_TRUE(has(plan_error([&] { doom_map_names(path); }), "not a WAD"));
  EXPECT_TRUE(has(plan_error([&] { doom_map_names(path + ".missing"); }), "cannot open")) << path;
}

TEST(DoomMap, TruncatedDirectoryIsAnErrorNamingTheFile) {
  std::vector<uint8_t> bytes = wad_bytes(TinyMap().lumps("MAP01"));
  bytes.resize(bytes.size() - 20);  // the directory is at the end
  TempFile f("truncated.wad");
  const std::string& path = f.write(bytes);
  const std::string e = plan_error([&] { read_doom_map(path, "MAP01"); });
  EXPECT_TRUE(has(e, path) && has(e, "directory") && has(e, "beyond the end")) << e;
}

TEST(DoomMap, TruncatedLinedefsLumpIsAnErrorNamingTheLump) {
  std::vector<Lump> lumps = TinyMap().lumps("MAP01");
  lumps[2].second.resize(lumps[2].second.size() - 5);
  ASSERT_EQ(lumps[2].first, "LINEDEFS");
  TempFile f("linedefs.wad");
  const std::string& path = f.write(wad_bytes(lumps));
  const std::string e = plan_error([&] { read_doom_map(path, "MAP01"); });
  EXPECT_TRUE(has(e, path + ":MAP01 (lump LINEDEFS)") && has(e, "14-byte")) << e;
}

TEST(DoomMap, LumpBeyondTheEndOfTheFileIsAnErrorNamingTheLump) {
  std::vector<uint8_t> bytes = wad_bytes(TinyMap().lumps("MAP01"));
  // Directory entry 8 is SECTORS: make its size run past the end of the file.
  const size_t dir = size_t(bytes[8] | bytes[9] << 8 | bytes[10] << 16 | bytes[11] << 24);
  ASSERT_EQ(std::string(bytes.begin() + long(dir + 16 * 8 + 8), bytes.begin() + long(dir + 16 * 8 + 15)), "SECTORS");
  bytes[dir + 16 * 8 + 6] = 0x10;  // size += 1 MiB
  TempFile f("beyond.wad");
  const std::string& path = f.write(bytes);
  const std::string e = plan_error([&] { read_doom_map(path, "MAP01"); });
  EXPECT_TRUE(has(e, path + ":MAP01 (lump SECTORS)") && has(e, "beyond the end")) << e;
}

TEST(DoomMap, MissingMapIsAnErrorListingTheMapsTheFileHas) {
  TempFile f("two_maps.wad");
  const std::string& path = f.write(wad_bytes(TinyMap().lumps("MAP01") + TinyMap().lumps("MAP02")));
  const std::string e = plan_error([&] { read_doom_map(path, "MAP07"); });
  EXPECT_TRUE(has(e, path) && has(e, "MAP07") && has(e, "MAP01, MAP02")) << e;
}

TEST(DoomMap, MissingRequiredLumpIsAnErrorNamingIt) {
  std::vector<Lump> lumps = TinyMap().lumps("MAP01");
  lumps.erase(lumps.begin() + 8);  // SECTORS
  TempFile f("no_sectors.wad");
  const std::string& path = f.write(wad_bytes(lumps));
  const std::string e = plan_error([&] { read_doom_map(path, "MAP01"); });
  EXPECT_TRUE(has(e, path + ":MAP01 (lump SECTORS)") && has(e, "no SECTORS lump")) << e;
}

TEST(DoomMap, UdmfMapIsAnErrorSayingSo) {
  const std::string text = "namespace = \"zdoom\";\nvertex { x = 0.0; y = 0.0; }\n";
  TempFile f("udmf.wad");
  const std::string& path =
      f.write(wad_bytes({{"MAP01", {}}, {"TEXTMAP", std::vector<uint8_t>(text.begin(), text.end())}, {"ENDMAP", {}}}));
  EXPECT_EQ(doom_map_names(path), std::vector<std::string>{"MAP01"});
  const std::string e = plan_error([&] { read_doom_map(path, "MAP01"); });
  EXPECT_TRUE(has(e, path + ":MAP01 (lump TEXTMAP)") && has(e, "UDMF")) << e;
}

// --- Freedoom ------------------------------------------------------------------------

namespace {

std::string freedoom(const std::string& name) { return std::string(AVENUES_FREEDOOM_DIR) + "/" + name; }

/// Every map of one WAD: read, decomposed, valid; the player's eye in a cell of its sector.
void every_map_decomposes(const std::string& wad) {
  const std::vector<std::string> maps = doom_map_names(wad);
  ASSERT_FALSE(maps.empty());
  double slowest = 0;
  std::string slowest_map;
  for (const std::string& m : maps) {
    SCOPED_TRACE(wad + ":" + m);
    const auto t0 = std::chrono::steady_clock::now();
    const Plan plan = read_doom_map(wad, m);
    const CellComplex c = build_cells(plan);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (seconds > slowest) slowest = seconds, slowest_map = m;
    EXPECT_EQ(cells_are_valid(c), "");
    EXPECT_GT(c.cells.size(), plan.rooms.size() / 2);
    EXPECT_GT(c.portals.size(), c.cells.size() / 2);
    // Warnings: one line each, naming an element of the map.
    for (const std::string& w : c.warnings) {
      EXPECT_EQ(w.find('\n'), std::string::npos) << w;
      EXPECT_TRUE(has(w, "sector ") || has(w, "linedef ") || has(w, "sidedef ") || has(w, "thing ") || has(w, "lump "))
          << w;
    }
    ASSERT_TRUE(plan.view.has_value());
    const Location eye = c.locate(plan.view->eye);
    EXPECT_EQ(eye.what, Location::What::Cell) << eye.solid;
  }
  // Speed is a benchmark's matter (bench/doom_vs_zdbsp.sh, docs/PERFORMANCE.md), not a
  // timed assertion that fails on a busy machine: the slowest map is only reported.
  std::printf("[ info ] %s: %zu maps, slowest %s %.2f s\n", wad.c_str(), maps.size(), slowest_map.c_str(), slowest);
}

}  // namespace

TEST(DoomMapFreedoom, EveryMapOfFreedoom1DecomposesIntoValidCells) {
  const std::string wad = freedoom("freedoom1.wad");
  if (!std::filesystem::exists(wad)) GTEST_SKIP() << wad << " is missing (apt-get install freedoom)";
  every_map_decomposes(wad);
}

TEST(DoomMapFreedoom, EveryMapOfFreedoom2DecomposesIntoValidCells) {
  const std::string wad = freedoom("freedoom2.wad");
  if (!std::filesystem::exists(wad)) GTEST_SKIP() << wad << " is missing (apt-get install freedoom)";
  every_map_decomposes(wad);
}

TEST(DoomMapFreedoom, ViewsOfFreedoomMapsAgreeWithRayCasting) {
  const std::vector<std::pair<std::string, std::string>> maps{
      {"freedoom1.wad", "E1M1"}, {"freedoom2.wad", "MAP01"}, {"freedoom2.wad", "MAP07"}, {"freedoom2.wad", "MAP30"}};
  std::mt19937 rng(1993);
  for (const auto& [file, m] : maps) {
    const std::string wad = freedoom(file);
    if (!std::filesystem::exists(wad)) GTEST_SKIP() << wad << " is missing (apt-get install freedoom)";
    SCOPED_TRACE(file + ":" + m);
    const Plan plan = read_doom_map(wad, m);
    const CellComplex c = build_cells(plan);
    // The player's view, then random eyes in random sector cells looking anywhere.
    std::vector<Camera> cams{Camera::look_at(plan.view->eye, plan.view->look, plan.view->fov_deg, 48, 32)};
    std::vector<CellId> rooms;
    for (CellId k = 0; k < CellId(c.cells.size()); ++k)
      if (c.cells[size_t(k)].kind == CellKind::Room) rooms.push_back(k);
    std::uniform_int_distribution<size_t> pick(0, rooms.size() - 1);
    std::uniform_real_distribution<double> u(0.05, 0.95), yaw(0, 360), pitch(-40, 40), fov(60, 110);
    for (int v = 0; v < 4; ++v) {
      const Cell& k = c.cells[size_t(rooms[pick(rng)])];
      std::vector<double> w(k.footprint.size());
      double sum = 0;
      for (double& x : w) sum += (x = u(rng));
      Vec2 p{0, 0};
      for (size_t i = 0; i < w.size(); ++i) p = p + (w[i] / sum) * k.footprint[i];
      cams.push_back(Camera::yaw_pitch({p.x, p.y, k.z0 + u(rng) * (k.z1 - k.z0)}, yaw(rng), pitch(rng), fov(rng), 48, 32));
    }
    int seeing_beyond = 0;  // views that see past their own cell
    for (size_t v = 0; v < cams.size(); ++v) {
      const Camera& cam = cams[v];
      SCOPED_TRACE("view " + std::to_string(v) + ": eye " + std::to_string(cam.eye.x) + "," +
                   std::to_string(cam.eye.y) + "," + std::to_string(cam.eye.z));
      const Location at = c.locate(cam.eye);
      ASSERT_EQ(at.what, Location::What::Cell);
      const VisibleSet vs = find_visible(c, cam, at.cell, Kernel::Double);
      seeing_beyond += vs.cells.size() > 1;
      const OracleResult r = check_visible_set(c, cam, vs, 1);
      EXPECT_EQ(r.missing, 0);
      EXPECT_EQ(r.extra, 0);
      EXPECT_EQ(find_visible(c, cam, at.cell, Kernel::Exact).cells, vs.cells);
    }
    EXPECT_GT(seeing_beyond, 0);
  }
}

// Avenues — meshes through Assimp (plans/assimp_reader.h) and IFC buildings
// (plans/formats/ifc_building.h): the right way up, in metres, bad files refused clearly.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "cells/build_cells.h"
#include "plans/assimp_reader.h"
#include "plans/formats/ifc_building.h"
#include "plans/mesh.h"
#include "ray_oracle.h"
#include "tests/test_files.h"
#include "visibility/camera.h"
#include "visibility/visible_set.h"

namespace fs = std::filesystem;
using namespace avenues;

namespace {

const fs::path kModels = "/usr/share/assimp/models";
const fs::path kIfc = fs::path(AVENUES_OUTSIDE_DIR) / "ifc";

Box3 bounds(const Mesh& m) {
  Box3 b;
  for (Vec3 v : m.vertices) b.add(v);
  return b;
}

/// The area-weighted normal of the triangles lying flat at the mesh's lowest height, facing up
/// or down, and their area: a floor plate's upper face has normal +z.
Vec3 normal_of_triangles_at(const Mesh& m, double z, double tol, double& area) {
  Vec3 sum;
  area = 0;
  for (const auto& t : m.triangles) {
    const Vec3 a = m.vertices[size_t(t[0])], b = m.vertices[size_t(t[1])], c = m.vertices[size_t(t[2])];
    if (std::fabs(a.z - z) > tol || std::fabs(b.z - z) > tol || std::fabs(c.z - z) > tol) continue;
    const Vec3 n = cross(b - a, c - a);
    sum = sum + 0.5 * n;
    area += 0.5 * length(n);
  }
  return sum;
}

std::string base64(const std::string& bytes) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = (unsigned char)bytes[i] << 16 | (unsigned char)bytes[i + 1] << 8 | (unsigned char)bytes[i + 2];
    out += {k[v >> 18], k[(v >> 12) & 63], k[(v >> 6) & 63], k[v & 63]};
  }
  if (i + 1 == bytes.size()) {
    const unsigned v = (unsigned char)bytes[i] << 16;
    out += {k[v >> 18], k[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == bytes.size()) {
    const unsigned v = (unsigned char)bytes[i] << 16 | (unsigned char)bytes[i + 1] << 8;
    out += {k[v >> 18], k[(v >> 12) & 63], k[(v >> 6) & 63], '='};
  }
  return out;
}

/// A 4 m square floor in the file's own axes: at height 0 of its up axis, its top face
/// (counter-clockwise from above) facing up. Y-up: the floor spans x and -z.
struct Floor {
  std::vector<std::array<float, 3>> v{{-2, 0, 2}, {2, 0, 2}, {2, 0, -2}, {-2, 0, -2}};  // Y-up, counter-clockwise from +y
  std::vector<int> tri{0, 1, 2, 0, 2, 3};
};

std::string gltf_floor() {
  const Floor f;
  std::string bin;
  for (const auto& p : f.v) bin.append(reinterpret_cast<const char*>(p.data()), 12);
  for (int i : f.tri) {
    const uint16_t s = uint16_t(i);
    bin.append(reinterpret_cast<const char*>(&s), 2);
  }
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1,"material":0}]}],
"materials":[{"pbrMetallicRoughness":{"baseColorFactor":[0.5,0.25,0.125,1]}}],
"buffers":[{"byteLength":60,"uri":"data:application/octet-stream;base64,)" +
         base64(bin) + R"("}],
"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":12}],
"accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[-2,0,-2],"max":[2,0,2]},
{"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"}]})";
}

/// The same floor in COLLADA, in the given up axis and unit (in centimetres: 400 units).
std::string collada_floor(bool z_up) {
  const std::string pts = z_up ? "-200 -200 0  200 -200 0  200 200 0  -200 200 0" : "-200 0 200  200 0 200  200 0 -200  -200 0 -200";
  return R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
<asset><unit name="centimeter" meter="0.01"/><up_axis>)" +
         std::string(z_up ? "Z_UP" : "Y_UP") + R"(</up_axis></asset>
<library_geometries><geometry id="floor"><mesh>
<source id="p"><float_array id="pa" count="12">)" +
         pts + R"(</float_array><technique_common><accessor source="#pa" count="4" stride="3">
<param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>
<vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
<triangles count="2"><input semantic="VERTEX" source="#v" offset="0"/><p>0 1 2 0 2 3</p></triangles>
</mesh></geometry></library_geometries>
<library_visual_scenes><visual_scene id="s"><node id="n"><instance_geometry url="#floor"/></node></visual_scene></library_visual_scenes>
<scene><instance_visual_scene url="#s"/></scene></COLLADA>
)";
}

class AssimpFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("avenues-assimp-" + std::to_string(::getpid()) + "-" + info->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return (dir_ / name).string();
  }
  fs::path dir_;
};

void expect_floor_up(const Mesh& m, double side) {
  const Box3 b = bounds(m);
  EXPECT_NEAR(b.hi.x - b.lo.x, side, 1e-4);
  EXPECT_NEAR(b.hi.y - b.lo.y, side, 1e-4);
  EXPECT_NEAR(b.hi.z - b.lo.z, 0, 1e-6);
  double area = 0;
  const Vec3 n = normal_of_triangles_at(m, b.lo.z, 1e-6, area);
  EXPECT_NEAR(area, side * side, 1e-3);
  EXPECT_GT(n.z, 0.99 * area) << "the floor faces up (+z)";
}

}  // namespace

TEST_F(AssimpFiles, GltfFloorIsYUpMetresTurnedToZUp) {
  const Mesh m = load_mesh(write("floor.gltf", gltf_floor()));
  expect_floor_up(m, 4);
}

TEST_F(AssimpFiles, ColladaFloorKeepsItsUpAxisAndUnitEitherWay) {
  expect_floor_up(load_mesh(write("y.dae", collada_floor(false))), 4);
  expect_floor_up(load_mesh(write("z.dae", collada_floor(true))), 4);
}

TEST_F(AssimpFiles, YUpObjStandsUpWithUpY) {
  const std::string obj = write("floor.obj", "v -2 0 2\nv 2 0 2\nv 2 0 -2\nv -2 0 -2\nf 1 2 3 4\n");
  MeshAxes y_up;
  y_up.up = 'y';
  y_up.metres_per_unit = 0.5;
  expect_floor_up(load_mesh(obj, y_up), 2);
  // Without --up, an OBJ is z up as OpenMesh has always read it: the floor stands on its side.
  const Box3 b = bounds(load_mesh(obj));
  EXPECT_NEAR(b.hi.z - b.lo.z, 4, 1e-9);
}

TEST_F(AssimpFiles, DeclaredAxesWinOverTheOptionWithAWarning) {
  MeshAxes x_up;
  x_up.up = 'x';
  std::vector<std::string> warnings;
  expect_floor_up(load_assimp_mesh(write("floor.gltf", gltf_floor()), x_up, &warnings), 4);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("ignored"), std::string::npos) << warnings[0];
}

TEST_F(AssimpFiles, MaterialColourIsKeptOnTheNode) {
  const ImportedScene s = import_scene(write("floor.gltf", gltf_floor()));
  bool found = false;
  for (const ImportedNode& n : s.nodes)
    if (!n.triangles.empty()) {
      EXPECT_TRUE(n.coloured);
      EXPECT_NEAR(n.colour[0], 0.5, 1e-6);
      EXPECT_NEAR(n.colour[1], 0.25, 1e-6);
      found = true;
    }
  EXPECT_TRUE(found);
}

TEST(AssimpModels, TestModelsStandOnTheirFeet) {
  if (!fs::exists(kModels / "Collada/duck.dae")) GTEST_SKIP() << "assimp-testmodels not installed (.ci/install-deps)";
  // The COLLADA duck (Y_UP, centimetres) is 1.54 m tall and stands just above the ground.
  const Box3 duck = bounds(load_mesh((kModels / "Collada/duck.dae").string()));
  EXPECT_NEAR(duck.hi.z - duck.lo.z, 1.5404, 1e-3);
  EXPECT_NEAR(duck.lo.z, 0.0993, 1e-3);
  // A Z_UP COLLADA (3ds Max, centimetres): the teapots stand on z = 0, 0.49 m tall.
  const Box3 teapots = bounds(load_mesh((kModels / "Collada/teapots.DAE").string()));
  EXPECT_NEAR(teapots.lo.z, 0, 1e-3);
  EXPECT_NEAR(teapots.hi.z, 0.4932, 1e-3);
  // Wuson, an OBJ exported Y-up: read with up y, its feet are at z = 0, its head 1.5 m up.
  MeshAxes y_up;
  y_up.up = 'y';
  const Box3 wuson = bounds(load_mesh((kModels / "OBJ/WusonOBJ.obj").string(), y_up));
  EXPECT_NEAR(wuson.lo.z, 0, 1e-3);
  EXPECT_NEAR(wuson.hi.z, 1.515, 1e-3);
  // The glTF box, with its root's own turn: a unit cube centred on the origin.
  const Box3 box = bounds(load_mesh((kModels / "glTF2/BoxTextured-glTF/BoxTextured.gltf").string()));
  EXPECT_NEAR(box.hi.z - box.lo.z, 1, 1e-6);
}

TEST(AssimpModels, TruncatedAndEmptyFilesNameTheFile) {
  if (!fs::exists(kModels / "invalid")) GTEST_SKIP() << "assimp-testmodels not installed (.ci/install-deps)";
  for (const auto& e : fs::directory_iterator(kModels / "invalid")) {
    const std::string path = e.path().string();
    const std::string ext = e.path().extension().string();
    if (ext == ".txt" || ext == ".xml") continue;  // a readme; .xml is a Sweet Home file to Avenues
    SCOPED_TRACE(path);
    try {
      const Mesh m = load_mesh(path);
      // Assimp's malformed2.obj is a cube with a stray line: readable, and read.
      EXPECT_FALSE(m.triangles.empty());
    } catch (const std::runtime_error& err) {
      EXPECT_NE(std::string(err.what()).find(path), std::string::npos) << err.what();
    }
  }
}

// --- IFC ------------------------------------------------------------------------

namespace {

struct IfcModel {
  Plan plan;
  CellComplex cells;
};

const IfcModel& ifc_model(const std::string& path) {
  static std::map<std::string, IfcModel> cache;
  auto it = cache.find(path);
  if (it == cache.end()) {
    IfcModel m;
    m.plan = read_ifc_building(path);
    m.cells = build_cells(m.plan);
    it = cache.emplace(path, std::move(m)).first;
  }
  return it->second;
}

std::string duplex() { return (kIfc / "duplex.ifc").string(); }

}  // namespace

TEST(Ifc, DuplexHasItsFourStoreysAndNamedSpacesAsRooms) {
  if (!fs::exists(duplex())) GTEST_SKIP() << "no " << duplex();
  const IfcModel& m = ifc_model(duplex());
  EXPECT_EQ(m.plan.storeys.size(), 4u);
  for (size_t i = 1; i < m.plan.storeys.size(); ++i) {
    const Storey& below = m.plan.storeys[i - 1];
    EXPECT_NEAR(m.plan.storeys[i].elevation, below.elevation + below.height + below.slab, 1e-9);
  }
  // Of its 57 IFC walls, the bulkheads above doors and the parapets (not standing on a
  // storey's floor) are dropped with warnings; the rest stand, some on two storeys.
  EXPECT_GE(m.plan.walls.size(), 40u);
  int doors = 0, windows = 0;
  for (const Wall& w : m.plan.walls)
    for (const Opening& o : w.openings) (o.kind == OpeningKind::Door ? doors : windows) += 1;
  EXPECT_GE(doors, 10);
  EXPECT_GE(windows, 10);
  // Spaces of one open floor (the duplex's living, dining and kitchen, parted only by
  // Revit's room separation lines) share a room, named "A102 + A103 + ...".
  std::set<std::string> named;
  for (const RoomInfo& r : m.cells.rooms) {
    if (!r.named || !(r.area > 0)) continue;
    for (size_t at = 0; at != std::string::npos;) {
      const size_t plus = r.name.find(" + ", at);
      named.insert(r.name.substr(at, plus == std::string::npos ? plus : plus - at));
      at = plus == std::string::npos ? plus : plus + 3;
    }
  }
  EXPECT_GE(named.size(), 18u) << "of its 21 spaces";
  EXPECT_TRUE(named.count("A102")) << "its largest living space";
  EXPECT_EQ(cells_are_valid(m.cells), "");
  ASSERT_TRUE(m.plan.view.has_value());
  const Location at = m.cells.locate(m.plan.view->eye);
  EXPECT_EQ(at.what, Location::What::Cell) << "the first view stands in free space";
}

TEST(Ifc, ViewsOfEachModelAgreeWithRayCasting) {
  const std::vector<std::string> models = {duplex(), (kIfc / "Office_A_20110811.ifc").string(),
                                           (kIfc / "IfcOpenHouse_IFC4.ifc").string(),
                                           (kModels / "IFC/AC14-FZK-Haus.ifc").string()};
  for (const std::string& path : models) {
    if (!fs::exists(path)) continue;
    SCOPED_TRACE(path);
    const IfcModel& m = ifc_model(path);
    EXPECT_EQ(cells_are_valid(m.cells), "");
    ASSERT_TRUE(m.plan.view.has_value());
    // The first view, and views from the labels of a few rooms, turned four ways.
    std::vector<Vec3> eyes = {m.plan.view->eye};
    for (size_t r = 0; r < m.plan.rooms.size() && eyes.size() < 3; r += std::max<size_t>(1, m.plan.rooms.size() / 2)) {
      const Room& room = m.plan.rooms[r];
      const Storey& st = m.plan.storeys[size_t(room.storey)];
      eyes.push_back({room.label->x, room.label->y, st.elevation + 1.5});
    }
    int views = 0;
    for (Vec3 eye : eyes) {
      const Location at = m.cells.locate(eye);
      if (at.what != Location::What::Cell) continue;
      for (int k = 0; k < 4; ++k) {
        const double a = k * std::numbers::pi / 2;
        const Camera cam = Camera::look_at(eye, eye + Vec3{std::cos(a), std::sin(a), 0}, 70, 64, 40);
        const VisibleSet vs = find_visible(m.cells, cam, at.cell, Kernel::Double);
        const avenues::testing::OracleResult r = avenues::testing::check_visible_set(m.cells, cam, vs, 2);
        EXPECT_EQ(r.missing, 0);
        ++views;
      }
    }
    EXPECT_GE(views, 4);
  }
}

TEST(Ifc, WhatCannotBeReadIsAPlanErrorNamingTheFile) {
  if (!fs::exists(duplex())) GTEST_SKIP() << "no " << duplex();
  const fs::path dir = fs::temp_directory_path() / ("avenues-ifc-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string text = avenues::testing::slurp(duplex());
  const std::string cut = (dir / "cut.ifc").string();
  std::ofstream(cut, std::ios::binary) << text.substr(0, text.size() / 2);
  const std::string not_step = (dir / "not.ifc").string();
  std::ofstream(not_step, std::ios::binary) << "[storey]\nname = 'x'\n";
  const std::string structural = (kIfc / "ISSUE_021_Mini_Project.ifc").string();
  for (const std::string& path : {cut, not_step, structural}) {
    if (!fs::exists(path)) continue;
    SCOPED_TRACE(path);
    try {
      (void)read_ifc_building(path);
      ADD_FAILURE() << "read";
    } catch (const PlanError& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
  }
  fs::remove_all(dir);
}

// Avenues — meshes through Assimp (plans/assimp_reader.h) and IFC buildings
// (plans/formats/ifc_building.h): the right way up, in metres, bad files refused clearly.
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
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
#include <tuple>
#include <vector>

#include "cells/build_cells.h"
#include "app/plan_source.h"
#include "cells/mesh_scene.h"
#include "plans/assimp_reader.h"
#include "plans/formats/ifc4_for_assimp.h"
#include "plans/formats/ifc_building.h"
#include "plans/formats/ifc_step.h"
#include "plans/image_colour.h"
#include "plans/mesh.h"
#include "plans/plan_writer.h"
#include "ray_oracle.h"
#include "render/halftone.h"
#include "tests/avenues_run.h"
#include "tests/test_files.h"
#include "visibility/camera.h"
#include "visibility/visible_set.h"
#include "visibility/walker.h"

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

/// A red floor (4 m square at y = 0, glTF's Y up) and a blue wall standing at its far
/// edge (z = -2, 2 m high), two primitives of one mesh with a material each.
std::string gltf_red_floor_blue_wall() {
  const std::vector<std::array<float, 3>> v{{-2, 0, 2}, {2, 0, 2},  {2, 0, -2}, {-2, 0, -2},
                                            {-2, 0, -2}, {2, 0, -2}, {2, 2, -2}, {-2, 2, -2}};
  const std::vector<int> tri{0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7};
  std::string bin;
  for (const auto& p : v) bin.append(reinterpret_cast<const char*>(p.data()), 12);
  for (int i : tri) {
    const uint16_t s = uint16_t(i);
    bin.append(reinterpret_cast<const char*>(&s), 2);
  }
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1,"material":0},
                         {"attributes":{"POSITION":0},"indices":2,"material":1}]}],
"materials":[{"name":"red","pbrMetallicRoughness":{"baseColorFactor":[0.8,0.05,0.05,1]}},
             {"name":"blue","pbrMetallicRoughness":{"baseColorFactor":[0.05,0.05,0.8,1]}}],
"buffers":[{"byteLength":120,"uri":"data:application/octet-stream;base64,)" +
         base64(bin) + R"("}],
"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":96},{"buffer":0,"byteOffset":96,"byteLength":12},
               {"buffer":0,"byteOffset":108,"byteLength":12}],
"accessors":[{"bufferView":0,"componentType":5126,"count":8,"type":"VEC3","min":[-2,0,-2],"max":[2,2,2]},
{"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"},
{"bufferView":2,"componentType":5123,"count":6,"type":"SCALAR"}]})";
}

class AssimpFiles : public avenues::testing::AvenuesRun {};

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

TEST_F(AssimpFiles, SceneKeepsItsMaterialColoursInTheCellsAndThePicture) {
  const std::string path = write("room.gltf", gltf_red_floor_blue_wall());
  const Mesh m = load_mesh(path);
  ASSERT_EQ(m.material_of.size(), m.triangles.size());
  const CellComplex c = read_mesh_scene(path);
  // The eye 1 m above the floor's middle (Avenues: z up; the wall stands at y = 2).
  const Vec3 eye{0, 0, 1};
  const Location at = c.locate(eye);
  ASSERT_EQ(at.what, Location::What::Cell);
  auto centre_pixel = [&](Vec3 look) {
    const Camera cam = Camera::look_at(eye, look, 30, 33, 33);
    const VisibleSet vs = find_visible(c, cam, at.cell, Kernel::Double);
    const Image img = render_view(c, cam, vs, HalftoneOptions{});
    EXPECT_EQ(img.channels, 3);
    const size_t k = (size_t(img.height / 2) * size_t(img.width) + size_t(img.width / 2)) * 3;
    return std::array<int, 3>{img.data[k], img.data[k + 1], img.data[k + 2]};
  };
  const std::array<int, 3> floor = centre_pixel({0, 0.3, 0});  // down at the floor
  EXPECT_GT(floor[0], 2 * floor[1]) << "the floor is red: " << floor[0] << "," << floor[1] << "," << floor[2];
  EXPECT_GT(floor[0], 2 * floor[2]);
  const std::array<int, 3> wall = centre_pixel({0, 2, 1});  // ahead at the wall
  EXPECT_GT(wall[2], 2 * wall[0]) << "the wall is blue: " << wall[0] << "," << wall[1] << "," << wall[2];
  EXPECT_GT(wall[2], 2 * wall[1]);
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

// A 3MF model is a zip archive (as a Sweet Home home is) and a Blender file saved
// compressed is gzip: the content says only that much, so Assimp's extension decides, and
// each opens as a whole scene.
// A file's own first camera (COLLADA's duck has one, a glTF its nodes' cameras) is where
// its scene starts, as its own viewer starts there: the duck before the eye.
TEST(AssimpModels, TheFilesFirstCameraIsTheFirstView) {
  if (!fs::exists(kModels / "Collada/duck.dae")) GTEST_SKIP() << "assimp-testmodels not installed (.ci/install-deps)";
  const Mesh duck = load_mesh((kModels / "Collada/duck.dae").string());
  ASSERT_TRUE(duck.viewpoint.has_value());
  const Box3 b = bounds(duck);
  const Vec3 middle = 0.5 * (b.lo + b.hi), ahead = duck.viewpoint->look - duck.viewpoint->eye;
  const double off = std::acos(dot(ahead, middle - duck.viewpoint->eye) / length(ahead) / length(middle - duck.viewpoint->eye));
  EXPECT_LT(off * 180 / std::numbers::pi, 10);
  EXPECT_GT(length(middle - duck.viewpoint->eye), 2 * (b.hi.z - b.lo.z));  // from outside it
  const CellComplex c = build_mesh_scene({duck});
  ASSERT_TRUE(c.view.has_value());
  EXPECT_EQ(c.view->eye, duck.viewpoint->eye);
  // A model with no camera keeps the first view Avenues chooses.
  EXPECT_FALSE(load_mesh((kModels / "3DS/fels.3ds").string()).viewpoint.has_value());
}

TEST(AssimpModels, ZippedAndGzippedModelsOpenByTheirExtension) {
  if (!fs::exists(kModels / "3MF/box.3mf")) GTEST_SKIP() << "assimp-testmodels not installed (.ci/install-deps)";
  for (const char* name : {"3MF/box.3mf", "BLEND/BlenderDefault_250_Compressed.blend", "BLEND/MirroredCube_252.blend"}) {
    SCOPED_TRACE(name);
    const std::string path = (kModels / name).string();
    EXPECT_EQ(app::parse_plan_spec(path).format, FileFormat::Model);
    const app::LoadedPlan loaded = app::load_plan_source(path, app::ImportOptions{});
    ASSERT_EQ(cells_are_valid(loaded.complex), "");
    EXPECT_GT(loaded.complex.cells.size(), 1u);
  }
  // A zip named as a home, or by no name a reader knows, is still taken for a home.
  const fs::path dir = fs::temp_directory_path() / "avenues-zip-names";
  fs::create_directories(dir);
  for (const char* name : {"home.sh3d", "archive.zip", "noname"}) {
    std::ofstream(dir / name, std::ios::binary) << std::string("PK\x03\x04", 4) << std::string(60, '\0');
    EXPECT_EQ(app::parse_plan_spec((dir / name).string()).format, FileFormat::SweetHome) << name;
  }
  fs::remove_all(dir);
}

// Text saved as UTF-16 (with its byte-order mark, as Windows tools write it), which Assimp's
// own readers refuse ("magic sequence not found", "malformed XML"), reads as the UTF-8 file
// it is saved from: the same triangles, in the same places.
TEST(AssimpModels, Utf16TextReadsAsItsUtf8Twin) {
  if (!fs::exists(kModels / "AC/SphereWithLight_UTF16LE.ac")) GTEST_SKIP() << "assimp-testmodels not installed (.ci/install-deps)";
  for (const auto& [utf16, twin] : {std::pair{"AC/SphereWithLight_UTF16LE.ac", "AC/SphereWithLight_UTF8BOM.ac"},
                                    std::pair{"Collada/cube_UTF16LE.dae", "Collada/cube_UTF8BOM.dae"}}) {
    SCOPED_TRACE(utf16);
    const Mesh a = load_mesh((kModels / utf16).string()), b = load_mesh((kModels / twin).string());
    ASSERT_EQ(a.triangles.size(), b.triangles.size());
    EXPECT_GT(a.triangles.size(), 0u);
    ASSERT_EQ(a.vertices.size(), b.vertices.size());
    for (size_t v = 0; v < a.vertices.size(); ++v) EXPECT_EQ(length(a.vertices[v] - b.vertices[v]), 0) << v;
    EXPECT_EQ(a.triangles, b.triangles);
  }
}

// A model whose name says no format is told by its content, as Assimp's own tools tell it:
// Assimp's "formatDetection" files (3DS's chunks, AC3D's and ASE's first keywords, a
// DirectX "xof " header, HMP, LightWave's IFF, STL and OFF), a binary glTF and a 3MF
// archive under no extension. Text that is TOML stays a plan; text that is neither, under
// an extension no reader has, is said to be so; a guess Assimp cannot read is reported
// as a file Avenues does not know, with Assimp's reason.
TEST_F(AssimpFiles, ModelsWhoseNamesSayNothingAreToldByTheirContent) {
  if (!fs::exists(kModels / "3DS/testFormatDetection")) GTEST_SKIP() << "assimp-testmodels not installed (.ci/install-deps)";
  std::vector<std::string> files;
  for (const char* name : {"3DS/testFormatDetection", "AC/TestFormatDetection", "ASE/TestFormatDetection",
                           "X/TestFormatDetection", "HMP/formatDetection", "LWO/LWO2/formatDetection",
                           "STL/formatDetection", "OFF/formatDetection"})
    files.push_back((kModels / name).string());
  using avenues::testing::Outcome;
  using avenues::testing::slurp;
  files.push_back(write("box-glb", slurp((kModels / "glTF2/BoxTextured-glTF-Binary/BoxTextured.glb").string())));
  files.push_back(write("box-3mf", slurp((kModels / "3MF/box.3mf").string())));
  for (const std::string& f : files) {
    SCOPED_TRACE(f);
    const app::LoadedPlan loaded = app::load_plan_source(f, app::ImportOptions{});
    EXPECT_EQ(cells_are_valid(loaded.complex), "");
    EXPECT_GT(loaded.complex.cells.size(), 1u);
    EXPECT_FALSE(loaded.complex.portals.empty());  // free space cut by the model, not the far box alone
  }
  EXPECT_EQ(app::parse_plan_spec(files[0]).format, FileFormat::Model);
  EXPECT_EQ(app::parse_plan_spec(files[8]).format, FileFormat::Model);

  // A plan under no extension is still a plan.
  const std::string plan = write("house", slurp(std::string(AVENUES_SOURCE_DIR) + "/plans/jones-house.toml"));
  EXPECT_EQ(app::load_plan_source(plan, app::ImportOptions{}).format, FileFormat::Toml);
  // Text of a format no reader has (POV-Ray's scene language): its extension named, and
  // TOML's reason.
  Outcome r = run({"cells", write("model.pov", "camera { location <0, 2, -3> look_at <0, 1, 2> }\n")});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output().find("model.pov is not a plan Avenues can read: its extension '.pov' names no format"),
            std::string::npos) << r.output();
  EXPECT_NE(r.output().find("TOML"), std::string::npos) << r.output();
  // Blender's VRML export says "Blender" in its first lines, which Assimp's Blender reader
  // took for its own: its first line tells VRML97, read by Avenues (plans/vrml_scene.h).
  if (fs::exists(kModels / "WRL/Wuson.wrl")) {
    r = run({"cells", (kModels / "WRL/Wuson.wrl").string(), "--json"});
    EXPECT_EQ(r.status, 0) << r.output();
  }
  // Files of only points and lines: Assimp's own words for them are put plainly.
  r = run({"cells", (kModels / "AC/openLine.ac").string()});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output().find("openLine.ac: it holds no surfaces, only points or lines"), std::string::npos) << r.output();
}

// A textured material takes its image's mean colour, as an OBJ's map_Kd does: images beside
// the model, found in any case (a DOS-era 3DS names "IMAGE1.JPG" for IMAGE1.jpg), TGA read
// by stb_image (a COLLADA duck's), glTF's base colour factor times its texture; an image not
// at hand leaves the material's colour, said once per model.
TEST_F(AssimpFiles, TexturedMaterialsTakeTheirImagesMeanColour) {
  if (!fs::exists(kModels / "Collada/duck.dae")) GTEST_SKIP() << "assimp-testmodels not installed (.ci/install-deps)";
  using avenues::testing::slurp;
  // TGA, uncompressed and run-length encoded: 2 x 1, red and blue, mean (0.5, 0, 0.5) in linear light.
  const std::string header_raw("\0\0\x02\0\0\0\0\0\0\0\0\0\x02\0\x01\0\x18\0", 18);
  const std::string red_blue = header_raw + std::string("\0\0\xFF\xFF\0\0", 6);  // BGR, BGR
  std::string rle_header = header_raw;
  rle_header[2] = '\x0A';
  const std::string rle = rle_header + std::string("\x01\0\0\xFF\xFF\0\0", 7);  // a raw packet of two
  for (const std::string& tga : {red_blue, rle}) {
    const std::array<double, 3> mean = mean_image_colour(tga, "red-blue.tga");
    EXPECT_NEAR(mean[0], 0.5, 1e-12);
    EXPECT_NEAR(mean[1], 0, 1e-12);
    EXPECT_NEAR(mean[2], 0.5, 1e-12);
  }
  EXPECT_THROW((void)mean_image_colour("no image at all", "text.tga"), std::runtime_error);

  std::vector<std::string> warnings;
  const Mesh duck = load_mesh((kModels / "Collada/duck.dae").string(), {}, &warnings);
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  ASSERT_EQ(duck.materials.size(), 1u);
  const std::array<double, 3> texture = mean_image_colour(slurp((kModels / "Collada/duckCM.tga").string()), "duck");
  EXPECT_EQ(duck.materials[0].colour, texture);
  EXPECT_GT(duck.materials[0].colour[1], 2 * duck.materials[0].colour[2]);  // yellow

  // In any case, folder by folder: test1.3ds names IMAGE1.JPG (IMAGE1.jpg beside it);
  // spheres.nff names ./../../LWO/LWo2/MappingModes/EarthCylindric.jpg (the folder is LWO2).
  for (const char* name : {"3DS/test1.3ds", "NFF/NFF/spheres.nff"}) {
    warnings.clear();
    const Mesh m = load_mesh((kModels / name).string(), {}, &warnings);
    for (const std::string& w : warnings) EXPECT_EQ(w.find("texture"), std::string::npos) << name << ": " << w;
  }

  // glTF: the base colour factor times the texture's mean (BoxTextured's factor is white).
  warnings.clear();
  const Mesh box = load_mesh((kModels / "glTF2/BoxTextured-glTF/BoxTextured.gltf").string(), {}, &warnings);
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  ASSERT_FALSE(box.material_of.empty());
  const Material& boxes = box.materials[size_t(box.material_of[0])];  // (Assimp adds a default material too)
  const std::array<double, 3> logo =
      mean_image_colour(slurp((kModels / "glTF2/BoxTextured-glTF/CesiumLogoFlat.png").string()), "logo");
  for (size_t c = 0; c < 3; ++c) EXPECT_NEAR(boxes.colour[c], logo[c], 1e-6);

  // The image gone: the material's own colour, and one warning naming the image.
  const std::string dir =
      fs::path(write("duck/duck.dae", slurp((kModels / "Collada/duck.dae").string()))).parent_path().string();
  warnings.clear();
  const Mesh bare = load_mesh(dir + "/duck.dae", {}, &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("'blinn3' (its image ./duckCM.tga is not at hand)"), std::string::npos) << warnings[0];
  EXPECT_NE(bare.materials[0].colour, texture);
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

// Assimp's check of a scene refuses some files its own reader makes whole: an OpenGEX scene
// whose lights or cameras have no node, a RAW file that leaves an empty slot among a node's
// children. Avenues uses none of those parts: it drops them, says so, and keeps every
// triangle Assimp reads from the file unchecked. A scene with no nodes at all is still
// refused, naming the file.
TEST(AssimpModels, ScenesAssimpsCheckRefusesForPartsAvenuesDoesNotUseOpenWithAWarning) {
  if (!fs::exists(kModels / "OpenGEX/camera.ogex")) GTEST_SKIP() << "assimp-testmodels not installed (.ci/install-deps)";
  for (const char* name : {"OpenGEX/camera.ogex", "OpenGEX/collada.ogex", "RAW/WithColor.raw", "RAW/WithTexture.raw"}) {
    SCOPED_TRACE(name);
    const std::string path = (kModels / name).string();
    size_t expected = 0;  // what Assimp itself reads, unchecked, in the nodes that show meshes
    {
      Assimp::Importer importer;
      const aiScene* raw = importer.ReadFile(path, aiProcess_Triangulate);
      ASSERT_NE(raw, nullptr) << importer.GetErrorString();
      std::vector<const aiNode*> stack{raw->mRootNode};
      while (!stack.empty()) {
        const aiNode* n = stack.back();
        stack.pop_back();
        if (!n) continue;
        for (unsigned k = 0; k < n->mNumMeshes; ++k) {
          const aiMesh* m = raw->mMeshes[n->mMeshes[k]];
          for (unsigned f = 0; f < m->mNumFaces; ++f) expected += m->mFaces[f].mNumIndices == 3;
        }
        for (unsigned c = 0; c < n->mNumChildren; ++c) stack.push_back(n->mChildren[c]);
      }
    }
    ASSERT_GT(expected, 0u);
    const ImportedScene scene = import_scene(path);
    size_t kept = 0;
    for (const ImportedNode& n : scene.nodes) kept += n.triangles.size();
    EXPECT_EQ(kept, expected);
    ASSERT_FALSE(scene.warnings.empty());
    EXPECT_NE(scene.warnings[0].find("Assimp's check of the scene failed (Validation failed"), std::string::npos)
        << scene.warnings[0];
    const app::LoadedPlan loaded = app::load_plan_source(path, app::ImportOptions{});
    EXPECT_EQ(cells_are_valid(loaded.complex), "");
  }
  const std::string empty = (kModels / "OpenGEX/empty_camera.ogex").string();
  try {
    import_scene(empty);
    ADD_FAILURE() << "a scene with no nodes was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(empty), std::string::npos) << e.what();
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

/// A room of IFC4's Reference View, every element a tessellated face set: a wall with a
/// window's hole (an IfcPolygonalFaceSet with IfcIndexedPolygonalFaceWithVoids, in brick red
/// by an IfcStyledItem naming its IfcSurfaceStyle directly), a wall placed by an
/// IfcMappedItem, two turned by their placement, one of three boxes with a door's hole (an
/// open set), a door, a window, and the room's IfcSpace; lengths in millimetres. The north
/// wall and the floor slab have no OwnerHistory, as IfcOpenShell writes them. A round
/// column (an IfcColumnStandardCase) is extruded from a profile bounded by an
/// IfcIndexedPolyCurve of two arcs; a basin (IfcSanitaryTerminal) is a profile and an
/// extrusion with no Position; a handrail is a swept disk with no StartParam or EndParam;
/// the units hold an IfcConversionBasedUnitWithOffset (degrees Fahrenheit).
std::string tessellated_house() { return std::string(AVENUES_SOURCE_DIR) + "/tests/fuzz/corpus/ifc/tessellated-house.ifc"; }

}  // namespace

TEST(Ifc, DuplexHasItsFourStoreysAndNamedSpacesAsRooms) {
  if (!fs::exists(duplex())) GTEST_SKIP() << "no " << duplex();
  const IfcModel& m = ifc_model(duplex());
  EXPECT_EQ(m.plan.storeys.size(), 4u);
  for (size_t i = 1; i < m.plan.storeys.size(); ++i) {
    const Storey& below = m.plan.storeys[i - 1];
    EXPECT_NEAR(m.plan.storeys[i].elevation, below.elevation + below.height + below.slab, 1e-9);
  }
  EXPECT_GE(m.plan.walls.size(), 47u);
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
  // Spaces are named by their LongName (A102 is the "Living Room", A101 the "Foyer").
  EXPECT_TRUE(named.count("Living Room")) << "its largest living space";
  EXPECT_TRUE(named.count("Foyer"));
  EXPECT_FALSE(named.count("A102"));
  EXPECT_EQ(cells_are_valid(m.cells), "");
  ASSERT_TRUE(m.plan.view.has_value());
  const Location at = m.cells.locate(m.plan.view->eye);
  EXPECT_EQ(at.what, Location::What::Cell) << "the first view stands in free space";
}

// Stairs cut stairwells into the floors they climb to, so that a walker standing on one
// climbs through: in every model, from the middle of each stair's opening at eye height on
// the storey below, up to eye height on the storey above, and down again. Away from a stair
// walking keeps to the floor.
TEST(Ifc, StairsCutStairwellsThatAWalkerClimbs) {
  const std::vector<std::pair<std::string, size_t>> models = {
      {duplex(), 2}, {(kIfc / "Office_A_20110811.ifc").string(), 1}, {(kModels / "IFC/AC14-FZK-Haus.ifc").string(), 1}};
  for (const auto& [path, stairs] : models) {
    if (!fs::exists(path)) continue;
    SCOPED_TRACE(path);
    const IfcModel& m = ifc_model(path);
    EXPECT_GE(m.plan.floor_openings.size(), stairs);
    EXPECT_EQ(cells_are_valid(m.cells), "");
    for (const FloorOpening& f : m.plan.floor_openings) {
      SCOPED_TRACE(f.name);
      EXPECT_NE(f.where.element.find("IfcStair"), std::string::npos) << f.where.element;
      ASSERT_GE(f.storey, 1u);
      const Storey &below = m.plan.storeys[f.storey - 1], &above = m.plan.storeys[f.storey];
      Vec2 c{0, 0};
      for (Vec2 p : f.outline) c = c + p;
      c = (1.0 / double(f.outline.size())) * c;
      Walker w(m.cells, {c.x, c.y, below.elevation + kEyeHeight});
      ASSERT_TRUE(w.on_stair());
      for (int i = 0; i < 400; ++i) w.move({0, 0, 0.05}, 1.0 / 60);
      EXPECT_NEAR(w.eye().z, above.elevation + kEyeHeight, 1e-6);
      for (int i = 0; i < 400; ++i) w.move({0, 0, -0.05}, 1.0 / 60);
      EXPECT_NEAR(w.eye().z, below.elevation + kEyeHeight, 1e-6);
    }
  }
  if (!fs::exists(duplex())) return;
  // In the duplex's bathroom, with no stair: a climb is refused.
  const IfcModel& m = ifc_model(duplex());
  const double z = m.plan.storeys[1].elevation + kEyeHeight;  // Level 1
  Walker w(m.cells, {5.3, -9.67, z});
  EXPECT_FALSE(w.on_stair());
  w.move({0, 0, 0.5}, 1.0 / 60);
  EXPECT_NEAR(w.eye().z, z, 1e-9);
}

TEST(Ifc, ViewsOfEachModelAgreeWithRayCasting) {
  const std::vector<std::string> models = {duplex(), (kIfc / "Office_A_20110811.ifc").string(),
                                           (kIfc / "IfcOpenHouse_IFC4.ifc").string(),
                                           (kModels / "IFC/AC14-FZK-Haus.ifc").string(), tessellated_house()};
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

namespace {

std::string l_walled_room() { return std::string(AVENUES_SOURCE_DIR) + "/tests/fuzz/corpus/ifc/l-walled-room.ifc"; }


/// IFC element labels ("IfcWall 'x'") of the plan's walls and of its objects.
std::set<std::string> labels_of_walls(const Plan& p) {
  std::set<std::string> out;
  for (const Wall& w : p.walls) out.insert(w.where.element);
  return out;
}

bool is_wall_label(const std::string& s) {
  return s.rfind("IfcWall", 0) == 0 || s.rfind("IfcCurtainWall", 0) == 0 || s.rfind("IfcColumn", 0) == 0;
}

}  // namespace

TEST(Ifc, LShapedWallsStandAsConvexPiecesOfTheirSection) {
  // Two L-shaped walls round a 4 m by 3 m room, a 1 m gap in the north side: each L is no
  // rectangle (it fills 10 % of its own), so each stands on the convex pieces of its section.
  const IfcModel& m = ifc_model(l_walled_room());
  ASSERT_EQ(labels_of_walls(m.plan).size(), 2u);
  double area = 0;
  for (const Wall& w : m.plan.walls) {
    ASSERT_FALSE(w.footprint.empty()) << w.name;
    EXPECT_TRUE(is_convex_ccw(w.footprint)) << w.name;
    area += signed_area(w.footprint);
  }
  // Exactly, but for Assimp's single-precision coordinates.
  EXPECT_NEAR(area, (4.4 * 0.2 + 3.2 * 0.2) + (3.0 * 0.2 + 3.2 * 0.2), 1e-5) << "the pieces cover the Ls";
  EXPECT_EQ(cells_are_valid(m.cells), "");
  EXPECT_EQ(m.cells.locate({2.2, 1.7, 1.2}).what, Location::What::Cell) << "the room";
  EXPECT_EQ(m.cells.locate({3.7, 3.3, 1.2}).what, Location::What::Cell) << "the gap in the north wall";
  for (Vec3 in_wall : {Vec3{0.1, 1.7, 1.2}, Vec3{4.3, 1.7, 1.2}, Vec3{2.2, 0.1, 1.2}, Vec3{1.5, 3.3, 1.2}, Vec3{4.3, 3.3, 1.2}})
    EXPECT_EQ(m.cells.locate(in_wall).what, Location::What::Solid) << in_wall.x << "," << in_wall.y;
  // The space's LongName, and its floor in the slab's red.
  ASSERT_EQ(m.plan.rooms.size(), 1u);
  EXPECT_EQ(m.plan.rooms[0].name, "Living Room");
  ASSERT_GE(m.plan.rooms[0].floor, 0);
  const Material& floor = m.plan.materials[size_t(m.plan.rooms[0].floor)];
  EXPECT_NEAR(floor.colour[0], 0.8, 1e-6);
  EXPECT_NEAR(floor.colour[1], 0.2, 1e-6);
  EXPECT_NEAR(floor.colour[2], 0.1, 1e-6);
  // Names as the file writes them, spaces kept (Assimp's node says "Southandeast").
  EXPECT_EQ(labels_of_walls(m.plan).count("IfcWall 'South and east'"), 1u);
  // The footprints survive --save-plan: written as 'footprint', read back the same.
  const Plan back = parse_plan(plan_as_toml(m.plan), "l-walled-room.toml");
  ASSERT_EQ(back.walls.size(), m.plan.walls.size());
  for (size_t i = 0; i < back.walls.size(); ++i) {
    ASSERT_EQ(back.walls[i].footprint.size(), m.plan.walls[i].footprint.size());
    for (size_t k = 0; k < back.walls[i].footprint.size(); ++k)
      EXPECT_NEAR(length(back.walls[i].footprint[k] - m.plan.walls[i].footprint[k]), 0, 1e-9);
  }
  // A footprint that is not convex is refused, naming the wall.
  std::string toml = plan_as_toml(m.plan);
  const size_t at = toml.find("footprint = [");
  ASSERT_NE(at, std::string::npos);
  toml.insert(at + 13, "[ 2.0, 2.0 ], ");
  EXPECT_THROW((void)parse_plan(toml, "bent.toml"), PlanError);
}

TEST(Ifc, EveryWallOfTheModelsStands) {
  // The IFC wall, curtain wall and column elements each file holds (counted in the files):
  // every one stands as plan walls (a parapet as a low wall, a bulkhead under a ceiling as a
  // wall with a gap beneath it) or, standing on no storey's floor nor in one storey's
  // band, as an opaque object.
  const std::vector<std::pair<std::string, size_t>> models = {
      {duplex(), 57}, {(kIfc / "Office_A_20110811.ifc").string(), 487}, {(kModels / "IFC/AC14-FZK-Haus.ifc").string(), 14}};
  for (const auto& [path, walls] : models) {
    if (!fs::exists(path)) continue;
    SCOPED_TRACE(path);
    const IfcModel& m = ifc_model(path);
    std::set<std::string> standing = labels_of_walls(m.plan);
    for (const Object& o : m.plan.objects)
      if (is_wall_label(o.where.element)) standing.insert(o.where.element);
    EXPECT_EQ(standing.size(), walls);
  }
  // The duplex's roof parapets (0.61 m) are low walls of the roof storey.
  const IfcModel& d = ifc_model(duplex());
  int low = 0;
  for (const Wall& w : d.plan.walls) low += w.height > 0 && w.height < 1;
  EXPECT_GE(low, 4);
}

// Gable walls under a pitched roof (IfcOpenHouse's east and west walls, FZK-Haus's attic
// walls, each one IFC wall clipped by the roof's planes) stand as their tops run: rising to
// the ridge and falling again, one wall with a bend (Wall::top_bends) where the profile
// seen from its side turns, the space over each slope free. Where such walls rise to the top
// storey's ceiling and a roof covers it, the roof is that storey's top, not a flat slab at
// the ridge.
TEST(Ifc, GableWallsSlopeToTheirRidgeAndTheRoofIsTheTopStoreysTop) {
  struct Gabled {
    std::string path;
    size_t gables;
    double eaves, ridge;  // [m] above the top storey's floor
  };
  const std::vector<Gabled> models = {{(kIfc / "IfcOpenHouse_IFC4.ifc").string(), 2, 3.0, 5.5},
                                      {(kModels / "IFC/AC14-FZK-Haus.ifc").string(), 2, 0.5, 3.3868}};
  int read = 0;
  for (const Gabled& g : models) {
    if (!fs::exists(g.path)) continue;
    SCOPED_TRACE(g.path);
    ++read;
    const IfcModel& m = ifc_model(g.path);
    const Storey& top = m.plan.storeys.back();
    EXPECT_EQ(top.slab, 0);
    size_t gables = 0;
    for (const Wall& w : m.plan.walls) {
      if (size_t(w.storey) + 1 != m.plan.storeys.size() || !w.sloped()) continue;
      SCOPED_TRACE(w.name);
      // A gable: its ends at the eaves, one bend at its middle, the ridge.
      if (w.top_bends.size() != 1 || std::fabs(w.top_bends[0].x - w.length() / 2) > 0.01) continue;
      ++gables;
      EXPECT_NEAR(w.height, g.eaves, 0.01);
      EXPECT_NEAR(w.height_at_end, g.eaves, 0.01);
      EXPECT_NEAR(w.top_bends[0].y, g.ridge, 0.01);
      // Solid 5 cm under its top and free 5 cm over it, a quarter and three quarters along.
      for (double f : {0.25, 0.75}) {
        const Vec2 p = w.centre[0] + f * (w.centre[1] - w.centre[0]);
        const double z = top.elevation + w.top_at(f * w.length());
        EXPECT_EQ(m.cells.locate({p.x, p.y, z - 0.05}).what, Location::What::Solid) << f;
        EXPECT_EQ(m.cells.locate({p.x, p.y, z + 0.05}).what, Location::What::Cell) << f;
      }
    }
    EXPECT_EQ(gables, g.gables);
  }
  if (read == 0) GTEST_SKIP() << "neither model is here";
  // The duplex has no gables: its roof storey keeps its slab. Office A's roof storey has
  // two gable walls, but the file holds no roof to cover it: it keeps its slab too.
  if (fs::exists(duplex())) {
    EXPECT_GT(ifc_model(duplex()).plan.storeys.back().slab, 0);
  }
  if (const std::string office = (kIfc / "Office_A_20110811.ifc").string(); fs::exists(office)) {
    const Plan& p = ifc_model(office).plan;
    int gables = 0;
    for (const Wall& w : p.walls) gables += size_t(w.storey) + 1 == p.storeys.size() && w.sloped();
    EXPECT_EQ(gables, 2);
    EXPECT_GT(p.storeys.back().slab, 0);
    // Those gables rise 4.6 m above its band: what is above stands as objects of the top
    // storey, from the band's top to the ridge, not lost.
    const Storey& top = p.storeys.back();
    int above = 0;
    for (const Object& o : p.objects) {
      if (o.name.find("(above the top storey)") == std::string::npos) continue;
      ++above;
      ASSERT_TRUE(o.model);
      double lo = HUGE_VAL, hi = -HUGE_VAL;
      for (Vec3 v : o.model->vertices) lo = std::min(lo, v.z), hi = std::max(hi, v.z);
      EXPECT_NEAR(lo, top.height + top.slab, 1e-6);
      EXPECT_NEAR(hi, 6.892, 0.01);
    }
    EXPECT_EQ(above, 2);
  }
}

// A wall standing on no floor (Office A's partitions hung 2.6 m up on Level 2) is a wall of
// its storey with a gap beneath it along its whole length, up to its foot: cut out of the
// free space, so a walker passes under it and an eye flying at its height is stopped.
TEST(Ifc, BulkheadsAreWallsWithAGapBeneath) {
  const std::string office = (kIfc / "Office_A_20110811.ifc").string();
  if (!fs::exists(office)) GTEST_SKIP() << "no " << office;
  const IfcModel& m = ifc_model(office);
  int hung = 0, crossed = 0;
  for (const Wall& w : m.plan.walls) {
    if (w.openings.empty() || w.openings[0].name != "beneath " + w.name) continue;
    SCOPED_TRACE(w.name);
    ++hung;
    const Opening& gap = w.openings[0];
    EXPECT_EQ(gap.kind, OpeningKind::Gap);
    EXPECT_EQ(gap.at, 0);
    EXPECT_NEAR(gap.width, length(w.centre.back() - w.centre.front()), 1e-9);
    EXPECT_GT(gap.head, 2.0);
    // Across the wall's middle: under it on foot, and into it flying at its height.
    const Storey& st = m.plan.storeys[size_t(w.storey)];
    const Vec2 a = w.centre.front(), b = w.centre.back(), mid = 0.5 * (a + b);
    const Vec2 across = (1.0 / length(b - a)) * Vec2{a.y - b.y, b.x - a.x};
    const Vec2 from = mid + (w.thickness / 2 + 0.5) * across, to = mid - (w.thickness / 2 + 0.5) * across;
    const double z = st.elevation + kEyeHeight;
    if (m.cells.locate({from.x, from.y, z}).what != Location::What::Cell ||
        m.cells.locate({to.x, to.y, z}).what != Location::What::Cell)
      continue;  // something else stands beside this one's middle
    const Location at = m.cells.locate({from.x, from.y, z});
    const SegmentCast under = cast_segment(m.cells, at.cell, {from.x, from.y, z}, {to.x, to.y, z});
    EXPECT_FALSE(under.blocked);
    const double high = st.elevation + 0.5 * (gap.head + std::min(st.height, w.height < 0 ? st.height : w.height));
    const Location up = m.cells.locate({from.x, from.y, high});
    ASSERT_EQ(up.what, Location::What::Cell);
    const SegmentCast into = cast_segment(m.cells, up.cell, {from.x, from.y, high}, {to.x, to.y, high});
    EXPECT_TRUE(into.blocked);
    ++crossed;
  }
  EXPECT_GE(hung, 3);
  EXPECT_GE(crossed, 1);
}

TEST(Ifc, SlabsAndCoveringsAreFloorsCeilingsOrObjects) {
  if (!fs::exists(duplex())) GTEST_SKIP() << "no " << duplex();
  const IfcModel& m = ifc_model(duplex());
  int floors = 0, ceilings = 0, slab_objects = 0;
  for (const Room& r : m.plan.rooms) floors += r.floor >= 0, ceilings += r.ceiling >= 0;
  for (const Object& o : m.plan.objects) slab_objects += o.where.element.rfind("IfcSlab", 0) == 0;
  EXPECT_GE(floors, 18) << "of 21 spaces, each over a finish floor";
  EXPECT_GE(ceilings, 15) << "under a gypsum board ceiling or the slab above";
  EXPECT_GE(slab_objects, 1) << "the roof slab, no room's floor, is drawn as an object";
}

TEST(Ifc, Ifc4TessellatedModelsStandAsTheirFacesSay) {
  // Assimp 5.2 crashes on IFC4's face sets and fails on styles named directly: the file is
  // read as IFC2X3 would write it (ifc4_for_assimp.h).
  const IfcModel& m = ifc_model(tessellated_house());
  EXPECT_EQ(cells_are_valid(m.cells), "");
  std::map<std::string, const Wall*> walls;
  for (const Wall& w : m.plan.walls) walls[w.name] = &w;
  ASSERT_EQ(walls.size(), 5u) << "South, North, West, East, the round column";
  // The column's section: round, its corners on the 300 mm circle, its area within 1 % (the
  // arcs become sides at most 5° across; Assimp's extrusion and the section keep fewer).
  const Wall& column = *walls.at("Round column");
  ASSERT_GE(column.footprint.size(), 30u);
  double area = 0;
  for (size_t k = 0; k < column.footprint.size(); ++k)
    area += cross(column.footprint[k], column.footprint[(k + 1) % column.footprint.size()]) / 2;
  EXPECT_NEAR(area, std::numbers::pi * 0.15 * 0.15, 0.01 * std::numbers::pi * 0.15 * 0.15);
  for (Vec2 p : column.footprint) EXPECT_NEAR(length(p - Vec2{3, 2}), 0.15, 1e-5);
  walls.erase("Round column");
  auto centre_x = [](const Wall& w) { return (w.centre.front().x + w.centre.back().x) / 2; };
  auto centre_y = [](const Wall& w) { return (w.centre.front().y + w.centre.back().y) / 2; };
  EXPECT_NEAR(centre_y(*walls.at("South")), 0.1, 1e-6);
  EXPECT_NEAR(centre_y(*walls.at("North")), 3.9, 1e-6) << "mapped 3.8 m north";
  EXPECT_NEAR(centre_x(*walls.at("West")), 0.1, 1e-6) << "its placement turns it along y";
  EXPECT_NEAR(centre_x(*walls.at("East")), 5.9, 1e-6);
  for (const auto& [name, w] : walls) EXPECT_NEAR(w->thickness, 0.2, 1e-6) << name;
  ASSERT_EQ(walls.at("South")->openings.size(), 1u);
  const Opening& window = walls.at("South")->openings[0];
  EXPECT_EQ(window.kind, OpeningKind::Window);
  EXPECT_NEAR(window.sill, 0.9, 1e-6);
  EXPECT_NEAR(window.head, 2.1, 1e-6);
  EXPECT_NEAR(window.width, 1.0, 1e-6);
  ASSERT_EQ(walls.at("East")->openings.size(), 1u) << "the door of the open set";
  EXPECT_EQ(walls.at("East")->openings[0].kind, OpeningKind::Door);
  EXPECT_EQ(walls.at("East")->openings[0].name, "Front door");
  EXPECT_NEAR(walls.at("East")->openings[0].width, 0.9, 1e-6);
  ASSERT_GE(walls.at("South")->material, 0);
  const auto brick = m.plan.materials[size_t(walls.at("South")->material)].colour;
  EXPECT_NEAR(brick[0], 0.8, 1e-6);
  EXPECT_NEAR(brick[1], 0.3, 1e-6);
  EXPECT_NEAR(brick[2], 0.2, 1e-6);
  ASSERT_EQ(m.plan.rooms.size(), 1u);
  EXPECT_EQ(m.plan.rooms[0].name, "Living room") << "its LongName";
  // IFC4's sanitary terminal, read by Assimp as IFC2X3's flow terminal, keeps its own kind in
  // its name; its extrusion stands where placed.
  std::map<std::string, Box3> objects;
  for (const Object& o : m.plan.objects) {
    ASSERT_TRUE(o.model) << o.where.element;
    Box3 b;
    for (Vec3 v : o.model->vertices) b.add(v);
    objects[o.where.element] = b;
  }
  ASSERT_EQ(objects.count("IfcSanitaryTerminal 'Basin'"), 1u) << "objects: " << objects.size();
  const Box3 basin = objects.at("IfcSanitaryTerminal 'Basin'");
  EXPECT_NEAR(basin.hi.x - basin.lo.x, 0.4, 1e-4);
  EXPECT_NEAR(basin.hi.y - basin.lo.y, 0.3, 1e-4);
  EXPECT_NEAR((basin.lo.x + basin.hi.x) / 2, 5.5, 1e-4);
  EXPECT_NEAR(basin.hi.z - basin.lo.z, 0.15, 1e-4);
  ASSERT_EQ(objects.count("IfcRailing 'Handrail'"), 1u);
  const Box3 rail = objects.at("IfcRailing 'Handrail'");
  EXPECT_NEAR(rail.hi.x - rail.lo.x, 2.0, 0.05) << "its whole polyline";

  // What cannot be used is dropped, said with its record and line, and the rest still read:
  // the east wall's set names a point its list lacks, the north wall's points are no numbers,
  // the column is tapered (IFC4's IfcExtrudedAreaSolidTapered).
  std::string text = avenues::testing::slurp(tessellated_house());
  const size_t east = text.find("$,.F.,((1,4,3)");
  ASSERT_NE(east, std::string::npos);
  text.replace(east, 14, "$,.F.,((1,4,99)");
  const size_t north = text.find("#58=IFCCARTESIANPOINTLIST3D(((0.0,");
  ASSERT_NE(north, std::string::npos);
  text.replace(north, 34, "#58=IFCCARTESIANPOINTLIST3D(((zero,");
  const std::string extrusion = "#113=IFCEXTRUDEDAREASOLID(#110,#112,#4,2700.);";
  const size_t tapered = text.find(extrusion);
  ASSERT_NE(tapered, std::string::npos);
  text.replace(tapered, extrusion.size(), "#113=IFCEXTRUDEDAREASOLIDTAPERED(#110,#112,#4,2700.,#110);");
  const fs::path dir = fs::temp_directory_path() / ("avenues-ifc4-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string broken = (dir / "broken.ifc").string();
  std::ofstream(broken, std::ios::binary) << text;
  const Plan p = read_ifc_building(broken);
  std::string said;
  for (const std::string& w : p.warnings) said += w + "\n";
  EXPECT_NE(said.find(broken + ": line 91, #84 (IfcTriangulatedFaceSet): 1 of its 36 faces cannot be used"),
            std::string::npos)
      << said;
  EXPECT_NE(said.find(broken + ": line 66, #59 (IfcTriangulatedFaceSet): its point list #58 is not a list of three "
                               "numbers each: its faces are dropped"),
            std::string::npos)
      << said;
  EXPECT_NE(said.find(broken + ": line 119, #113 (IfcExtrudedAreaSolidTapered): read as an IfcExtrudedAreaSolid, "
                               "without its taper (the end profile)"),
            std::string::npos)
      << said;
  std::set<std::string> kept;
  for (const Wall& w : p.walls) kept.insert(w.name);
  EXPECT_EQ(kept, (std::set<std::string>{"South", "West", "East", "Round column"}));
  EXPECT_NE(said.find("IfcWall 'North'"), std::string::npos) << "the wall left with no faces is dropped, by name\n" << said;
  fs::remove_all(dir);
}

TEST(IfcStep, Ifc4RecordsAssimpCannotReadAreRewrittenAsIfc2x3WritesThem) {
  const std::string head = "ISO-10303-21;\nHEADER;\nFILE_SCHEMA(('IFC4'));\nENDSEC;\nDATA;\n";
  EXPECT_FALSE(ifc4_for_assimp(head + "#1=IFCCARTESIANPOINT((0.,0.,0.));\nENDSEC;\nEND-ISO-10303-21;\n"))
      << "nothing to rewrite: Assimp reads the file itself";
  // A closed tetrahedron whose faces reach its points through PnIndex.
  const std::string tetra = head +
                            "#1=IFCCARTESIANPOINTLIST3D(((9.,9.,9.),(0.,0.,0.),(1.E3,0.,0.),(0.,1000.,0.),(0.,0.,1000.)));\n"
                            "#2=IFCTRIANGULATEDFACESET(#1,$,.T.,((1,3,2),(1,2,4),(1,4,3),(2,3,4)),(2,3,4,5));\n"
                            "ENDSEC;\nEND-ISO-10303-21;\n";
  const auto t = ifc4_for_assimp(tetra);
  ASSERT_TRUE(t);
  EXPECT_EQ(t->face_sets, 1u);
  EXPECT_TRUE(t->warnings.empty());
  EXPECT_NE(t->text.find("#2=IFCFACETEDBREP(#"), std::string::npos) << t->text;
  EXPECT_NE(t->text.find("=IFCCLOSEDSHELL((#"), std::string::npos);
  EXPECT_NE(t->text.find("=IFCCARTESIANPOINT((1.E3,0.,0.))"), std::string::npos) << "copied as written";
  EXPECT_EQ(t->text.find("IFCCARTESIANPOINT((9.,9.,9.))"), std::string::npos) << "a point no face names is not made";
  EXPECT_EQ(ifc4_for_assimp(t->text), std::nullopt) << "what it writes is IFC2X3's";
  EXPECT_TRUE(step_data_problem(t->text) == std::nullopt) << "every new reference has its record";
  auto count = [](const std::string& s, const std::string& what) {
    size_t n = 0;
    for (size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count(t->text, "=IFCPOLYLOOP("), 4u);
  EXPECT_EQ(count(t->text, "=IFCCARTESIANPOINT("), 4u);

  // A polygonal set: a square with a square hole, a face naming a point the list lacks, a
  // face of two points; and a style named directly by its styled item.
  const std::string square = head +
                             "#1=IFCCARTESIANPOINTLIST3D(((0.,0.,0.),(4.,0.,0.),(4.,4.,0.),(0.,4.,0.),(1.,1.,0.),(1.,2.,0.),"
                             "(2.,2.,0.),(2.,1.,0.)));\n"
                             "#2=IFCINDEXEDPOLYGONALFACEWITHVOIDS((1,2,3,4),((5,6,7,8)));\n"
                             "#3=IFCINDEXEDPOLYGONALFACE((1,2,9));\n#4=IFCINDEXEDPOLYGONALFACE((1,2,2,1));\n"
                             "#5=IFCPOLYGONALFACESET(#1,.T.,(#2,#3,#4),$);\n"
                             "#6=IFCCOLOURRGB($,1.,0.,0.);\n#7=IFCSURFACESTYLESHADING(#6);\n"
                             "#8=IFCSURFACESTYLE('Red',.BOTH.,(#7));\n#9=IFCSTYLEDITEM(#5,(#8),'paint');\n"
                             "ENDSEC;\nEND-ISO-10303-21;\n";
  const auto q = ifc4_for_assimp(square);
  ASSERT_TRUE(q);
  EXPECT_EQ(q->styles, 1u);
  EXPECT_NE(q->text.find("#5=IFCSHELLBASEDSURFACEMODEL((#"), std::string::npos) << "no longer closed: " << q->text;
  EXPECT_NE(q->text.find("=IFCOPENSHELL((#"), std::string::npos);
  EXPECT_EQ(count(q->text, "=IFCFACEBOUND(#"), 1u) << "the hole";
  EXPECT_EQ(count(q->text, "=IFCFACE((#"), 1u);
  ASSERT_EQ(q->warnings.size(), 1u);
  EXPECT_EQ(q->warnings[0], "line 10, #5 (IfcPolygonalFaceSet): 2 of its 3 faces cannot be used (not a list of "
                            "indices, a point its list does not have, or fewer than three points): dropped");
  const size_t styled = q->text.find("#9=IFCSTYLEDITEM(#5,(#");
  ASSERT_NE(styled, std::string::npos) << q->text;
  EXPECT_NE(q->text.find("=IFCPRESENTATIONSTYLEASSIGNMENT((#8))"), std::string::npos);
  EXPECT_NE(q->text.find("),'paint');", styled), std::string::npos);
  EXPECT_TRUE(step_data_problem(q->text) == std::nullopt);

  // An indexed curve: a straight piece, then a half circle about (1, 1) through (2, 1).
  const auto c = ifc4_for_assimp(head + "#1=IFCCARTESIANPOINTLIST2D(((0.,0.),(1.,0.),(2.,1.),(1.,2.)));\n"
                                        "#2=IFCINDEXEDPOLYCURVE(#1,(IFCLINEINDEX((1,2)),IFCARCINDEX((2,3,4))),.F.);\n"
                                        "#3=IFCINDEXEDPOLYCURVE(#1,$,.F.);\nENDSEC;\n");
  ASSERT_TRUE(c);
  EXPECT_EQ(c->curves, 2u);
  EXPECT_TRUE(step_data_problem(c->text) == std::nullopt);
  EXPECT_NE(c->text.find("#2=IFCPOLYLINE((#"), std::string::npos) << c->text;
  EXPECT_NE(c->text.find("#3=IFCPOLYLINE((#"), std::string::npos) << c->text;
  int on_circle = 0;
  for_each_step_record(c->text, [&](const StepRecord& r) {
    if (r.keyword != "IFCCARTESIANPOINT" || r.id > 41) return;  // #2's points come first: #4 to #41
    const auto xy = step_list(r.attributes[0]);
    ASSERT_TRUE(xy && xy->size() == 2);
    const Vec2 p{std::stod(std::string((*xy)[0])), std::stod(std::string((*xy)[1]))};
    if (p.x >= 1) on_circle += std::fabs(length(p - Vec2{1, 1}) - 1) < 1e-12;
  });
  EXPECT_EQ(on_circle, 37) << "its ends, and 35 points 5° apart";

  // NURBS boundaries IFC2X3 has no form for: left out, said; an advanced face (an IfcFaceSurface
  // bounded by curves) is read as a face surface, whose edge loops Assimp passes over.
  const auto n = ifc4_for_assimp(head + "#1=IFCCLOSEDSHELL((#3));\n#2=IFCADVANCEDBREP(#1);\n#3=IFCADVANCEDFACE((),#4,.T.);\nENDSEC;\n");
  ASSERT_TRUE(n);
  EXPECT_EQ(n->solids, 2u);
  EXPECT_NE(n->text.find("#2=IFCBOUNDINGBOX(#"), std::string::npos) << n->text;
  EXPECT_NE(n->text.find("#3=IFCFACESURFACE((),#4,.T.)"), std::string::npos) << n->text;
  ASSERT_EQ(n->warnings.size(), 2u);
  EXPECT_EQ(n->warnings[0], "line 7, #2 (IfcAdvancedBrep): IFC2X3, which Assimp reads, has no form for it: its geometry is left out");
  EXPECT_EQ(n->warnings[1], "line 8, #3 (IfcAdvancedFace): read as an IfcFaceSurface: its edge loops (curves, not polygons) are left out");

  // An IfcRoot with no OwnerHistory (optional in IFC4) is given one.
  const auto o = ifc4_for_assimp(head + "#7=IFCWALL('2BTBFw6f90Nfh9rP1dlXrr', $ ,'w',$,$,$,$,$,.STANDARD.);\n"
                                        "#8=IFCCARTESIANPOINT((0.,0.,0.));\nENDSEC;\n");
  ASSERT_TRUE(o);
  EXPECT_EQ(o->owners, 1u);
  EXPECT_NE(o->text.find("#7=IFCWALL('2BTBFw6f90Nfh9rP1dlXrr',#13,'w',$,$,$,$,$,.STANDARD.);"), std::string::npos) << o->text;
  EXPECT_NE(o->text.find("=IFCOWNERHISTORY(#"), std::string::npos);
  EXPECT_TRUE(step_data_problem(o->text) == std::nullopt);

  // Points that are no numbers: the set is an empty bounding box, which Assimp passes over.
  const auto z = ifc4_for_assimp(head + "#1=IFCCARTESIANPOINTLIST3D(((0.,0.,0.),(1.,0.,0.),(nan,1.,0.)));\n"
                                        "#2=IFCTRIANGULATEDFACESET(#1,$,.T.,((1,2,3)),$);\nENDSEC;\n");
  ASSERT_TRUE(z);
  EXPECT_NE(z->text.find("#2=IFCBOUNDINGBOX(#"), std::string::npos) << z->text;
  EXPECT_TRUE(step_data_problem(z->text) == std::nullopt);
  ASSERT_EQ(z->warnings.size(), 1u);
  EXPECT_NE(z->warnings[0].find("#2 (IfcTriangulatedFaceSet): its point list #1 is not a list of three numbers"),
            std::string::npos)
      << z->warnings[0];

  // CSG (IFC2X3 and IFC4 alike): a block and a cylinder are the extrusions they are; a CSG
  // solid is its tree's root, a boolean result copied as written under the solid's id; a
  // sphere is left out, said, as is a block of no size.
  const auto g = ifc4_for_assimp(head + "#1=IFCAXIS2PLACEMENT3D(#9,$,$);\n#2=IFCBLOCK(#1,2.,0.8,0.5);\n"
                                        "#3=IFCRIGHTCIRCULARCYLINDER(#1,2.5,0.1);\n#4=IFCBOOLEANRESULT(.DIFFERENCE.,#2,#3);\n"
                                        "#5=IFCCSGSOLID(#4);\n#6=IFCCSGSOLID(#2);\n#7=IFCSPHERE(#1,1.);\n"
                                        "#8=IFCBLOCK(#1,0.,1.,1.);\n#9=IFCCARTESIANPOINT((0.,0.,0.));\nENDSEC;\n");
  ASSERT_TRUE(g);
  EXPECT_TRUE(step_data_problem(g->text) == std::nullopt) << g->text;
  EXPECT_NE(g->text.find("#2=IFCEXTRUDEDAREASOLID(#"), std::string::npos) << g->text;
  EXPECT_NE(g->text.find(",#1,#"), std::string::npos) << "placed where the block is";
  EXPECT_NE(g->text.find("=IFCCARTESIANPOINT((1.,0.4))"), std::string::npos) << "the rectangle's middle, in as few digits as read back";
  EXPECT_NE(g->text.find("=IFCRECTANGLEPROFILEDEF(.AREA.,$,#"), std::string::npos);
  EXPECT_NE(g->text.find(",2.,0.8)"), std::string::npos) << "its sides as written";
  EXPECT_NE(g->text.find(",0.5);"), std::string::npos) << "its height as the depth";
  EXPECT_NE(g->text.find("#3=IFCEXTRUDEDAREASOLID(#"), std::string::npos);
  EXPECT_NE(g->text.find("=IFCCIRCLEPROFILEDEF(.AREA.,$,#"), std::string::npos);
  EXPECT_NE(g->text.find(",2.5);"), std::string::npos) << "the cylinder's height";
  EXPECT_NE(g->text.find("#4=IFCBOOLEANRESULT(.DIFFERENCE.,#2,#3);"), std::string::npos) << "as written";
  EXPECT_NE(g->text.find("#5=IFCBOOLEANRESULT(.DIFFERENCE.,#2,#3)"), std::string::npos) << "the CSG solid's root";
  EXPECT_NE(g->text.find("#6=IFCEXTRUDEDAREASOLID(#"), std::string::npos) << "a CSG solid of one block";
  EXPECT_NE(g->text.find("#7=IFCBOUNDINGBOX(#"), std::string::npos);
  EXPECT_NE(g->text.find("#8=IFCBOUNDINGBOX(#"), std::string::npos);
  size_t ups = 0;
  for (size_t at = g->text.find("IFCDIRECTION((0.,0.,1.))"); at != std::string::npos;
       at = g->text.find("IFCDIRECTION((0.,0.,1.))", at + 1))
    ++ups;
  EXPECT_EQ(ups, 1u) << "one direction for every extrusion";
  ASSERT_EQ(g->warnings.size(), 2u);
  EXPECT_EQ(g->warnings[0], "line 12, #7 (IfcSphere): Assimp reads no IfcSphere: its geometry is left out");
  EXPECT_EQ(g->warnings[1], "line 13, #8 (IfcBlock): its Position and dimensions are not a placement and positive "
                            "numbers: its geometry is left out");
}

TEST(IfcStep, ListsAndReferencesAreReadAsWritten) {
  EXPECT_EQ(step_list(" ((1,2,3), (4,5,6)) "), (std::vector<std::string_view>{"(1,2,3)", "(4,5,6)"}));
  EXPECT_EQ(step_list("('a,b)',#3)"), (std::vector<std::string_view>{"'a,b)'", "#3"}));
  EXPECT_EQ(step_list("()"), std::vector<std::string_view>{});
  EXPECT_EQ(step_list("(1,,2)"), std::nullopt);
  EXPECT_EQ(step_list("(1,2"), std::nullopt);
  EXPECT_EQ(step_list("(1))("), std::nullopt);
  EXPECT_EQ(step_list("$"), std::nullopt);
  EXPECT_EQ(step_reference(" #42 "), 42u);
  EXPECT_EQ(step_reference("#"), std::nullopt);
  EXPECT_EQ(step_reference("#4a"), std::nullopt);
}

TEST(IfcStep, NamesAndLongNamesAreReadFromTheRecords) {
  const std::string text =
      "ISO-10303-21;\nDATA;\n/* a comment; with a semicolon */\n"
      "#1= IFCSPACE('0BTBFw6f90Nfh9rP1dlXrr',#33,'A101','',$,#487,#513,'Foyer',.ELEMENT.,.INTERNAL.,$);\n"
      "#2=IFCSPACE('1BTBFw6f90Nfh9rP1dlXrr',#33,'K1',$,$,#4,#5,'K\\X2\\00FC\\X0\\che; Bar''s',.ELEMENT.,$,$);\n"
      "#3=IFCWALL('2BTBFw6f90Nfh9rP1dlXrr',#5,'Basic Wall:Interior - 92mm',$,$,#6,#7,$);\n"
      "#4=IFCSPACE('3BTBFw6f90Nfh9rP1dlXrr',#33,'B1',$,$,#4,#5,$,.ELEMENT.,$,$);\n"
      "#5=IFCSPACE('4BTBFw6f90Nfh9rP1dlXrr',#33,'B2',$,$,#4,#5,'bad \\X2\\00F\\X0\\',.ELEMENT.,$,$);\n"
      "#6=IFCCARTESIANPOINT((0.,0.));\nENDSEC;\n";
  const auto names = ifc_root_names(text);
  EXPECT_EQ(names.at("0BTBFw6f90Nfh9rP1dlXrr").long_name, "Foyer");
  EXPECT_EQ(names.at("0BTBFw6f90Nfh9rP1dlXrr").name, "A101");
  EXPECT_EQ(names.at("1BTBFw6f90Nfh9rP1dlXrr").long_name, "K\xC3\xBC" "che; Bar's");
  EXPECT_EQ(names.at("2BTBFw6f90Nfh9rP1dlXrr").name, "Basic Wall:Interior - 92mm");
  EXPECT_EQ(names.at("3BTBFw6f90Nfh9rP1dlXrr").long_name, "");
  EXPECT_EQ(names.at("4BTBFw6f90Nfh9rP1dlXrr").long_name, "") << "a malformed escape is no name";
  bool ok = true;
  EXPECT_EQ(decode_step_string("\\S\\D\\X\\E9\\\\", ok), "\xC3\x84\xC3\xA9\\");
  EXPECT_TRUE(ok);
  (void)decode_step_string("\\X2\\D800\\X0\\", ok);
  EXPECT_FALSE(ok) << "a lone surrogate";
}

TEST(Ifc, CsgColumnsStandAsTheirBlocksAndCylindersSay) {
  // The L-walled room with two columns made by CSG, which Assimp reads only as extrusions:
  // a 0.4 m block less a cylinder (a boolean result, the root of an IfcCsgSolid) and a
  // round column (an IfcRightCircularCylinder alone); a ball on the floor left out, said.
  std::string text = avenues::testing::slurp(l_walled_room());
  const std::string columns =
      "#200=IFCCARTESIANPOINT((1.,1.,0.));\n#201=IFCAXIS2PLACEMENT3D(#200,#9,#10);\n"
      "#202=IFCBLOCK(#201,0.4,0.4,2.5);\n#203=IFCCARTESIANPOINT((1.2,1.2,0.));\n"
      "#204=IFCAXIS2PLACEMENT3D(#203,#9,#10);\n#205=IFCRIGHTCIRCULARCYLINDER(#204,2.5,0.05);\n"
      "#206=IFCBOOLEANRESULT(.DIFFERENCE.,#202,#205);\n#207=IFCCSGSOLID(#206);\n"
      "#208=IFCSHAPEREPRESENTATION(#12,'Body','CSG',(#207));\n#209=IFCPRODUCTDEFINITIONSHAPE($,$,(#208));\n"
      "#210=IFCCOLUMN('0ZvctVUKr0kugbFTf53O9L',#5,'Square',$,$,#14,#209,$);\n"
      "#211=IFCCARTESIANPOINT((3.,2.,0.));\n#212=IFCAXIS2PLACEMENT3D(#211,#9,#10);\n"
      "#213=IFCRIGHTCIRCULARCYLINDER(#212,2.5,0.15);\n#214=IFCSHAPEREPRESENTATION(#12,'Body','CSG',(#213));\n"
      "#215=IFCPRODUCTDEFINITIONSHAPE($,$,(#214));\n#216=IFCCOLUMN('1ZvctVUKr0kugbFTf53O9L',#5,'Round',$,$,#14,#215,$);\n"
      "#217=IFCSPHERE(#212,0.1);\n#218=IFCSHAPEREPRESENTATION(#12,'Body','CSG',(#217));\n"
      "#219=IFCPRODUCTDEFINITIONSHAPE($,$,(#218));\n#220=IFCFURNISHINGELEMENT('2ZvctVUKr0kugbFTf53O9L',#5,'Ball',$,$,#14,#219,$);\n"
      "#221=IFCRELCONTAINEDINSPATIALSTRUCTURE('3ZvctVUKr0kugbFTf53O9L',#5,$,$,(#210,#216,#220),#17);\n";
  text.insert(text.rfind("ENDSEC;"), columns);
  const fs::path dir = fs::temp_directory_path() / ("avenues-ifc-csg-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string path = (dir / "csg-columns.ifc").string();
  std::ofstream(path, std::ios::binary) << text;
  const Plan plan = read_ifc_building(path);
  const CellComplex c = build_cells(plan);
  EXPECT_EQ(cells_are_valid(c), "");
  const std::set<std::string> walls = labels_of_walls(plan);
  EXPECT_EQ(walls.count("IfcColumn 'Square'"), 1u);
  EXPECT_EQ(walls.count("IfcColumn 'Round'"), 1u);
  EXPECT_EQ(c.locate({1.05, 1.05, 1.2}).what, Location::What::Solid) << "the square column's corner";
  EXPECT_EQ(c.locate({3.0, 2.14, 1.2}).what, Location::What::Solid) << "the round column";
  EXPECT_EQ(c.locate({3.0, 2.2, 1.2}).what, Location::What::Cell) << "beside it";
  EXPECT_EQ(c.locate({2.2, 1.7, 1.2}).what, Location::What::Cell) << "the room";
  const bool said = std::any_of(plan.warnings.begin(), plan.warnings.end(), [](const std::string& w) {
    return w.find("(IfcSphere): Assimp reads no IfcSphere") != std::string::npos;
  });
  EXPECT_TRUE(said) << "the ball";
  fs::remove_all(dir);
}

TEST(Ifc, AModelOfGeometryAssimpHasNoFormForIsRefusedNamingWhatWasLeftOut) {
  // Only a ball (IfcSphere, which Assimp reads in no form): nothing is left for Assimp to
  // read, and the error says what was left out and where, not only Assimp's own words.
  std::string text = avenues::testing::slurp(l_walled_room());
  text.erase(text.find("/* Wall A"), text.rfind("ENDSEC;") - text.find("/* Wall A"));
  text.insert(text.rfind("ENDSEC;"),
              "#200=IFCSPHERE(#11,0.5);\n#201=IFCSHAPEREPRESENTATION(#12,'Body','CSG',(#200));\n"
              "#202=IFCPRODUCTDEFINITIONSHAPE($,$,(#201));\n"
              "#203=IFCBUILDINGELEMENTPROXY('0ZvctVUKr0kugbFTf53O9L',#5,'Ball',$,$,#14,#202,$,$);\n"
              "#204=IFCRELCONTAINEDINSPATIALSTRUCTURE('1ZvctVUKr0kugbFTf53O9L',#5,$,$,(#203),#17);\n");
  const fs::path dir = fs::temp_directory_path() / ("avenues-ifc-ball-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string path = (dir / "ball.ifc").string();
  std::ofstream(path, std::ios::binary) << text;
  try {
    read_ifc_building(path);
    FAIL() << "read";
  } catch (const PlanError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find("#200 (IfcSphere): Assimp reads no IfcSphere: its geometry is left out"), std::string::npos)
        << what;
  }
  fs::remove_all(dir);
}

TEST(Ifc, DanglingReferencesAndBrokenRecordsAreRefusedBeforeAssimpCrashesOnThem) {
  // Assimp 5.2's STEP reader dereferences what it could not resolve (a fuzzer found both).
  const std::string room = avenues::testing::slurp(l_walled_room());
  const fs::path dir = fs::temp_directory_path() / ("avenues-ifc-step-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::vector<std::tuple<std::string, std::string, std::string>> cases = {
      {"#36=IFCPOLYLINE((#30,", "#36=IFCPOLYLINE((#930,", "#930 refers to no record"},
      {"#9=IFCDIRECTION(", "#9=IFCDIRE@TION(", "record #9 is not a STEP record"},
      {"#10=IFCDIRECTION(", "#9=IFCDIRECTION(", "record #9 is defined twice"}};
  for (const auto& [from, to, why] : cases) {
    std::string text = room;
    text.replace(text.find(from), from.size(), to);
    const std::string path = (dir / "broken.ifc").string();
    std::ofstream(path, std::ios::binary) << text;
    try {
      (void)read_ifc_building(path);
      ADD_FAILURE() << "read: " << to;
    } catch (const PlanError& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
      EXPECT_GT(e.where().line, 1) << e.what();
    }
  }
  fs::remove_all(dir);
}

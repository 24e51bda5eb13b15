// Tests of an OBJ model's own materials (plans/obj_materials.h): usemtl groups put on the
// faces OpenMesh kept, MTL libraries' Kd and map_Kd, and what cannot be read; an OBJ read
// from disk (plans/mesh.h, load_mesh) in its MTL's colours, as a whole scene and as a
// plan's object, in the pictures.
#include <gtest/gtest.h>

#include <string>

#include "core/srgb.h"
#include "plans/mesh.h"
#include "plans/obj_materials.h"
#include "render/raster.h"
#include "tests/avenues_run.h"
#include "tests/picture_checks.h"

namespace avenues {
namespace {

/// A unit cube as OBJ: six quads, the first before any usemtl, then "Red Paint" (a name
/// with a space) for three, "Wood" for two.
std::string cube_obj(const std::string& extra_face = "") {
  return "# a cube\nmtllib cube.mtl other lib.mtl\n"
         "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
         "f 1 4 3 2\n"
         "usemtl Red Paint\n"
         "f 5 6 7 8\nf 1 2 6 5\nf 2/1 3/2 7/3 6/4\n" +
         extra_face +
         "usemtl Wood # a comment\n"
         "f -8 -4 -1 -5\nf 4 8 7 3\n";
}

TEST(ObjMaterials, EachFaceTakesTheUsemtlInForceWhereItStands) {
  const ObjMaterialUse use = obj_material_use(cube_obj());
  EXPECT_TRUE(use.uses_materials);
  ASSERT_EQ(use.libraries, (std::vector<std::string>{"cube.mtl other lib.mtl"}));
  EXPECT_EQ(use.face_material, (std::vector<std::string>{"default", "Red Paint", "Red Paint", "Red Paint", "Wood", "Wood"}));
  // A face naming one vertex twice, or of two corners, is one OpenMesh refuses: not counted.
  const ObjMaterialUse odd = obj_material_use(cube_obj("f 1 2 1\nf 3 4\n"));
  EXPECT_EQ(odd.face_material.size(), 6u);
  EXPECT_FALSE(obj_material_use("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").uses_materials);
}

// Lenient as OBJ's own tools are: a vertex that is no coordinate costs the faces using it,
// a face naming no vertex costs itself, each said with its line; the materials of the faces
// left still go onto the right faces; text in UTF-16 reads as the same cube.
TEST(ObjReader, WhatCannotBeUsedIsDroppedAndSaidWithItsLine) {
  // Vertex 9, listed last (line 21), is bad: "3.1+e2"; one extra face uses it, another
  // names vertex 12, which there is none of.
  const std::string obj = cube_obj("f 1 2 9\nf 1 2 12\n") + "v 0 0 3.1+e2\n";
  std::vector<std::string> warnings;
  const Mesh m = read_mesh_bytes(obj, ".obj", "cube.obj", &warnings);
  EXPECT_EQ(m.triangles.size(), 12u);  // the cube's six quads, no more
  ASSERT_EQ(warnings.size(), 1u);
  for (const char* said : {"cube.obj", "3 element(s)", "line 21: '3.1+e2' is not a coordinate", "vertex is dropped",
                           "line 16: face corner '9' names a vertex that is dropped",
                           "line 17: face corner '12' names no vertex"})
    EXPECT_NE(warnings[0].find(said), std::string::npos) << said << " in " << warnings[0];
  // The dropped faces' lines are gone from what the materials are counted on too.
  ASSERT_EQ(m.material_of.size(), m.triangles.size());
  const MaterialId want[6] = {0, 1, 1, 1, 2, 2};
  for (size_t t = 0; t < m.triangles.size(); ++t) EXPECT_EQ(m.material_of[t], want[m.polygon_of[t]]) << t;
  // The stand-in for the bad vertex is a good one: the extent is the cube's.
  for (const Vec3& v : m.vertices) EXPECT_TRUE(v.z >= 0 && v.z <= 1) << v.z;

  // Nothing left: refused, naming the line that cost the last face.
  try {
    (void)read_mesh_bytes("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n", ".obj", "bad.obj");
    ADD_FAILURE() << "read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.obj: no face is left: line 4: face corner '7'"), std::string::npos)
        << e.what();
  }

  // UTF-16, either byte order, with its mark: the same cube. A character beyond ASCII is named.
  const std::string ascii = cube_obj();
  for (const bool little : {true, false}) {
    std::string wide = little ? "\xFF\xFE" : "\xFE\xFF";
    for (char ch : ascii) wide += little ? std::string{ch, '\0'} : std::string{'\0', ch};
    const Mesh w = read_mesh_bytes(wide, ".obj", "wide.obj");
    EXPECT_EQ(w.triangles, read_mesh_bytes(ascii, ".obj", "cube.obj").triangles);
    EXPECT_EQ(w.vertices.size(), 8u);
  }
  EXPECT_THROW((void)read_mesh_bytes(std::string("\xFF\xFEv\0 \0\xE9\0", 8), ".obj", "e.obj"), std::runtime_error);
  EXPECT_EQ(read_mesh_bytes("\xEF\xBB\xBF" + ascii, ".obj", "bom.obj").triangles.size(), 12u);
}

TEST(ObjMaterials, NamesGoOntoTheMeshOnlyWhenTheFacesAgree) {
  const std::string obj = cube_obj();
  Mesh m = read_mesh_bytes(obj, ".obj", "cube.obj");
  ASSERT_EQ(m.materials.size(), 3u);
  EXPECT_EQ(m.materials[0].name, "default");
  EXPECT_EQ(m.materials[1].name, "Red Paint");
  EXPECT_EQ(m.materials[2].name, "Wood");
  EXPECT_EQ(m.materials[1].colour, Material().colour);
  ASSERT_EQ(m.material_of.size(), m.triangles.size());
  ASSERT_EQ(m.triangles.size(), 12u);
  const MaterialId want[6] = {0, 1, 1, 1, 2, 2};
  for (size_t t = 0; t < m.triangles.size(); ++t) EXPECT_EQ(m.material_of[t], want[m.polygon_of[t]]) << t;

  // Counted differently (here: told so), the names cannot be placed: one material, the
  // one most faces use, and the reason.
  Mesh shifted = read_mesh_bytes(obj, ".obj", "cube.obj");
  const std::string why = name_obj_materials(shifted, obj_material_use(obj), 5);
  EXPECT_NE(why.find("OpenMesh kept 5 of its faces where its text has 6"), std::string::npos) << why;
  EXPECT_NE(why.find("material 'Red Paint'"), std::string::npos) << why;
  ASSERT_EQ(shifted.materials.size(), 1u);
  EXPECT_EQ(shifted.materials[0].name, "Red Paint");
  EXPECT_EQ(shifted.material_of, std::vector<MaterialId>(shifted.triangles.size(), 0));
}

TEST(ObjMaterials, MtlGivesEachMaterialItsKdAndMapKd) {
  const MtlLibrary lib = read_mtl(
      "# library\nKd 1 1 1\nnewmtl Red Paint\nKa 0.2 0.2 0.2\nKd 0.5 0.25 1.5\n\n"
      "newmtl Wood\nKd 0.4\nmap_Kd -s 1 1 1 wood grain.png\n"
      "newmtl Broken\nKd 0.1 green 0.3\nmap_Kd\nnewmtl Wood\nKd 0.3 0.2 0.1\n");
  ASSERT_EQ(lib.materials.size(), 4u);
  const MtlMaterial* red = lib.find("Red Paint");
  ASSERT_NE(red, nullptr);
  EXPECT_EQ(red->line, 3);
  EXPECT_EQ(*red->diffuse, (std::array<double, 3>{0.5, 0.25, 1.0}));  // clamped to [0, 1]
  EXPECT_TRUE(red->diffuse_map.empty());
  // A name defined twice: the later.
  const MtlMaterial* wood = lib.find("Wood");
  ASSERT_NE(wood, nullptr);
  EXPECT_EQ(wood->line, 13);
  EXPECT_EQ(*wood->diffuse, (std::array<double, 3>{0.3, 0.2, 0.1}));
  EXPECT_EQ(lib.materials[1].diffuse_map, "-s 1 1 1 wood grain.png");
  EXPECT_EQ(*lib.materials[1].diffuse, (std::array<double, 3>{0.4, 0.4, 0.4}));  // one number: a grey
  EXPECT_FALSE(lib.find("Broken")->diffuse);
  ASSERT_EQ(lib.problems.size(), 3u);
  EXPECT_EQ(lib.problems[0], "line 2: Kd before any newmtl");
  EXPECT_EQ(lib.problems[1], "line 11: Kd of material 'Broken' is not one or three numbers: \"0.1 green 0.3\"");
  EXPECT_EQ(lib.problems[2], "line 12: map_Kd of material 'Broken' names no image");
  // The files they name, in the order Sweet Home tries them.
  EXPECT_EQ(map_kd_candidates(lib.materials[1].diffuse_map),
            (std::vector<std::string>{"grain.png", "-s 1 1 1 wood grain.png"}));
  EXPECT_EQ(map_kd_candidates("wood.png"), (std::vector<std::string>{"wood.png"}));
  EXPECT_EQ(mtllib_candidates("cube.mtl other lib.mtl"),
            (std::vector<std::string>{"cube.mtl", "other", "lib.mtl", "cube.mtl other lib.mtl"}));
}

// --- an OBJ read from disk, in its MTL's colours ---------------------------------------

using avenues::testing::expect_pixel_shows;

/// Kd as Avenues reads it (sRGB-encoded, obj_materials.h), in linear light.
std::array<double, 3> kd(double r, double g, double b) {
  return {linear_from_srgb(r), linear_from_srgb(g), linear_from_srgb(b)};
}

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

/// A floor (z = 0, "Brick") and a wall ahead of it (y = 2, "Sea", facing −y), z-up metres.
const std::string kRoomObj =
    "mtllib room.mtl\n"
    "v -3 -2 0\nv 3 -2 0\nv 3 3 0\nv -3 3 0\n"
    "v -2 2 0\nv 2 2 0\nv 2 2 2.5\nv -2 2 2.5\n"
    "usemtl Brick\nf 1 2 3 4\n"
    "usemtl Sea\nf 5 6 7 8\n";

/// A cube 1 m wide, its base centred on the origin, z up: its front (facing −y) "Paint",
/// the rest "Label".
const std::string kCrateObj =
    "mtllib materials/crate.mtl\n"
    "v -.5 -.5 0\nv .5 -.5 0\nv .5 .5 0\nv -.5 .5 0\nv -.5 -.5 1\nv .5 -.5 1\nv .5 .5 1\nv -.5 .5 1\n"
    "usemtl Label\nf 1 4 3 2\nf 5 6 7 8\n"
    "usemtl Paint\nf 1 2 6 5\n"
    "usemtl Label\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";

class ObjColours : public avenues::testing::AvenuesRun {
 protected:
  /// A 2 x 1 PNG, its left pixel red and its right blue: mean (0.5, 0, 0.5) in linear light.
  void red_blue_png(const std::string& name) {
    Image png;
    png.resize(2, 1, 3);
    png.data = {255, 0, 0, 0, 0, 255};
    write(name, "");
    write_image(png, path(name).string());
  }
  /// `avenues view FILE` from `eye` towards `look`, 20° wide, lit from the eye: the picture.
  Image view(const std::string& file, const std::string& eye, const std::string& look, std::string* err = nullptr) {
    const avenues::testing::Outcome r = run({"view", file, "--eye", eye, "--look", look, "--fov", "20", "--size",
                                             "32x18", "--lights", "eye", "-o", path("view.ppm").string()});
    EXPECT_EQ(r.status, 0) << r.err;
    if (err) *err = r.err;
    return read_image(path("view.ppm").string());
  }
};

// An OBJ scene's usemtl groups take their MTL's Kd, in the cells' faces and the picture.
TEST_F(ObjColours, ASceneFacesShowTheirMaterialsKd) {
  const std::string obj = write("room.obj", kRoomObj);
  write("room.mtl", "newmtl Brick\nKd 0.8 0.3 0.1\nnewmtl Sea\nKa 1 1 1\nKd 0.1 0.4 0.7\n");
  std::vector<std::string> warnings;
  const Mesh m = load_mesh(obj, {}, &warnings);
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  ASSERT_EQ(m.materials.size(), 2u);
  EXPECT_EQ(m.materials[0].colour, kd(0.8, 0.3, 0.1));
  EXPECT_EQ(m.materials[1].where.str(), path("room.mtl").string() + ":3 (material 'Sea')");
  std::string err;
  expect_pixel_shows(view(obj, "0,0,1", "0,2,1", &err), kd(0.1, 0.4, 0.7), "the wall (Sea)");
  EXPECT_EQ(err.find("warning"), std::string::npos) << err;
  expect_pixel_shows(view(obj, "0,0,1", "0,0.3,0"), kd(0.8, 0.3, 0.1), "the floor (Brick)");
}

// A map_Kd image is its mean colour in linear light, found beside the MTL file that names
// it (the MTL in a folder of its own here); an image that is missing leaves Kd, with one
// warning naming it.
TEST_F(ObjColours, MapKdIsTheImagesMeanFoundBesideItsLibrary) {
  red_blue_png("materials/textures/label.png");
  const std::string obj = write("crate.obj", kCrateObj);
  write("materials/crate.mtl", "newmtl Label\nKd 1 1 1\nmap_Kd textures/label.png\nnewmtl Paint\nKd 0.9 0.6 0.2\n");
  std::vector<std::string> warnings;
  Mesh m = load_mesh(obj, {}, &warnings);
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  ASSERT_EQ(m.materials.size(), 2u);
  EXPECT_EQ(m.materials[0].name, "Label");
  for (size_t k = 0; k < 3; ++k) EXPECT_NEAR(m.materials[0].colour[k], (std::array<double, 3>{0.5, 0, 0.5})[k], 1e-12);
  EXPECT_EQ(m.materials[1].colour, kd(0.9, 0.6, 0.2));

  write("materials/crate.mtl", "newmtl Label\nKd 0.2 0.2 0.2\nmap_Kd gone.png\nnewmtl Paint\nKd 0.9 0.6 0.2\n");
  warnings.clear();
  m = load_mesh(obj, {}, &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0], "mesh " + obj + ": material 'Label': its image gone.png (map_Kd) is not at hand: its Kd colour is used instead");
  EXPECT_EQ(m.materials[0].colour, kd(0.2, 0.2, 0.2));
}

// A material no library defines is Java 3D's built-in one of that name, as in Sweet Home
// 3D's OBJ loader (many catalogue models name them with no MTL file); a library's own
// definition of such a name wins; a name neither defines keeps the default grey, said once.
TEST_F(ObjColours, JavaThreeDsBuiltInMaterialsColourWhatNoLibraryDefines) {
  // Java 3D's DefaultMaterials: flblonde Kd 0.5714 0.3283 0.0443, archwhite 0.9959 (grey).
  const std::string obj = write("crate.obj",
                                "mtllib crate.mtl\n"
                                "v -.5 -.5 0\nv .5 -.5 0\nv .5 .5 0\nv -.5 .5 0\nv -.5 -.5 1\nv .5 -.5 1\nv .5 .5 1\nv -.5 .5 1\n"
                                "usemtl flblonde\nf 1 4 3 2\nf 5 6 7 8\n"
                                "usemtl white\nf 1 2 6 5\n"
                                "usemtl archwhite\nf 2 3 7 6\n"
                                "usemtl no such paint\nf 3 4 8 7\nf 4 1 5 8\n");
  write("crate.mtl", "newmtl white\nKd 0.1 0.2 0.3\n");
  std::vector<std::string> warnings;
  const Mesh m = load_mesh(obj, {}, &warnings);
  ASSERT_EQ(m.materials.size(), 4u);
  EXPECT_EQ(m.materials[0].name, "flblonde");
  EXPECT_EQ(m.materials[0].colour, kd(0.5714, 0.3283, 0.0443));
  EXPECT_EQ(m.materials[0].where.str(), "Java 3D's built-in materials (material 'flblonde')");
  EXPECT_EQ(m.materials[1].colour, kd(0.1, 0.2, 0.3)) << "the library's 'white', not Java 3D's";
  EXPECT_EQ(m.materials[2].colour, kd(0.9959, 0.9959, 0.9959));
  EXPECT_EQ(m.materials[3].colour, Material().colour);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0], "mesh " + obj +
                             ": 1 material(s) its faces use are defined in no MTL library nor among Java 3D's built-in "
                             "materials ('no such paint'): they keep Avenues' default colour");
  // With no library at all, the same colours, and the warning says it names none.
  write("bare.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl flblonde\nf 1 2 3\n");
  warnings.clear();
  EXPECT_EQ(load_mesh(path("bare.obj").string(), {}, &warnings).materials.at(0).colour, kd(0.5714, 0.3283, 0.0443));
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  write("bare.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl Oak\nf 1 2 3\n");
  load_mesh(path("bare.obj").string(), {}, &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("defined in no MTL library (it names none: mtllib) nor among Java 3D's"), std::string::npos)
      << warnings[0];
  // In the picture: the crate's front (y = -0.5) is Java 3D's white overridden, its base
  // flblonde; seen from in front, lit from the eye.
  const std::string scene = write("room.toml",
                                  "name = 'crate room'\nunits = 'm'\n"
                                  "[[wall]]\nname = 'outside'\nthickness = 0.2\npath = [[0, 0], [5, 0], [5, 4], [0, 4], [0, 0]]\n"
                                  "[[room]]\nname = 'room'\nat = [1, 1]\n"
                                  "[[object]]\nname = 'crate'\nmesh = 'crate.obj'\nposition = [2.5, 2, 0]\n");
  expect_pixel_shows(view(scene, "2.5,0.5,0.5", "2.5,2,0.5"), kd(0.1, 0.2, 0.3), "the crate's front (its library's white)");
}

// An OBJ written on Windows names its library and images with backslashes, an image often
// by the absolute path it had there: read as slashes, else the file beside its library.
TEST_F(ObjColours, WindowsPathsInMtllibAndMapKdAreFound) {
  red_blue_png("materials/label.png");
  std::string obj = kCrateObj;
  obj.replace(obj.find("materials/crate.mtl"), 19, "materials\\crate.mtl");
  write("crate.obj", obj);
  write("materials/crate.mtl",
        "newmtl Label\nKd 1 1 1\nmap_Kd C:\\Users\\me\\textures\\label.png\nnewmtl Paint\nKd 0.9 0.6 0.2\n");
  std::vector<std::string> warnings;
  const Mesh m = load_mesh(path("crate.obj").string(), {}, &warnings);
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  ASSERT_EQ(m.materials.size(), 2u);
  for (size_t k = 0; k < 3; ++k) EXPECT_NEAR(m.materials[0].colour[k], (std::array<double, 3>{0.5, 0, 0.5})[k], 1e-12);
  EXPECT_EQ(m.materials[1].colour, kd(0.9, 0.6, 0.2));
  EXPECT_EQ(paths_beside("a/b.obj", "x\\y.mtl"), (std::vector<std::string>{"a/x\\y.mtl", "a/x/y.mtl", "a/y.mtl"}));
  EXPECT_EQ(paths_beside("b.obj", "y.mtl"), (std::vector<std::string>{"y.mtl"}));
}

// An [[object]] OBJ in a TOML plan is drawn in its MTL's colours, face by face.
TEST_F(ObjColours, APlansObjectShowsItsMaterials) {
  red_blue_png("materials/textures/label.png");
  write("crate.obj", kCrateObj);
  write("materials/crate.mtl", "newmtl Label\nmap_Kd textures/label.png\nnewmtl Paint\nKd 0.9 0.6 0.2\n");
  const std::string plan = write("room.toml",
                                 "name = 'crate room'\nunits = 'm'\n"
                                 "[[wall]]\nname = 'outside'\nthickness = 0.2\npath = [[0, 0], [5, 0], [5, 4], [0, 4], [0, 0]]\n"
                                 "[[room]]\nname = 'room'\nat = [1, 1]\n"
                                 "[[object]]\nname = 'crate'\nmesh = 'crate.obj'\nposition = [2.5, 2, 0]\n");
  // Its front (y = 1.5), then its left side (x = 2), each from in front of it.
  std::string err;
  expect_pixel_shows(view(plan, "2.5,0.5,0.5", "2.5,2,0.5", &err), kd(0.9, 0.6, 0.2), "the crate's front (Paint)");
  EXPECT_EQ(err.find("warning"), std::string::npos) << err;
  expect_pixel_shows(view(plan, "0.8,2,0.5", "2.5,2,0.5"), {0.5, 0, 0.5}, "the crate's side (Label, the image's mean)");
}

// An MTL library that is missing: one warning naming it, and the default grey; the real
// Cornell box names one it comes without.
TEST_F(ObjColours, AMissingLibraryIsOneWarningAndTheDefaultColour) {
  const std::string obj = write("room.obj", kRoomObj);
  std::vector<std::string> warnings;
  const Mesh m = load_mesh(obj, {}, &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0], "mesh " + obj + ": its material library 'room.mtl' is not at hand (" + path("room.mtl").string() +
                             "): its materials keep Avenues' default colour");
  ASSERT_EQ(m.materials.size(), 2u);
  for (const Material& mat : m.materials) EXPECT_EQ(mat.colour, Material().colour) << mat.name;
  std::string err;
  const Image pic = view(obj, "0,0,1", "0,2,1", &err);
  EXPECT_EQ(count(err, "is not at hand"), 1u) << err;
  const std::array<double, 3> grey = Material().colour;
  expect_pixel_shows(pic, grey, "the wall, in the default grey");

  // As a plan's object: the warning names the object's place in the plan and the library.
  write("crate.obj", kCrateObj);
  const std::string plan = write("room.toml",
                                 "name = 'crate room'\nunits = 'm'\n"
                                 "[[wall]]\nname = 'outside'\nthickness = 0.2\npath = [[0, 0], [5, 0], [5, 4], [0, 4], [0, 0]]\n"
                                 "[[room]]\nname = 'room'\nat = [1, 1]\n"
                                 "[[object]]\nname = 'crate'\nmesh = 'crate.obj'\nposition = [2.5, 2, 0]\n");
  view(plan, "2.5,0.5,0.5", "2.5,2,0.5", &err);
  EXPECT_EQ(count(err, "is not at hand"), 1u) << err;
  EXPECT_NE(err.find("room.toml:10:1 (object 'crate'): warning: mesh "), std::string::npos) << err;

  const std::string cornell = avenues::testing::outside_path("meshes/CornellBox-Original.obj");
  warnings.clear();
  load_mesh(cornell, {}, &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("'CornellBox-Original.mtl' is not at hand"), std::string::npos) << warnings[0];
  // The viking room's library is at hand, but its faces use a material it does not define.
  warnings.clear();
  load_mesh(avenues::testing::outside_path("meshes/viking-room/viking_room.obj"), {}, &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("1 material(s) its faces use are defined in no MTL library nor among Java 3D's "
                             "built-in materials ('Texture1')"),
            std::string::npos)
      << warnings[0];
}

}  // namespace
}  // namespace avenues

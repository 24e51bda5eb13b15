// Tests of an OBJ model's own materials (plans/obj_materials.h): usemtl groups put on the
// faces OpenMesh kept, MTL libraries' Kd and map_Kd, and what cannot be read.
#include <gtest/gtest.h>

#include <string>

#include "plans/mesh.h"
#include "plans/obj_materials.h"

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

}  // namespace
}  // namespace avenues

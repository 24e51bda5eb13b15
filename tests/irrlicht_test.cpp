// Avenues — Irrlicht's XML scenes and meshes (plans/irrlicht_scene.h), which Debian's
// Assimp refuses: placed as Irrlicht places them, the right side out, in their colours;
// broken files refused naming the line, slips passed over as Irrlicht's reader does.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <filesystem>
#include <string>
#include <vector>

#include "cells/mesh_scene.h"
#include "core/srgb.h"
#include "plans/assimp_reader.h"
#include "plans/image_colour.h"
#include "plans/irrlicht_scene.h"
#include "plans/mesh.h"
#include "tests/avenues_run.h"
#include "tests/test_files.h"

namespace fs = std::filesystem;
using namespace avenues;
using avenues::testing::slurp;

namespace {

const fs::path kModels = "/usr/share/assimp/models";
const fs::path kCorpus = fs::path(AVENUES_SOURCE_DIR) / "tests" / "fuzz" / "corpus" / "irrlicht";

/// ASCII text as Irrlicht writes its XML: UTF-16, little-endian, with its byte-order mark.
std::string utf16le(const std::string& ascii) {
  std::string out = "\xFF\xFE";
  for (char c : ascii) out += c, out += '\0';
  return out;
}

Box3 bounds(const std::vector<Vec3>& vs) {
  Box3 b;
  for (Vec3 v : vs) b.add(v);
  return b;
}

void expect_box(const Box3& b, Vec3 lo, Vec3 hi) {
  EXPECT_NEAR(b.lo.x, lo.x, 1e-9);
  EXPECT_NEAR(b.lo.y, lo.y, 1e-9);
  EXPECT_NEAR(b.lo.z, lo.z, 1e-9);
  EXPECT_NEAR(b.hi.x, hi.x, 1e-9);
  EXPECT_NEAR(b.hi.y, hi.y, 1e-9);
  EXPECT_NEAR(b.hi.z, hi.z, 1e-9);
}

const ImportedNode& node_named(const ImportedScene& s, const std::string& name) {
  for (const ImportedNode& n : s.nodes)
    if (n.name == name) return n;
  ADD_FAILURE() << "no node '" << name << "'";
  static const ImportedNode none;
  return none;
}

Vec3 normal_of(const ImportedNode& n, size_t t) {
  const Vec3 a = n.vertices[size_t(n.triangles[t][0])], b = n.vertices[size_t(n.triangles[t][1])],
             c = n.vertices[size_t(n.triangles[t][2])];
  return cross(b - a, c - a);
}

bool said(const std::vector<std::string>& warnings, const std::string& what) {
  return std::any_of(warnings.begin(), warnings.end(), [&](const std::string& w) { return w.find(what) != std::string::npos; });
}

class Irrlicht : public avenues::testing::AvenuesRun {
 protected:
  /// The corpus' scene (UTF-16, as Irrlicht writes it) and its shed, with a hidden node, a
  /// missing mesh and an OBJ named in another case than its file's, in the test's folder.
  std::string scene() {
    std::string text = slurp(kCorpus / "scene.irr");
    const std::string more = R"(	<node type="cube">
		<attributes>
			<string name="Name" value="hidden" />
			<bool name="Visible" value="false" />
		</attributes>
		<node type="sphere"><attributes><string name="Name" value="under hidden" /></attributes></node>
	</node>
	<node type="mesh">
		<attributes>
			<string name="Name" value="ghost" />
			<string name="Mesh" value="nowhere.x" />
		</attributes>
	</node>
	<node type="mesh">
		<attributes>
			<string name="Name" value="prop" />
			<string name="Mesh" value="Props\Thing.OBJ" />
		</attributes>
	</node>
</irr_scene>)";
    text.replace(text.rfind("</irr_scene>"), std::string::npos, more);
    write("shed.irrmesh", slurp(kCorpus / "shed.irrmesh"));
    write("props/thing.obj", "v 2 0 0\nv 0 1 0\nv 0 0 3\nf 1 2 3\n");
    return write("scene.irr", utf16le(text));
  }
};

}  // namespace

// Debian's Assimp refuses the cellar ("XML parse error while loading IRRMESH file"); read
// here, it stands in Avenues' axes (Irrlicht's y is z), a room seen from inside as Irrlicht
// shows it, coloured by its textures.
TEST(IrrlichtMesh, TheCellarStandsInAvenuesAxesARoomSeenFromInsideInItsTexturesColours) {
  const fs::path cellar = kModels / "IRRMesh/cellar.irrmesh";
  if (!fs::exists(cellar)) GTEST_SKIP() << "assimp-testmodels not installed (.ci/install-deps)";
  EXPECT_EQ(irrlicht_file_kind(cellar.string()), IrrlichtFile::Mesh);
  EXPECT_EQ(irrlicht_file_kind((kModels / "IRR/box.irr").string()), IrrlichtFile::Scene);
  EXPECT_EQ(irrlicht_file_kind((kModels / "Collada/duck.dae").string()), IrrlichtFile::None);
  EXPECT_EQ(assimp_importer_by_content(cellar.string()), "Avenues' Irrlicht mesh reader");
  const ImportedScene s = import_scene(cellar.string());
  EXPECT_NE(s.format.find("Irrlicht mesh"), std::string::npos) << s.format;
  ASSERT_EQ(s.nodes.size(), 2u);  // the root and the mesh
  const ImportedNode& n = s.nodes[1];
  EXPECT_EQ(n.triangles.size(), 272u);  // 260 + 12 in its two buffers
  // Its own bounding box, minEdge="-198.610886 -40.792053 -61.869953" maxEdge="129.228073 51.635353 162.326492",
  // is looser than its vertices in y; x and Irrlicht's z (Avenues' y) are met.
  const Box3 box = bounds(n.vertices);
  EXPECT_NEAR(box.lo.x, -198.610886, 1e-5);
  EXPECT_NEAR(box.hi.x, 129.228073, 1e-5);
  EXPECT_NEAR(box.lo.y, -61.869953, 1e-5);
  EXPECT_NEAR(box.hi.y, 162.326492, 1e-5);
  EXPECT_NEAR(box.lo.z, -40.792053, 1e-5);
  // A room seen from inside, as Irrlicht shows it (its material culls back faces): its
  // faces look into the room, so their volume is negative (inward) and the room is free
  // space, where an eye can stand.
  double volume = 0;
  for (size_t t = 0; t < n.triangles.size(); ++t) {
    const Vec3 a = n.vertices[size_t(n.triangles[t][0])], b = n.vertices[size_t(n.triangles[t][1])],
               c = n.vertices[size_t(n.triangles[t][2])];
    volume += dot(a, cross(b, c)) / 6;
  }
  EXPECT_LT(volume, -1e6);
  const CellComplex c = build_mesh_scene({load_mesh(cellar.string())});
  EXPECT_EQ(c.locate({-60, 60, 0}).what, Location::What::Cell);
  // Two materials, the first the mean of its ground texture.
  ASSERT_EQ(s.materials.size(), 2u);
  const std::array<double, 3> ground =
      mean_image_colour(slurp(kModels / "IRRMesh/brownground_1-1.jpg"), "brownground_1-1.jpg");
  for (int k = 0; k < 3; ++k) EXPECT_DOUBLE_EQ(s.materials[0].colour[size_t(k)], ground[size_t(k)]);
  EXPECT_TRUE(s.materials[0].coloured);
  // As one mesh (load_mesh), every triangle has its material.
  const Mesh m = load_mesh(cellar.string());
  EXPECT_EQ(m.materials.size(), 2u);
  EXPECT_EQ(m.material_of.size(), m.triangles.size());
}

// The corpus' scene: a cube placed, turned and stretched, a sphere within it placed by it,
// an .irrmesh under an empty node, an OBJ turned as Irrlicht's OBJ reader turns it, and
// what is no surface (a light, a hidden node, animators, a missing mesh) said and left out.
TEST_F(Irrlicht, ScenesPlaceTheirNodesAsIrrlichtDoesAndSayWhatTheyLeaveOut) {
  const std::string path = scene();
  EXPECT_EQ(irrlicht_file_kind(path), IrrlichtFile::Scene);
  ImportOptions o;
  const ImportedScene s = import_scene(path, o);
  EXPECT_NE(s.format.find("Irrlicht scene"), std::string::npos);
  // The cube of side 2 stretched ×3 along x, turned 90° about Irrlicht's y, at (10, 1, 5):
  // x ∈ 9..11, Irrlicht's z 2..8 (Avenues' y), Irrlicht's y 0..2 (Avenues' z).
  const ImportedNode& block = node_named(s, "block");
  expect_box(bounds(block.vertices), {9, 2, 0}, {11, 8, 2});
  EXPECT_EQ(block.triangles.size(), 12u);
  const std::array<double, 3> green{0, 1, 0};
  EXPECT_EQ(s.materials[size_t(block.triangle_material[0])].colour, green);  // the node's <materials>
  // Its faces look out: each normal points away from its middle (10, 5, 1).
  for (size_t t = 0; t < block.triangles.size(); ++t)
    EXPECT_GT(dot(normal_of(block, t), block.vertices[size_t(block.triangles[t][0])] - Vec3{10, 5, 1}), 0) << t;
  // The sphere of radius 1 at (0, 10, 0) within the cube, so stretched and turned with it.
  const ImportedNode& ball = node_named(s, "ball");
  expect_box(bounds(ball.vertices), {9, 2, 10}, {11, 8, 12});
  EXPECT_EQ(ball.triangles.size(), size_t(2 * 8 + 2 * 8 * 4));  // two caps, four bands of 8 × 6
  EXPECT_EQ(s.nodes[size_t(ball.parent)].name, "block");
  for (size_t t = 0; t < ball.triangles.size(); ++t)
    EXPECT_GT(dot(normal_of(ball, t), ball.vertices[size_t(ball.triangles[t][0])] - Vec3{10, 5, 11}), 0) << t;
  // The shed under the empty node at Irrlicht's z = 20: its floor faces up, its wall (whose
  // file's normals say +z, Irrlicht's) faces Avenues' +y; each buffer its own colour.
  const ImportedNode& shed = node_named(s, "shed");
  ASSERT_EQ(shed.triangles.size(), 3u);
  expect_box(bounds(shed.vertices), {0, 20, 0}, {4, 22, 3});
  EXPECT_GT(normal_of(shed, 0).z, 0);
  EXPECT_GT(normal_of(shed, 1).z, 0);
  EXPECT_GT(normal_of(shed, 2).y, 0);
  const auto srgb = [](int r, int g, int b) { return linear_from_srgb(std::array<double, 3>{r / 255.0, g / 255.0, b / 255.0}); };
  EXPECT_EQ(s.materials[size_t(shed.triangle_material[0])].colour, srgb(0xc0, 0x80, 0x40));
  EXPECT_EQ(s.materials[size_t(shed.triangle_material[2])].colour, srgb(0x80, 0x80, 0xff));
  // The OBJ, named Props\Thing.OBJ, is props/thing.obj: (2, 0, 0), (0, 1, 0), (0, 0, 3) read
  // with x negated as Irrlicht reads an OBJ, then into Avenues' axes; its face still faces
  // the way it did, (3, 6, 2) in its file, (−3, 2, 6) here.
  const ImportedNode& prop = node_named(s, "prop");
  ASSERT_EQ(prop.triangles.size(), 1u);
  expect_box(bounds(prop.vertices), {-2, 0, 0}, {0, 3, 1});
  const Vec3 np = normal_of(prop, 0);
  EXPECT_NEAR(np.x / np.z, -0.5, 1e-12);
  EXPECT_NEAR(np.y / np.z, 1.0 / 3, 1e-12);
  EXPECT_GT(np.z, 0);
  // What was left out, said.
  for (const ImportedNode& n : s.nodes) EXPECT_TRUE(n.name != "hidden" && n.name != "under hidden" && n.name != "ghost") << n.name;
  EXPECT_TRUE(said(s.warnings, "node 'hidden' (cube, line ")) << s.warnings.size();
  EXPECT_TRUE(said(s.warnings, "1 node(s) of type light left out"));
  EXPECT_TRUE(said(s.warnings, "1 animator(s) not played"));
  EXPECT_TRUE(said(s.warnings, "node 'ghost': its mesh 'nowhere.x' is not beside the scene: left out"));
  for (const std::string& w : s.warnings) EXPECT_EQ(w.rfind(path, 0), 0u) << w;
  // The camera is where the scene's viewer starts: at Irrlicht's (5, 1.6, −10), looking at
  // its Target (5, 1.6, 0); Fovy 72° high, 105° across a 16:9 picture. A scene built from it
  // starts there.
  ASSERT_TRUE(s.viewpoint.has_value());
  EXPECT_EQ(s.viewpoint->eye, (Vec3{5, -10, 1.6}));
  EXPECT_EQ(s.viewpoint->look, (Vec3{5, 0, 1.6}));
  EXPECT_NEAR(s.viewpoint->fov_deg, 2 * std::atan(std::tan(1.256637 / 2) * 16 / 9) * 180 / std::numbers::pi, 1e-9);
  const CellComplex c = build_mesh_scene({mesh_of_scene(s)});
  ASSERT_TRUE(c.view.has_value());
  EXPECT_EQ(c.view->eye, s.viewpoint->eye);
  // In metres as --unit says: centimetres make the block a hundredth. An up axis is no
  // option: Irrlicht's is y.
  o.axes.metres_per_unit = 0.01;
  o.axes.up = 'z';
  const ImportedScene small = import_scene(path, o);
  expect_box(bounds(node_named(small, "block").vertices), {0.09, 0.02, 0}, {0.11, 0.08, 0.02});
  EXPECT_TRUE(said(small.warnings, "up axis 'z' ignored: Irrlicht's files are y up"));
}

// Strict where the file is broken, lenient where Irrlicht is.
TEST_F(Irrlicht, BrokenFilesAreRefusedNamingTheLineAndSlipsArePassedOver) {
  auto refused = [&](const std::string& name, const std::string& text, const std::string& what) {
    const std::string p = write(name, text);
    try {
      (void)read_irrlicht(p);
      ADD_FAILURE() << name << " was read";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(p + what), std::string::npos) << e.what();
    }
  };
  // Tags that do not match, on a line with others: no guess at what was meant.
  refused("mismatch.irr", "<?xml version=\"1.0\"?>\n<irr_scene>\n<node type=\"cube\"><attributes></node>\n</irr_scene>\n",
          ":3: XML syntax error");
  refused("other.irr", "<?xml version=\"1.0\"?>\n<scene/>\n", ":2: not an Irrlicht scene or mesh: the root element is <scene>");
  refused("lamp.irr", utf16le("<irr_scene><node type=\"light\"><attributes><string name=\"Name\" value=\"lamp\"/></attributes></node></irr_scene>"),
          ": it holds no triangle Avenues can draw");
  // An attribute written value="="x.png" (as in Assimp's own scenegraphAnim.irr), alone on
  // its line: passed over, as irrXML does.
  std::string shed = slurp(kCorpus / "shed.irrmesh");
  shed.replace(shed.find("<texture name=\"Texture1\" value=\"\" />"), 36, "<texture name=\"Texture1\" value=\"=\"x.png\" />");
  // A vertex that is no number drops the triangles using it; so does an index past the end.
  shed[shed.find("4 3 0 0 0 1")] = 'x';
  shed[shed.find("0 1 2 0 2 3") + 10] = '9';
  const std::string p = write("slips.irrmesh", shed);
  const ImportedScene s = read_irrlicht(p);
  ASSERT_EQ(s.nodes.size(), 2u);
  EXPECT_EQ(s.nodes[1].triangles.size(), 1u);  // 0 1 2 of the first buffer
  EXPECT_TRUE(said(s.warnings, p + ": line 8 is not well-formed XML")) << s.warnings.front();
  EXPECT_TRUE(said(s.warnings, "buffer 2 of slips.irrmesh: 1 vertex(es) whose position is not a number (the first on line 27)"));
  EXPECT_TRUE(said(s.warnings, "buffer 1 of slips.irrmesh: 1 triangle(s) naming no usable vertex (the first on line 17)"));
}

// The command line: a cellar walked into, a scene told by its content under no extension,
// a broken one refused with status 2 naming its line.
TEST_F(Irrlicht, TheCommandLineShowsTheCellarAndRefusesABrokenSceneNamingItsLine) {
  const fs::path cellar = kModels / "IRRMesh/cellar.irrmesh";
  if (!fs::exists(cellar)) GTEST_SKIP() << "assimp-testmodels not installed (.ci/install-deps)";
  const avenues::testing::Outcome r =
      run({"view", cellar.string(), "--eye=-60,60,0", "--look=60,60,-5", "--size", "320x180", "-o", "cellar.png"});
  ASSERT_EQ(r.status, 0) << r.output();
  EXPECT_TRUE(fs::exists(path("cellar.png")));
  const std::string scene_path = scene();
  fs::copy_file(scene_path, path("a-scene"));
  const avenues::testing::Outcome told = run({"view", "a-scene", "--eye=5,10,1", "--look=10,5,1", "--size", "320x180", "-o", "scene.png"});
  ASSERT_EQ(told.status, 0) << told.output();
  EXPECT_NE(told.err.find("1 node(s) of type light left out"), std::string::npos) << told.err;
  write("broken.irr", utf16le("<?xml version=\"1.0\"?>\n<irr_scene>\n<node type=\"cube\"><attributes></node>\n</irr_scene>\n"));
  const avenues::testing::Outcome bad = run({"view", "broken.irr", "-o", "broken.png"});
  EXPECT_EQ(bad.status, 2) << bad.output();
  EXPECT_NE(bad.err.find("broken.irr:3: XML syntax error"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(path("broken.png")));
}

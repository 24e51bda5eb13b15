// Avenues — VRML97 worlds (plans/vrml_scene.h), which Debian's Assimp does not read: every
// face where the file puts it, right side out, in its colours; nodes it does not draw passed
// over; broken files refused naming the line.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "cells/build_cells.h"
#include "cells/mesh_scene.h"
#include "plans/assimp_reader.h"
#include "plans/mesh.h"
#include "plans/vrml_scene.h"
#include "tests/avenues_run.h"
#include "tests/soup_checks.h"
#include "tests/test_files.h"

namespace fs = std::filesystem;
using namespace avenues;
using avenues::testing::expect_soup_views_agree_with_rays;
using avenues::testing::slurp;
using avenues::testing::visible_triangles_missing_from_export;

namespace {

const fs::path kModels = "/usr/share/assimp/models";
const fs::path kRoom = fs::path(AVENUES_SOURCE_DIR) / "tests" / "fuzz" / "corpus" / "vrml" / "room.wrl";

Box3 bounds(const std::vector<Vec3>& vs) {
  Box3 b;
  for (Vec3 v : vs) b.add(v);
  return b;
}

Vec3 middle(const Box3& b) { return 0.5 * (b.lo + b.hi); }

double area(const ImportedNode& n) {
  double a = 0;
  for (const auto& t : n.triangles)
    a += length(cross(n.vertices[size_t(t[1])] - n.vertices[size_t(t[0])], n.vertices[size_t(t[2])] - n.vertices[size_t(t[0])])) / 2;
  return a;
}

/// Whether every triangle of n faces away from `inside`.
bool outward(const ImportedNode& n, Vec3 inside) {
  for (const auto& t : n.triangles) {
    const Vec3 a = n.vertices[size_t(t[0])], b = n.vertices[size_t(t[1])], c = n.vertices[size_t(t[2])];
    if (dot(cross(b - a, c - a), (1.0 / 3) * (a + b + c) - inside) <= 0) return false;
  }
  return true;
}

std::vector<const ImportedNode*> nodes_of(const ImportedScene& s, const std::string& geometry) {
  std::vector<const ImportedNode*> out;
  for (const ImportedNode& n : s.nodes)
    if (n.name.rfind(geometry + " (", 0) == 0) out.push_back(&n);
  return out;
}

bool said(const std::vector<std::string>& warnings, const std::string& what) {
  return std::any_of(warnings.begin(), warnings.end(), [&](const std::string& w) { return w.find(what) != std::string::npos; });
}

class Vrml : public avenues::testing::AvenuesRun {};

}  // namespace

// The corpus' room, as CAD tools export one: its walls (one of them a U round a door, not
// convex), a table turned on its Transform with a ball above it, a cylinder, a cone and a
// ground grid; a viewpoint, a light in a PROTO, a sensor and a ROUTE passed over.
TEST(VrmlWorld, ARoomStandsWhereItsTransformsPutItInItsColours) {
  EXPECT_TRUE(is_vrml(kRoom.string()));
  EXPECT_FALSE(is_vrml((fs::path(AVENUES_SOURCE_DIR) / "plans" / "jones-house.toml").string()));
  EXPECT_EQ(assimp_importer_by_content(kRoom.string()), "Avenues' VRML97 reader");
  const ImportedScene s = import_scene(kRoom.string());
  EXPECT_EQ(s.format, "VRML97 (Avenues' reader)");
  // The walls: VRML's (x, y, z) is Avenues' (x, −z, y): 4 m along x, 3 m along −y, 2.5 m up.
  const auto walls = nodes_of(s, "IndexedFaceSet");
  ASSERT_EQ(walls.size(), 1u);
  const Box3 w = bounds(walls[0]->vertices);
  EXPECT_EQ(w.lo.x, 0);
  EXPECT_EQ(w.hi.x, 4);
  EXPECT_EQ(w.lo.y, -3);
  EXPECT_EQ(w.hi.y, 0);
  EXPECT_EQ(w.lo.z, 0);
  EXPECT_EQ(w.hi.z, 2.5);
  // Floor 12 m², walls 10 + 7.5 + 7.5 m², the wall with the door 10 − 2.1 m²: the door's
  // notch is left open by the triangulation, not covered by a fan.
  EXPECT_NEAR(area(*walls[0]), 12 + 10 + 7.5 + 7.5 + 7.9, 1e-9);
  const std::array<double, 3> plaster{0.9, 0.88, 0.8};
  EXPECT_EQ(s.materials[size_t(walls[0]->triangle_material[0])].colour, plaster);
  // The table, a box of 1.2 × 0.75 × 0.8 turned 0.5 rad about y, centred over (2, −1.5)
  // with its top at 0.75 m; in the walls' material (USE); outward.
  const auto boxes = nodes_of(s, "Box");
  ASSERT_EQ(boxes.size(), 1u);
  const Box3 table = bounds(boxes[0]->vertices);
  EXPECT_NEAR(middle(table).x, 2, 1e-12);
  EXPECT_NEAR(middle(table).y, -1.5, 1e-12);
  EXPECT_NEAR(table.lo.z, 0, 1e-12);
  EXPECT_NEAR(table.hi.z, 0.75, 1e-12);
  EXPECT_GT(table.hi.x - table.lo.x, 1.2);  // turned: wider along x than its own width
  EXPECT_TRUE(outward(*boxes[0], middle(table)));
  EXPECT_EQ(s.materials[size_t(boxes[0]->triangle_material[0])].colour, plaster);
  // The ball 0.5 m above the table's middle, radius 0.1, in no material (uncoloured).
  const auto balls = nodes_of(s, "Sphere");
  ASSERT_EQ(balls.size(), 1u);
  const Box3 ball = bounds(balls[0]->vertices);
  EXPECT_NEAR(middle(ball).x, 2, 1e-12);
  EXPECT_NEAR(middle(ball).y, -1.5, 1e-12);
  EXPECT_NEAR(middle(ball).z, 0.875, 1e-12);
  EXPECT_NEAR(ball.hi.z - ball.lo.z, 0.2, 1e-12);
  EXPECT_TRUE(outward(*balls[0], middle(ball)));
  EXPECT_FALSE(balls[0]->coloured);
  // The cylinder and the cone about VRML's y, Avenues' z, through the origin; outward.
  for (const char* round : {"Cylinder", "Cone"}) {
    const auto r = nodes_of(s, round);
    ASSERT_EQ(r.size(), 1u) << round;
    const Box3 b = bounds(r[0]->vertices);
    EXPECT_NEAR(b.hi.z, -b.lo.z, 1e-12) << round;
    EXPECT_NEAR(b.hi.z - b.lo.z, std::string(round) == "Cone" ? 0.3 : 1.2, 1e-12) << round;
    // (The cone's apex triangles have no area there; the rest point out.)
    ImportedNode with_area = *r[0];
    std::erase_if(with_area.triangles, [&](const auto& t) {
      return length(cross(with_area.vertices[size_t(t[1])] - with_area.vertices[size_t(t[0])],
                          with_area.vertices[size_t(t[2])] - with_area.vertices[size_t(t[0])])) < 1e-12;
    });
    EXPECT_TRUE(outward(with_area, {0, 0, 0})) << round;
  }
  // The ground: 3 × 2 heights 2 m and 3 m apart, facing up.
  const auto grid = nodes_of(s, "ElevationGrid");
  ASSERT_EQ(grid.size(), 1u);
  EXPECT_EQ(grid[0]->triangles.size(), 4u);
  for (const auto& t : grid[0]->triangles)
    EXPECT_GT(cross(grid[0]->vertices[size_t(t[1])] - grid[0]->vertices[size_t(t[0])],
                    grid[0]->vertices[size_t(t[2])] - grid[0]->vertices[size_t(t[0])]).z, 0);
  const Box3 ground = bounds(grid[0]->vertices);
  EXPECT_EQ(ground.hi.x, 4);
  EXPECT_EQ(ground.lo.y, -3);
  EXPECT_NEAR(ground.hi.z, 0.1, 1e-12);
  // The PROTO Lamp's instance is its body's PointLight: passed over, as lights are.
  EXPECT_FALSE(said(s.warnings, "Lamp")) << s.warnings.size();
  // --unit and --up: millimetres make it a thousandth; z up leaves its axes as written.
  ImportOptions o;
  o.axes.metres_per_unit = 0.001;
  o.axes.up = 'z';
  const Box3 small = bounds(nodes_of(read_vrml(kRoom.string(), o), "IndexedFaceSet")[0]->vertices);
  EXPECT_NEAR(small.hi.y, 0.0025, 1e-15);
  EXPECT_NEAR(small.hi.z, 0.003, 1e-15);
  // As one mesh, in cells: sound, every face someone could see kept, views agreeing with
  // rays, and an eye in the room in free space.
  const std::vector<Mesh> meshes{load_mesh(kRoom.string())};
  const CellComplex c = build_mesh_scene(meshes);
  ASSERT_EQ(cells_are_valid(c), "");
  EXPECT_EQ(visible_triangles_missing_from_export(c, meshes), 0);
  expect_soup_views_agree_with_rays(c, 8, 2026, 96, 64, 8);
  EXPECT_EQ(c.locate({1, -1, 1.6}).what, Location::What::Cell);
  // The first Viewpoint, where a VRML browser starts, is where the scene starts: at VRML's
  // (2, 1.6, 5) looking along −z; 45° high, 72.7° across a 16:9 picture.
  ASSERT_TRUE(s.viewpoint.has_value());
  EXPECT_EQ(s.viewpoint->eye, (Vec3{2, -5, 1.6}));
  EXPECT_EQ(s.viewpoint->look, (Vec3{2, -4, 1.6}));
  EXPECT_NEAR(s.viewpoint->fov_deg, 72.7, 0.05);
  ASSERT_TRUE(c.view.has_value());
  EXPECT_EQ(c.view->eye, s.viewpoint->eye);
  EXPECT_EQ(c.view->look, s.viewpoint->look);
}

// Gzipped (.wrz), inlined worlds placed by the Transform round the Inline, and an Inline
// that names the world holding it, said and left out.
TEST_F(Vrml, GzippedAndInlinedWorldsAreRead) {
  const std::string room = write("room.wrl", slurp(kRoom));
  ASSERT_EQ(run_argv({"gzip", "-k", "-n", room}).status, 0);
  fs::rename(path("room.wrl.gz"), path("room.wrz"));
  EXPECT_TRUE(is_vrml(path("room.wrz").string()));
  const ImportedScene plain = read_vrml(room), gz = read_vrml(path("room.wrz").string());
  ASSERT_EQ(plain.nodes.size(), gz.nodes.size());
  for (size_t k = 0; k < plain.nodes.size(); ++k) EXPECT_EQ(plain.nodes[k].vertices, gz.nodes[k].vertices) << k;
  write("shed/shed.wrl", "#VRML V2.0 utf8\nShape { geometry Box { size 2 2 2 } }\nInline { url \"../site.wrl\" }\n");
  const std::string site =
      write("site.wrl", "#VRML V2.0 utf8\nTransform { translation 10 0 0 children [ Inline { url [ \"http://x/y.wrl\" \"shed/shed.wrl\" ] } ] }\n");
  const ImportedScene s = read_vrml(site);
  const auto boxes = nodes_of(s, "Box");
  ASSERT_EQ(boxes.size(), 1u);
  const Box3 b = bounds(boxes[0]->vertices);
  EXPECT_EQ(b.lo.x, 9);
  EXPECT_EQ(b.hi.x, 11);
  EXPECT_TRUE(said(s.warnings, "Inline '../site.wrl' (line 3) names a world that holds it: left out"));
}

/// The volume a node's triangles bound, positive where they face out (the divergence
/// theorem, about its first corner).
double signed_volume(const ImportedNode& n) {
  double v = 0;
  const Vec3 o = n.vertices.front();
  for (const auto& t : n.triangles)
    v += dot(n.vertices[size_t(t[0])] - o, cross(n.vertices[size_t(t[1])] - o, n.vertices[size_t(t[2])] - o)) / 6;
  return v;
}

/// Whether every edge of the node's triangles is walked once each way (a closed surface,
/// consistently turned), corners compared by place.
bool closed_surface(const ImportedNode& n) {
  std::map<std::pair<std::array<double, 3>, std::array<double, 3>>, int> walked;
  auto at = [&](int i) { const Vec3 p = n.vertices[size_t(i)]; return std::array<double, 3>{p.x, p.y, p.z}; };
  for (const auto& t : n.triangles)
    for (int k = 0; k < 3; ++k) ++walked[{at(t[size_t(k)]), at(t[size_t((k + 1) % 3)])}];
  for (const auto& [edge, count] : walked) {
    const auto back = walked.find({edge.second, edge.first});
    if (count != 1 || back == walked.end() || back->second != 1) return false;
  }
  return true;
}

// Extrusions, swept as VRML97 defines them (ISO/IEC 14772-1, 6.18): the default is a box
// 2 × 1 × 2 standing on the origin; a pipe round a bend (its section at the bend in the
// plane halfway between the legs), a cross-section turned the other
// way, a spine along x and a cone tapered to a point are closed and face out; an open
// cross-section has sides only.
TEST_F(Vrml, ExtrusionsAreSweptAsVrmlDefinesThem) {
  const std::string world = write("extrusions.wrl", R"(#VRML V2.0 utf8
Shape { geometry Extrusion { } }
Transform { translation 10 0 0 children Shape { geometry Extrusion {
  crossSection [ 1 0, 0.7071 -0.7071, 0 -1, -0.7071 -0.7071, -1 0, -0.7071 0.7071, 0 1, 0.7071 0.7071, 1 0 ]
  scale 0.1 0.1 spine [ 0 0 0, 0 2 0, 2 2 0 ] } } }
Transform { translation 20 0 0 children Shape { geometry Extrusion {
  crossSection [ 1 1, -1 1, -1 -1, 1 -1, 1 1 ] } } }
Transform { translation 30 0 0 children Shape { geometry Extrusion { spine [ 0 0 0, 3 0 0 ] } } }
Transform { translation 40 0 0 children Shape { geometry Extrusion { scale [ 1 1, 0 0 ] } } }
Transform { translation 50 0 0 children Shape { geometry Extrusion { crossSection [ 1 0, 0 1, -1 0 ] } } }
)");
  const ImportedScene s = read_vrml(world);
  const auto e = nodes_of(s, "Extrusion");
  ASSERT_EQ(e.size(), 6u);
  for (const std::string& w : s.warnings) EXPECT_EQ(w.find("Extrusion"), std::string::npos) << w;
  // The box: VRML's x −1..1, y 0..1, z −1..1 is Avenues' x −1..1, y −1..1, z 0..1.
  const Box3 box = bounds(e[0]->vertices);
  EXPECT_EQ(box.lo, (Vec3{-1, -1, 0}));
  EXPECT_EQ(box.hi, (Vec3{1, 1, 1}));
  EXPECT_EQ(e[0]->triangles.size(), 12u);
  EXPECT_TRUE(outward(*e[0], {0, 0, 0.5}));
  EXPECT_NEAR(signed_volume(*e[0]), 4, 1e-12);
  // Every closed one closed and facing out; the open one's sides only (2 of them, 4 triangles).
  for (const size_t k : {0u, 1u, 2u, 3u, 4u}) {
    EXPECT_TRUE(closed_surface(*e[k])) << k;
    EXPECT_GT(signed_volume(*e[k]), 0) << k;
  }
  EXPECT_NEAR(signed_volume(*e[2]), 4, 1e-12);
  EXPECT_NEAR(signed_volume(*e[4]), 4.0 / 3, 1e-12);  // a pyramid: a third of its box
  EXPECT_EQ(e[5]->triangles.size(), 4u);
  // The pipe: 0.1 m across, up 2 m then along x 2 m; its bend keeps its cross-section whole.
  const Box3 pipe = bounds(e[1]->vertices);
  EXPECT_NEAR(pipe.lo.x, 10 - 0.1, 1e-9);
  EXPECT_NEAR(pipe.hi.x, 12, 1e-9);
  // It starts flat on the ground and ends upright, its section 0.1 about the spine's height.
  EXPECT_NEAR(pipe.lo.z, 0, 1e-12);
  EXPECT_NEAR(pipe.hi.z, 2.1, 1e-9);
  // The spine along x: the section's plane turned as +y turns onto +x.
  const Box3 along = bounds(e[3]->vertices);
  EXPECT_NEAR(along.lo.x, 30, 1e-12);
  EXPECT_NEAR(along.hi.x, 33, 1e-12);
  EXPECT_NEAR(along.hi.z - along.lo.z, 2, 1e-12);
  // As one mesh, in cells: the closed ones are solids, every face someone could see kept.
  const std::vector<Mesh> meshes{load_mesh(world)};
  const CellComplex c = build_mesh_scene(meshes);
  ASSERT_EQ(cells_are_valid(c), "");
  EXPECT_EQ(visible_triangles_missing_from_export(c, meshes), 0);
  EXPECT_EQ(c.locate({0, 0, 0.5}).what, Location::What::Solid);
  expect_soup_views_agree_with_rays(c, 8, 2026, 96, 64, 8);
}

// PROTOs, as CAD exports and hand-written worlds use them: each instance is its body's first
// node, every IS given the instance's value or the PROTO's default; instances within a
// PROTO's body, a node USEd twice in a body, a DEF in a body not seen outside it. An
// EXTERNPROTO's instances (their body elsewhere) are left out with a warning naming them.
TEST_F(Vrml, ProtoInstancesAreExpanded) {
  const std::string world = write("protos.wrl", R"(#VRML V2.0 utf8
PROTO Post [ field SFFloat height 2  exposedField SFColor colour 0.5 0.5 0.5  eventIn SFBool set_lit ] {
  DEF POST Transform { translation 0 1 0 children [
    Shape { appearance Appearance { material Material { diffuseColor IS colour } }
            geometry Box { size 0.2 2 0.2 } } ] }
  PointLight { }
}
PROTO Fence [ field SFColor colour 1 0 0  field SFVec3f at 0 0 0 ] {
  Transform { translation IS at children [ Post { colour IS colour }  Transform { translation 2 0 0 children Post { colour IS colour } } ] }
}
EXTERNPROTO Gate [ field SFColor colour ] "gate.wrl#Gate"
Post { }
Transform { translation 10 0 0 children Post { colour 0 0 1 } }
Fence { at 20 0 0 colour 0 1 0 }
Fence { at 30 0 0 }
Gate { colour 1 1 1 }
)");
  const ImportedScene s = read_vrml(world);
  const auto posts = nodes_of(s, "Box");
  ASSERT_EQ(posts.size(), 6u);
  // Each post 0.2 across, 2 high, standing on the ground where its instance puts it, in the
  // colour the instance gives (or the PROTO's default).
  const double xs[] = {0, 10, 20, 22, 30, 32};
  const std::array<double, 3> colours[] = {{0.5, 0.5, 0.5}, {0, 0, 1}, {0, 1, 0}, {0, 1, 0}, {1, 0, 0}, {1, 0, 0}};
  for (size_t k = 0; k < posts.size(); ++k) {
    const Box3 b = bounds(posts[k]->vertices);
    EXPECT_NEAR(middle(b).x, xs[k], 1e-12) << k;
    EXPECT_NEAR(b.lo.z, 0, 1e-12) << k;
    EXPECT_NEAR(b.hi.z, 2, 1e-12) << k;
    EXPECT_TRUE(posts[k]->coloured) << k;
    EXPECT_EQ(posts[k]->colour, colours[k]) << k;
  }
  EXPECT_TRUE(said(s.warnings, "1 instance(s) of EXTERNPROTO Gate (its body is in another file, not read) left out"));
  // In cells: sound, every post's faces kept, views agreeing with rays.
  const std::vector<Mesh> meshes{load_mesh(world)};
  const CellComplex c = build_mesh_scene(meshes);
  ASSERT_EQ(cells_are_valid(c), "");
  EXPECT_EQ(visible_triangles_missing_from_export(c, meshes), 0);
  expect_soup_views_agree_with_rays(c, 8, 2027, 96, 64, 8);
  // A DEF in a PROTO's body is the body's own.
  const std::string leaky = write("leaky.wrl", "#VRML V2.0 utf8\nPROTO P [ ] { DEF INNER Group { } }\nP { }\nUSE INNER\n");
  try {
    (void)read_vrml(leaky);
    ADD_FAILURE() << "a USE of a name DEFined only in a PROTO's body was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("leaky.wrl:4"), std::string::npos) << e.what();
  }
  // Each PROTO holding two instances of the one before: refused past two million nodes.
  std::string doubling = "#VRML V2.0 utf8\nPROTO P0 [ field SFColor c 1 1 1 ] { Shape { appearance Appearance { material Material { diffuseColor IS c } } geometry Box { } } }\n";
  for (int k = 1; k <= 24; ++k)
    doubling += "PROTO P" + std::to_string(k) + " [ field SFColor c 1 1 1 ] { Group { children [ P" + std::to_string(k - 1) +
                " { c IS c } P" + std::to_string(k - 1) + " { c IS c } ] } }\n";
  doubling += "P24 { }\n";
  try {
    (void)read_vrml(write("doubling.wrl", doubling));
    ADD_FAILURE() << "2^24 nodes from 27 lines were read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("more than 2000000"), std::string::npos) << e.what();
  }
}

// Faces in their own colours, as CAD exports give them: a Color node with a colour a face
// (colorPerVertex FALSE, by colorIndex or in order) or a corner (TRUE: the face takes its
// corners' mean), standing for the Material's diffuseColor; an ElevationGrid's likewise.
TEST_F(Vrml, FacesTakeTheirColoursFromAColorNode) {
  const std::string world = write("colours.wrl", R"(#VRML V2.0 utf8
Shape { appearance Appearance { material Material { diffuseColor 0.5 0.5 0.5 } }
  geometry IndexedFaceSet { coord DEF C Coordinate { point [ 0 0 0, 1 0 0, 1 1 0, 0 1 0, 2 0 0, 2 1 0 ] }
    coordIndex [ 0 1 2 3 -1 1 4 5 2 -1 ]
    color Color { color [ 1 0 0, 0 1 0, 0 0 1 ] } colorPerVertex FALSE colorIndex [ 2 0 ] } }
Shape { geometry IndexedFaceSet { coord USE C coordIndex [ 0 1 2 -1, 0 2 3 -1 ]
    color Color { color [ 1 0 0, 0 1 0 ] } colorPerVertex FALSE } }
Shape { geometry IndexedFaceSet { coord USE C coordIndex [ 0 1 2 3 -1 ]
    color Color { color [ 1 0 0, 0 0 1 ] } colorIndex [ 0 0 1 1 -1 ] } }
)");
  const ImportedScene s = read_vrml(world);
  const auto sets = nodes_of(s, "IndexedFaceSet");
  ASSERT_EQ(sets.size(), 3u);
  auto colour_of_triangle = [&](const ImportedNode& n, size_t t) {
    const int m = n.triangle_material.at(t);
    EXPECT_GE(m, 0);
    return s.materials.at(size_t(m)).colour;
  };
  using C = std::array<double, 3>;
  // By colorIndex, a colour a face: the first quad blue, the second red (two triangles each).
  ASSERT_EQ(sets[0]->triangles.size(), 4u);
  EXPECT_EQ(colour_of_triangle(*sets[0], 0), (C{0, 0, 1}));
  EXPECT_EQ(colour_of_triangle(*sets[0], 1), (C{0, 0, 1}));
  EXPECT_EQ(colour_of_triangle(*sets[0], 2), (C{1, 0, 0}));
  EXPECT_EQ(colour_of_triangle(*sets[0], 3), (C{1, 0, 0}));
  // In order, with no Material at all.
  EXPECT_EQ(colour_of_triangle(*sets[1], 0), (C{1, 0, 0}));
  EXPECT_EQ(colour_of_triangle(*sets[1], 1), (C{0, 1, 0}));
  EXPECT_TRUE(sets[1]->coloured);
  // A colour a corner: half red, half blue.
  EXPECT_EQ(colour_of_triangle(*sets[2], 0), (C{0.5, 0, 0.5}));
  // An ElevationGrid's colours: one a square, or one a point (the square their mean).
  const std::string grids = write("grids.wrl", R"(#VRML V2.0 utf8
Shape { geometry ElevationGrid { xDimension 3 zDimension 2 height [ 0 0 0, 0 0 0 ]
  color Color { color [ 1 0 0, 0 0 1 ] } colorPerVertex FALSE } }
Shape { geometry ElevationGrid { xDimension 2 zDimension 2 height [ 0 0, 0 0 ]
  color Color { color [ 1 0 0, 1 0 0, 0 1 0, 0 1 0 ] } } }
)");
  const ImportedScene g = read_vrml(grids);
  const auto eg = nodes_of(g, "ElevationGrid");
  ASSERT_EQ(eg.size(), 2u);
  auto grid_colour = [&](const ImportedNode& n, size_t t) { return g.materials.at(size_t(n.triangle_material.at(t))).colour; };
  ASSERT_EQ(eg[0]->triangles.size(), 4u);
  EXPECT_EQ(grid_colour(*eg[0], 0), (C{1, 0, 0}));
  EXPECT_EQ(grid_colour(*eg[0], 1), (C{1, 0, 0}));
  EXPECT_EQ(grid_colour(*eg[0], 2), (C{0, 0, 1}));
  EXPECT_EQ(grid_colour(*eg[1], 0), (C{0.5, 0.5, 0}));
}

// X3D's triangle and quad sets, as X3D exporters write meshes: the same unit square (two
// triangles, one quad, a strip, a fan), in order or by index, each facing +y (VRML's up:
// Avenues' +z) and covering the square once; a colour a face.
TEST_F(Vrml, X3dTriangleAndQuadSetsAreDrawn) {
  const std::string world = write("sets.x3dv", R"(#X3D V3.0 utf8
PROFILE Interchange
Shape { geometry TriangleSet { coord Coordinate { point [ 0 0 0, 0 0 1, 1 0 1, 0 0 0, 1 0 1, 1 0 0 ] } } }
Shape { geometry IndexedTriangleSet { index [ 0 1 2 0 2 3 ] coord DEF Q Coordinate { point [ 0 0 0, 0 0 1, 1 0 1, 1 0 0 ] }
  color Color { color [ 1 0 0, 0 1 0 ] } colorPerVertex FALSE } }
Shape { geometry QuadSet { coord USE Q } }
Shape { geometry IndexedQuadSet { index [ 0 1 2 3 ] coord USE Q } }
Shape { geometry TriangleStripSet { stripCount [ 4 ] coord Coordinate { point [ 0 0 0, 0 0 1, 1 0 0, 1 0 1 ] } } }
Shape { geometry IndexedTriangleStripSet { index [ 0 1 3 2 -1 ] coord USE Q } }
Shape { geometry TriangleFanSet { fanCount [ 4 ] coord USE Q } }
Shape { geometry IndexedTriangleFanSet { index [ 0 1 2 3 -1 ] coord USE Q } }
)");
  const ImportedScene s = read_vrml(world);
  for (const std::string& w : s.warnings) EXPECT_EQ(w.find("Set"), std::string::npos) << w;
  const char* kinds[] = {"TriangleSet", "IndexedTriangleSet", "QuadSet", "IndexedQuadSet", "TriangleStripSet",
                         "IndexedTriangleStripSet", "TriangleFanSet", "IndexedTriangleFanSet"};
  for (const char* kind : kinds) {
    const auto n = nodes_of(s, kind);
    ASSERT_EQ(n.size(), 1u) << kind;
    EXPECT_EQ(n[0]->triangles.size(), 2u) << kind;
    EXPECT_NEAR(area(*n[0]), 1, 1e-12) << kind;
    for (const auto& t : n[0]->triangles)
      EXPECT_GT(cross(n[0]->vertices[size_t(t[1])] - n[0]->vertices[size_t(t[0])],
                      n[0]->vertices[size_t(t[2])] - n[0]->vertices[size_t(t[0])]).z, 0) << kind;
  }
  const auto coloured = nodes_of(s, "IndexedTriangleSet");
  EXPECT_EQ(s.materials.at(size_t(coloured[0]->triangle_material.at(0))).colour, (std::array<double, 3>{1, 0, 0}));
  EXPECT_EQ(s.materials.at(size_t(coloured[0]->triangle_material.at(1))).colour, (std::array<double, 3>{0, 1, 0}));
}

// What is not VRML97 and what is broken is refused naming the file and line.
TEST_F(Vrml, BrokenWorldsAreRefusedNamingTheLine) {
  auto refused = [&](const std::string& name, const std::string& text, const std::string& what) {
    const std::string p = write(name, text);
    try {
      (void)read_vrml(p);
      ADD_FAILURE() << name << " was read";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(p + what), std::string::npos) << e.what();
    }
  };
  refused("old.wrl", "#VRML V1.0 ascii\nSeparator { Cube { } }\n", ":1: VRML 1.0 is not read");
  refused("open.wrl", "#VRML V2.0 utf8\n\nShape {\n  geometry Box { size 1 1 1 }\n", ":3: node Shape begun here is never closed");
  refused("use.wrl", "#VRML V2.0 utf8\nShape { appearance USE Paint geometry Box { } }\n", ":2: USE Paint: no node before it is DEF Paint");
  refused("number.wrl", "#VRML V2.0 utf8\nShape { geometry Box { size 1 1.5e 1 } }\n", ":2: '1.5e 1 } }");
  refused("empty.wrl", "#VRML V2.0 utf8\nViewpoint { position 0 1.6 5 }\n", ": it draws no triangle Avenues can use");
  std::string deep = "#VRML V2.0 utf8\n";
  for (int k = 0; k < 1100; ++k) deep += "Group { children [\n";
  refused("deep.wrl", deep, ":1003: nodes nested more than 1000 deep");
  // Each group USEs the one before twice: 2^40 nodes in 40 lines.
  std::string doubling = "#VRML V2.0 utf8\nDEF G0 WorldInfo { }\n";
  for (int k = 1; k <= 40; ++k)
    doubling += "DEF G" + std::to_string(k) + " Group { children [ USE G" + std::to_string(k - 1) + " USE G" +
                std::to_string(k - 1) + " ] }\n";
  refused("doubling.wrl", doubling, ": its nodes, each USE counted again, number more than 2000000");
}

// The command line: a world opens and is walked into; a broken one exits 2 naming its line.
TEST_F(Vrml, TheCommandLineOpensAWorldAndRefusesABrokenOne) {
  const avenues::testing::Outcome r =
      run({"view", kRoom.string(), "--eye=1,-1,1.6", "--look=3,-2,1.2", "--size", "320x180", "-o", "room.png"});
  ASSERT_EQ(r.status, 0) << r.output();
  EXPECT_TRUE(fs::exists(path("room.png")));
  write("noext", slurp(kRoom));  // told by its first line
  EXPECT_EQ(run({"cells", "noext"}).status, 0);
  write("broken.wrl", "#VRML V2.0 utf8\nShape { geometry IndexedFaceSet { coord Coordinate { point [ 0 0 0 ] }\n");
  const avenues::testing::Outcome bad = run({"view", "broken.wrl", "-o", "broken.png"});
  EXPECT_EQ(bad.status, 2) << bad.output();
  EXPECT_NE(bad.err.find("broken.wrl:2: node IndexedFaceSet begun here is never closed"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(path("broken.png")));
}

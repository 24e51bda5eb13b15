// Tests of cells/mesh_scene.h: meshes as whole scenes, their free space cut into convex
// cells by CGAL's Nef polyhedra (MeshSceneMethod::Nef, the former path; the soup BSP that
// is now the default has its own tests, soup_bsp_test.cpp), checked by cells_are_valid,
// by volume, and by the ray-casting oracle on random views.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <stdexcept>

#include "cells/build_cells.h"
#include "cells/mesh_scene.h"
#include "ray_oracle.h"
#include "visibility/visible_set.h"
#include "tests/test_files.h"
#include "tests/test_meshes.h"
#include "tests/test_plans.h"

using namespace avenues;
using avenues::testing::box_volume;
using avenues::testing::free_volume;
using avenues::testing::check_visible_set;
using avenues::testing::OracleResult;

namespace {

/// The Nef path's parameters (margin etc. as given).
MeshSceneParams nef(MeshSceneParams p = {}) {
  p.method = MeshSceneMethod::Nef;
  return p;
}

std::string scene_path(const std::string& name) {
  return (std::filesystem::path(AVENUES_SOURCE_DIR) / "plans" / "scenes" / name).string();
}

/// A box mesh `size` large with its base centred on `at`.
Mesh box_at(Vec3 size, Vec3 at) {
  Mesh m = box_mesh(size);
  for (Vec3& v : m.vertices) v = v + at;
  return m;
}

/// A box as a general convex cell (Cell::prism == false), all its faces opaque.
Cell box_cell(Vec3 lo, Vec3 hi) {
  Cell c;
  c.kind = CellKind::Outside;
  c.prism = false;
  c.footprint = {{lo.x, lo.y}, {hi.x, lo.y}, {hi.x, hi.y}, {lo.x, hi.y}};
  c.z0 = lo.z, c.z1 = hi.z;
  auto at = [&](int k) { return Vec3{k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z}; };
  // Corners counter-clockwise seen from inside, and the outward normal of each face.
  const int quads[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
  const Vec3 normals[6] = {{0, 0, -1}, {0, 0, 1}, {0, -1, 0}, {0, 1, 0}, {-1, 0, 0}, {1, 0, 0}};
  for (int q = 0; q < 6; ++q) {
    Face f;
    for (int k : quads[q]) f.poly.push_back(at(k));
    f.plane = {normals[q], -dot(normals[q], f.poly[0])};
    f.opaque.push_back({f.poly, -1});
    c.faces.push_back(f);
  }
  return c;
}

using avenues::testing::random_point_in;  // strictly inside a cell

/// Random views from random cells, each checked against ray casting and the exact kernel.
void expect_views_agree_with_rays(const CellComplex& c, int views, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<size_t> pick(0, c.cells.size() - 1);
  std::uniform_real_distribution<double> yaw(0, 360), pitch(-60, 60), fov(40, 110);
  for (int v = 0; v < views; ++v) {
    const CellId cell = CellId(pick(rng));
    const Vec3 eye = random_point_in(c.cells[size_t(cell)], rng);
    const Location loc = c.locate(eye);
    ASSERT_EQ(loc.what, Location::What::Cell) << "view " << v;
    ASSERT_TRUE(c.cells[size_t(loc.cell)].contains(eye, 1e-9)) << "view " << v;
    const double y = yaw(rng), p = pitch(rng), f = fov(rng);
    Camera cam = Camera::yaw_pitch(eye, y, p, f, 96, 64);
    SCOPED_TRACE("view " + std::to_string(v) + ": eye " + std::to_string(eye.x) + "," + std::to_string(eye.y) + "," +
                 std::to_string(eye.z) + " yaw " + std::to_string(y) + " pitch " + std::to_string(p) + " fov " +
                 std::to_string(f));
    VisibleSet vs = find_visible(c, cam, loc.cell, Kernel::Double);
    OracleResult r = check_visible_set(c, cam, vs, 1);
    EXPECT_EQ(r.missing, 0);
    EXPECT_EQ(r.extra, 0);
    EXPECT_EQ(find_visible(c, cam, loc.cell, Kernel::Exact).cells, vs.cells);
  }
}

}  // namespace

TEST(MeshScene, ACubeInABoxGivesValidConvexCellsFillingTheFreeSpace) {
  const CellComplex c = build_mesh_scene({box_at({1, 1, 1}, {0, 0, 0})}, nef());
  EXPECT_EQ(cells_are_valid(c), "");
  EXPECT_TRUE(c.warnings.empty());
  // The far box is the cube's bounds grown by the margin (2 m).
  EXPECT_DOUBLE_EQ(c.far_box.lo.x, -2.5);
  EXPECT_DOUBLE_EQ(c.far_box.hi.z, 3);
  ASSERT_GE(c.cells.size(), 2u);  // free space around a cube is not convex
  for (const Cell& cell : c.cells) {
    EXPECT_FALSE(cell.prism);
    EXPECT_EQ(cell.kind, CellKind::Outside);
  }
  EXPECT_NEAR(free_volume(c), box_volume(c.far_box) - 1, 1e-9 * box_volume(c.far_box));
  // Every cell reaches every other through portals.
  std::vector<int> seen(c.cells.size(), 0);
  std::vector<CellId> stack{0};
  seen[0] = 1;
  while (!stack.empty()) {
    CellId k = stack.back();
    stack.pop_back();
    for (PortalId p : c.cells[size_t(k)].portals)
      if (!seen[size_t(c.portals[size_t(p)].other(k))]++) stack.push_back(c.portals[size_t(p)].other(k));
  }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 0), 0);
  // The cube's twelve edges are its real lines, all convex, each on some cell.
  ASSERT_EQ(c.lines.size(), 12u);
  std::vector<double> covered(c.lines.size(), 0);
  for (const Cell& cell : c.cells)
    for (const CellLine& l : cell.lines) covered[size_t(l.line)] = std::max(covered[size_t(l.line)], l.t1 - l.t0);
  for (size_t i = 0; i < c.lines.size(); ++i) {
    EXPECT_EQ(c.lines[i].kind, LineKind::Convex);
    EXPECT_NEAR(length(c.lines[i].b - c.lines[i].a), 1, 1e-12);
    EXPECT_GT(covered[i], 0.0) << "line " << i;
  }
  // Inside the cube is solid, named after the mesh.
  const Location in = c.locate({0, 0, 0.5});
  EXPECT_EQ(in.what, Location::What::Solid);
  EXPECT_NE(in.solid.find("box"), std::string::npos) << in.solid;
}

TEST(MeshScene, RandomViewsAroundACubeAgreeWithRayCasting) {
  const CellComplex c = build_mesh_scene({box_at({1, 1, 1}, {0, 0, 0})}, nef());
  ASSERT_EQ(cells_are_valid(c), "");
  expect_views_agree_with_rays(c, 16, 1971);
}

TEST(MeshScene, RandomViewsBetweenTwoBoxesInARoomAgreeWithRayCasting) {
  // A table and a cupboard; the far box, 0.5 m beyond them, stands for the room's walls.
  MeshSceneParams params;
  params.margin = 0.5;
  const CellComplex c = build_mesh_scene({box_at({1.6, 0.9, 0.75}, {0, 0, 0}), box_at({0.6, 1.2, 2.0}, {2.2, 0.8, 0})}, nef(params));
  ASSERT_EQ(cells_are_valid(c), "");
  EXPECT_NEAR(free_volume(c), box_volume(c.far_box) - 1.6 * 0.9 * 0.75 - 0.6 * 1.2 * 2.0, 1e-9 * box_volume(c.far_box));
  EXPECT_EQ(c.lines.size(), 24u);
  expect_views_agree_with_rays(c, 16, 1981);
}

TEST(MeshScene, PaperScenesGiveValidCellsAndAgreeWithRayCasting) {
  // Every bundled scene but the ripple torus, whose 225 crossing plates take minutes to
  // decompose. Closed solids leave the box minus their volume; the open ones (the cottage's
  // sheets, the bottomless cubes) are repaired with one warning per component. (The
  // cottage's walls, roof and chimney touch in T-junctions, which the reader joins: they
  // are one component of 11 polygons, not three.)
  struct Scene {
    const char* name;
    size_t warnings;
  };
  for (const Scene& s : {Scene{"wylie-tetrahedron.off", 0}, Scene{"wylie-cube.off", 0}, Scene{"crow-object.off", 0},
                         Scene{"torus.off", 0}, Scene{"cubes.off", 32}, Scene{"cottage.off", 7}}) {
    SCOPED_TRACE(s.name);
    const CellComplex c = read_mesh_scene(scene_path(s.name), nef());
    ASSERT_EQ(cells_are_valid(c), "");
    EXPECT_EQ(c.warnings.size(), s.warnings);
    EXPECT_EQ(c.plan_name, std::filesystem::path(s.name).stem().string());
    EXPECT_TRUE(std::any_of(c.timings.begin(), c.timings.end(), [](const StageTime& t) { return t.stage == "decompose"; }));
    if (s.warnings == 0) {
      const Mesh m = load_mesh(scene_path(s.name));
      double solid = 0;
      for (const auto& t : m.triangles)
        solid += dot(m.vertices[size_t(t[0])], cross(m.vertices[size_t(t[1])], m.vertices[size_t(t[2])])) / 6;
      EXPECT_GT(solid, 0);
      EXPECT_NEAR(free_volume(c), box_volume(c.far_box) - solid, 1e-9 * box_volume(c.far_box));
    }
    // The first view stands in free space.
    ASSERT_TRUE(c.view.has_value());
    EXPECT_EQ(c.locate(c.view->eye).what, Location::What::Cell);
    expect_views_agree_with_rays(c, 6, 7);
  }
}

TEST(MeshScene, TheValidatorChecksGeneralConvexCells) {
  CellComplex c;
  c.far_box.lo = {-5, -5, -5}, c.far_box.hi = {5, 5, 5};
  c.cells = {box_cell({0, 0, 0}, {1, 1, 1}), box_cell({1, 0, 0}, {2, 1, 1})};  // touching, not overlapping
  ASSERT_EQ(cells_are_valid(c), "");
  CellComplex overlap = c;
  overlap.cells[1] = box_cell({0.5, 0.5, 0.5}, {2, 1, 1});
  EXPECT_NE(cells_are_valid(overlap).find("overlap"), std::string::npos) << cells_are_valid(overlap);
  CellComplex inside_out = c;  // a face turned clockwise seen from inside
  std::reverse(inside_out.cells[0].faces[2].poly.begin(), inside_out.cells[0].faces[2].poly.end());
  EXPECT_NE(cells_are_valid(inside_out).find("cell 0"), std::string::npos) << cells_are_valid(inside_out);
  CellComplex dented = c;  // a vertex pushed out of its face's plane
  dented.cells[1].faces[1].poly[0].z += 0.1;
  EXPECT_NE(cells_are_valid(dented).find("not planar"), std::string::npos) << cells_are_valid(dented);
  CellComplex open = c;  // a face missing: no longer closed
  open.cells[0].faces.pop_back();
  EXPECT_NE(cells_are_valid(open).find("not closed"), std::string::npos) << cells_are_valid(open);
  CellComplex low = c;  // heights that do not hold the vertices
  low.cells[0].z1 = 0.5;
  EXPECT_NE(cells_are_valid(low).find("heights"), std::string::npos) << cells_are_valid(low);
  CellComplex bare = c;  // a face with nothing covering it
  bare.cells[1].faces[0].opaque.clear();
  EXPECT_NE(cells_are_valid(bare).find("cover"), std::string::npos) << cells_are_valid(bare);
}

TEST(MeshScene, ACubeMissingAFaceIsClosedByItsHullAndReported) {
  Mesh open = box_at({1, 1, 1}, {0, 0, 0});
  open.path = "open-cube.obj";
  open.triangles.resize(10);  // the last two triangles are one side
  open.polygon_of.resize(10);
  const CellComplex c = build_mesh_scene({open}, nef());
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_NE(c.warnings[0].find("open-cube.obj"), std::string::npos) << c.warnings[0];
  EXPECT_NE(c.warnings[0].find("not closed"), std::string::npos) << c.warnings[0];
  EXPECT_NE(c.warnings[0].find("convex hull"), std::string::npos) << c.warnings[0];
  EXPECT_EQ(cells_are_valid(c), "");
  EXPECT_NEAR(free_volume(c), box_volume(c.far_box) - 1, 1e-9 * box_volume(c.far_box));
}

TEST(MeshScene, AFlatOpenComponentBecomesAThinPlateAndIsReported) {
  Mesh quad;
  quad.path = "sign.off";
  quad.vertices = {{0, 0, 0}, {2, 0, 0}, {2, 0, 1}, {0, 0, 1}};  // upright, facing -y
  quad.triangles = {{0, 1, 2}, {0, 2, 3}};
  quad.polygon_of = {0, 0};
  MeshSceneParams params;
  params.sheet_thickness = 0.02;
  const CellComplex c = build_mesh_scene({quad}, nef(params));
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_NE(c.warnings[0].find("sheet"), std::string::npos) << c.warnings[0];
  EXPECT_EQ(cells_are_valid(c), "");
  EXPECT_NEAR(free_volume(c), box_volume(c.far_box) - 2 * 1 * 0.02, 1e-9 * box_volume(c.far_box));
  // Seen from either side, the plate hides what is behind it.
  EXPECT_EQ(c.locate({1, 0, 0.5}).what, Location::What::Solid);
  EXPECT_EQ(c.locate({1, 0.5, 0.5}).what, Location::What::Cell);
}

TEST(MeshScene, EachConnectedComponentIsASolid) {
  Mesh two = box_at({1, 1, 1}, {0, 0, 0});
  const Mesh other = box_at({1, 1, 1}, {3, 0, 0});
  const int base = int(two.vertices.size());
  two.vertices.insert(two.vertices.end(), other.vertices.begin(), other.vertices.end());
  for (auto t : other.triangles) two.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  for (int p : other.polygon_of) two.polygon_of.push_back(p + 6);
  const std::vector<Mesh> parts = mesh_components(two);
  ASSERT_EQ(parts.size(), 2u);
  for (const Mesh& m : parts) {
    EXPECT_EQ(m.vertices.size(), 8u);
    EXPECT_EQ(m.triangles.size(), 12u);
    EXPECT_TRUE(m.closed);
  }
  const CellComplex c = build_mesh_scene({two}, nef());
  EXPECT_EQ(cells_are_valid(c), "");
  EXPECT_NEAR(free_volume(c), box_volume(c.far_box) - 2, 1e-9 * box_volume(c.far_box));
}

TEST(MeshScene, AnUnreadableFileIsAnErrorNamingIt) {
  const std::string missing = "/nonexistent/scene.off";
  try {
    read_mesh_scene(missing);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
  }
  EXPECT_THROW(build_mesh_scene({}), std::invalid_argument);
  MeshSceneParams bad;
  bad.margin = 0;
  EXPECT_THROW(build_mesh_scene({box_mesh({1, 1, 1})}, bad), std::invalid_argument);
}

// A model in site coordinates (a survey's easting and northing: 512 km, 5,400 km) keeps
// every coordinate its OBJ or OFF file gives, as the same model near the origin does:
// OpenMesh reads them into floats (half a metre apart up there), so the file's own
// numbers are read again in double. A shelf's two faces 1 cm apart stay two faces, and
// the scene has the cells it has at the origin.
TEST(MeshScene, AModelInSiteCoordinatesKeepsItsFilesOwnNumbers) {
  avenues::testing::TempDir dir;
  auto obj = [](double x0, double y0) {
    const double q[][4][3] = {{{0, 0, 0}, {4, 0, 0}, {4, 3, 0}, {0, 3, 0}},       {{0, 0, 0}, {0, 0, 2.5}, {4, 0, 2.5}, {4, 0, 0}},
                              {{4, 0, 0}, {4, 0, 2.5}, {4, 3, 2.5}, {4, 3, 0}},   {{4, 3, 0}, {4, 3, 2.5}, {0, 3, 2.5}, {0, 3, 0}},
                              {{1, 1, 0.51}, {2, 1, 0.51}, {2, 1.3, 0.51}, {1, 1.3, 0.51}},
                              {{1.001, 1, 0.52}, {1.001, 1.3, 0.52}, {2.001, 1.3, 0.52}, {2.001, 1, 0.52}}};
    std::string text;
    char line[128];
    for (const auto& quad : q)
      for (const auto& v : quad) {
        std::snprintf(line, sizeof line, "v %.3f %.3f %.3f\n", x0 + v[0], y0 + v[1], v[2]);
        text += line;
      }
    for (int k = 0; k < 6; ++k) text += "f " + std::to_string(4 * k + 1) + " " + std::to_string(4 * k + 2) + " " +
                                        std::to_string(4 * k + 3) + " " + std::to_string(4 * k + 4) + "\n";
    return text;
  };
  const double x0 = 512345.678, y0 = 5400123.456;
  const std::string far = dir.write("far.obj", obj(x0, y0)), near = dir.write("near.obj", obj(0, 0));
  const Mesh m = load_mesh(far);
  ASSERT_EQ(m.vertices.size(), 24u);
  EXPECT_EQ(m.vertices[0].x, 512345.678);
  EXPECT_EQ(m.vertices[0].y, 5400123.456);
  EXPECT_EQ(m.vertices[23].x, std::strtod("512347.679", nullptr));
  const CellComplex at_site = read_mesh_scene(far), at_origin = read_mesh_scene(near);
  EXPECT_EQ(at_site.cells.size(), at_origin.cells.size());
  EXPECT_EQ(at_site.portals.size(), at_origin.portals.size());
  // An OFF file's vertex lines alike.
  const std::string off = dir.write("far.off", "OFF\n# a triangle\n3 1 0\n512345.678 5400123.456 0.25\n512346 5400123.456 0\n"
                                                "512345.678 5400124 0\n3 0 1 2\n");
  const Mesh t = load_mesh(off);
  ASSERT_EQ(t.vertices.size(), 3u);
  EXPECT_EQ(t.vertices[0].x, 512345.678);
  EXPECT_EQ(t.vertices[0].y, 5400123.456);
  EXPECT_EQ(t.vertices[0].z, 0.25);
  // An ASCII STL's vertex lines alike, its triangles' shared corners joined as OpenMesh
  // joins them (a binary STL holds floats: those it keeps).
  const std::string stl = dir.write("far.stl", "solid far\nfacet normal 0 0 1\nouter loop\nvertex 512345.678 5400123.456 0.25\n"
                                               "vertex 512346 5400123.456 0\nvertex 512345.678 5400124 0\nendloop\nendfacet\n"
                                               "facet normal 0 0 1\nouter loop\nvertex 512346 5400123.456 0\n"
                                               "vertex 512346.25 5400124.125 0.5\nvertex 512345.678 5400124 0\nendloop\n"
                                               "endfacet\nendsolid far\n");
  const Mesh s = load_mesh(stl);
  ASSERT_EQ(s.vertices.size(), 4u);
  EXPECT_EQ(s.triangles.size(), 2u);
  EXPECT_EQ(s.vertices[0].x, 512345.678);
  EXPECT_EQ(s.vertices[0].y, 5400123.456);
  EXPECT_EQ(s.vertices[2].y, 5400124.0);
  // A PLY file's, ASCII or binary, in double or in float (then as the file has them).
  const std::string ascii = dir.write("far.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
                                                  "property double z\nelement face 1\nproperty list uchar int vertex_indices\n"
                                                  "end_header\n512345.678 5400123.456 0.25\n512346 5400123.456 0\n"
                                                  "512345.678 5400124 0\n3 0 1 2\n");
  EXPECT_EQ(load_mesh(ascii).vertices[0].y, 5400123.456);
  for (bool big : {false, true}) {
    std::string bin = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                      " 1.0\nelement vertex 3\nproperty uchar flag\nproperty double x\nproperty double y\nproperty float z\n"
                      "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    auto put = [&](const void* p, size_t n) {
      std::string b(static_cast<const char*>(p), n);
      if (big) std::reverse(b.begin(), b.end());
      bin += b;
    };
    const double xy[3][2] = {{512345.678, 5400123.456}, {512346, 5400123.456}, {512345.678, 5400124}};
    for (const auto& v : xy) {
      const unsigned char flag = 7;
      const float z = 0.25f;
      put(&flag, 1), put(&v[0], 8), put(&v[1], 8), put(&z, 4);
    }
    const unsigned char three = 3;
    put(&three, 1);
    for (int i = 0; i < 3; ++i) put(&i, 4);
    const Mesh b = load_mesh(dir.write(big ? "big.ply" : "little.ply", bin));
    ASSERT_EQ(b.vertices.size(), 3u) << big;
    EXPECT_EQ(b.vertices[0].x, 512345.678) << big;
    EXPECT_EQ(b.vertices[2].y, 5400124.0) << big;
    EXPECT_EQ(b.vertices[1].z, 0.25) << big;
  }
}

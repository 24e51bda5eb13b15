// Tests of cells/soup_bsp.h through build_mesh_scene (MeshSceneMethod::Bsp, the default):
// soups as they are — open, coincident, crossing — and the meshes from outside, each
// checked by cells_are_valid, by volume (free space is the whole far box), by counting
// the input triangles present as opaque surface, and by the ray oracle on random views.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <random>
#include <set>
#include <tuple>

#include <tbb/global_control.h>

#include "cells/build_cells.h"
#include "cells/mesh_scene.h"
#include "cells/solid_insides.h"
#include "cells/soup_bsp.h"
#include "core/float_rounding.h"
#include "plans/mesh.h"
#include "soup_checks.h"
#include "tests/test_meshes.h"

using namespace avenues;
using avenues::testing::box_volume;
using avenues::testing::free_volume;
using avenues::testing::mesh_from;
using avenues::testing::expect_soup_views_agree_with_rays;
using avenues::testing::outside_path;
using avenues::testing::snapping_reach;
using avenues::testing::closed_solids_volume;
using avenues::testing::triangles_missing_from_export;
using avenues::testing::visible_triangles_missing_from_export;

namespace {

Mesh cube(Vec3 at, double size) {
  Mesh m = box_mesh({size, size, size});
  for (Vec3& v : m.vertices) v = v + at;
  return m;
}

}  // namespace

// A closed, outward-oriented cube is a solid: seen from outside only, its inside no free
// space (Location::What::Solid, named), every face still kept as its outside.
TEST(SoupBsp, AClosedCubeIsSeenFromOutsideOnlyAndItsInsideIsSolid) {
  Mesh m = cube({0, 0, 0}, 1);
  m.path = "cube.obj";
  const CellComplex c = build_mesh_scene({m});
  ASSERT_EQ(cells_are_valid(c), "");
  EXPECT_TRUE(c.warnings.empty());
  EXPECT_NEAR(free_volume(c), box_volume(c.far_box) - 1, 1e-9 * box_volume(c.far_box));
  const Location in = c.locate({0, 0, 0.5});
  EXPECT_EQ(in.what, Location::What::Solid);
  EXPECT_EQ(in.solid, "cube.obj: solid 1");
  EXPECT_EQ(c.locate({0, 0, 1.5}).what, Location::What::Cell);
  EXPECT_EQ(triangles_missing_from_export(c, {m}), 0);
  // Every opaque piece of a cell on the cube looks away from it (its cell is outside).
  for (const Cell& cell : c.cells)
    for (const Face& f : cell.faces)
      for (const OpaquePoly& op : f.opaque)
        for (Vec3 p : op.poly) EXPECT_FALSE(p.x > -0.5 + 1e-9 && p.x < 0.5 - 1e-9 && p.y > -0.5 + 1e-9 && p.y < 0.5 - 1e-9 && p.z > 1e-9 && p.z < 1 - 1e-9);
  // The six axis-aligned sides are the only splitters: 26 cells around the cube at most,
  // however they are merged by the cost.
  EXPECT_LE(c.cells.size(), 26u);
  EXPECT_EQ(c.lines.size(), 12u);
  expect_soup_views_agree_with_rays(c, 12, 16, 96, 64, 1);
}

// What is not a solid stays two-sided, its inside free: a cube turned inwards (a room
// modelled from inside), and the same cube with its vertices split at every corner (as
// readers split them where normals differ) is still a solid.
TEST(SoupBsp, AnInwardCubeIsARoomAndASplitCubeIsStillASolid) {
  Mesh room = cube({0, 0, 0}, 1);
  for (auto& t : room.triangles) std::swap(t[1], t[2]);
  const CellComplex r = build_mesh_scene({room});
  ASSERT_EQ(cells_are_valid(r), "");
  EXPECT_NEAR(free_volume(r), box_volume(r.far_box), 1e-9 * box_volume(r.far_box));
  EXPECT_EQ(r.locate({0, 0, 0.5}).what, Location::What::Cell);
  EXPECT_TRUE(closed_solids({room}).empty());

  const Mesh whole = cube({0, 0, 0}, 1);
  Mesh split;
  split.path = "split.obj";
  for (const auto& t : whole.triangles) {
    const int base = int(split.vertices.size());
    for (int k = 0; k < 3; ++k) split.vertices.push_back(whole.vertices[size_t(t[size_t(k)])]);
    split.triangles.push_back({base, base + 1, base + 2});
  }
  const std::vector<ClosedSolid> solids = closed_solids({split});
  ASSERT_EQ(solids.size(), 1u);
  EXPECT_NEAR(solids[0].volume, 1, 1e-12);
  const CellComplex c = build_mesh_scene({split});
  ASSERT_EQ(cells_are_valid(c), "");
  EXPECT_NEAR(free_volume(c), box_volume(c.far_box) - 1, 1e-9 * box_volume(c.far_box));
  EXPECT_EQ(c.locate({0, 0, 0.5}).what, Location::What::Solid);

  // One triangle turned the wrong way: not consistently oriented, so not a solid.
  Mesh turned = whole;
  std::swap(turned.triangles[0][1], turned.triangles[0][2]);
  EXPECT_TRUE(closed_solids({turned}).empty());
  const CellComplex t = build_mesh_scene({turned});
  ASSERT_EQ(cells_are_valid(t), "");
  EXPECT_EQ(t.locate({0, 0, 0.5}).what, Location::What::Cell);
}

// Two cubes side by side share a face, which nobody can see: it is in neither's export.
// A sheet through a third cube cuts its inside in two; both halves are solid. A closed
// cube inside a room modelled from inside is solid, the room around it free.
TEST(SoupBsp, AbuttingAndPiercedSolidsAndASolidInARoom) {
  Mesh pair = cube({0, 0, 0}, 1);
  pair.path = "pair.obj";
  const Mesh second = cube({1, 0, 0}, 1);
  const int base = int(pair.vertices.size());
  pair.vertices.insert(pair.vertices.end(), second.vertices.begin(), second.vertices.end());
  for (const auto& t : second.triangles) pair.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  pair.polygon_of.clear();
  const CellComplex c = build_mesh_scene({pair});
  ASSERT_EQ(cells_are_valid(c), "");
  EXPECT_NEAR(free_volume(c), box_volume(c.far_box) - 2, 1e-9 * box_volume(c.far_box));
  // The two triangles of the shared face (x = 0.5) are between two solids: not exported.
  EXPECT_EQ(triangles_missing_from_export(c, {pair}), 4);
  // Welded at their shared corners, they are one closed surface: one solid of two insides.
  EXPECT_EQ(c.locate({0.2, 0, 0.5}).solid, "pair.obj: solid 1");
  EXPECT_EQ(c.locate({0.8, 0, 0.5}).solid, "pair.obj: solid 1");
  expect_soup_views_agree_with_rays(c, 8, 30, 96, 64, 1);

  Mesh pierced = cube({0, 0, 0}, 1);
  pierced.path = "pierced.obj";
  const int v = int(pierced.vertices.size());
  pierced.vertices.insert(pierced.vertices.end(), {{-1, -1, 0.4}, {1, -1, 0.4}, {1, 1, 0.6}, {-1, 1, 0.6}});
  pierced.triangles.push_back({v, v + 1, v + 2}), pierced.triangles.push_back({v, v + 2, v + 3});
  pierced.polygon_of.clear();
  const CellComplex p = build_mesh_scene({pierced});
  ASSERT_EQ(cells_are_valid(p), "");
  EXPECT_NEAR(free_volume(p), box_volume(p.far_box) - 1, 1e-9 * box_volume(p.far_box));
  EXPECT_EQ(p.locate({0, 0, 0.2}).what, Location::What::Solid);
  EXPECT_EQ(p.locate({0, 0, 0.8}).what, Location::What::Solid);
  EXPECT_EQ(p.locate({0, 0, 1.5}).what, Location::What::Cell);
  expect_soup_views_agree_with_rays(p, 8, 31, 96, 64, 1);

  Mesh room = cube({0, 0, -1}, 6);
  for (auto& t : room.triangles) std::swap(t[1], t[2]);
  const Mesh block = cube({0, 0, 0}, 1);
  const CellComplex r = build_mesh_scene({room, block});
  ASSERT_EQ(cells_are_valid(r), "");
  EXPECT_NEAR(free_volume(r), box_volume(r.far_box) - 1, 1e-9 * box_volume(r.far_box));
  EXPECT_EQ(r.locate({0, 0, 0.5}).what, Location::What::Solid);
  EXPECT_EQ(r.locate({2, 2, 2}).what, Location::What::Cell);
  EXPECT_EQ(triangles_missing_from_export(r, {room, block}), 0);
  expect_soup_views_agree_with_rays(r, 8, 32, 96, 64, 1);
}

// The first view: inside the scene's largest enclosed free region, where it has one, else
// outside looking at the scene. A closed cube turned inwards (a room modelled from inside)
// is such a region; the same cube turned outwards is a solid block, and one missing a side
// joins its inside to the outside: both are seen from outside.
TEST(SoupBsp, TheFirstViewIsInsideAnEnclosedRoomAndOutsideASolid) {
  Mesh room = cube({0, 0, 0}, 4);
  for (auto& t : room.triangles) std::swap(t[1], t[2]);
  const Box3 inside{{-2, -2, 0}, {2, 2, 4}};
  const CellComplex r = build_mesh_scene({room});
  ASSERT_TRUE(r.view.has_value());
  EXPECT_TRUE(inside.contains(r.view->eye, -1e-9)) << r.view->eye.x << "," << r.view->eye.y << "," << r.view->eye.z;
  EXPECT_NEAR(r.view->look.z, r.view->eye.z, 1e-12);
  const CellComplex solid = build_mesh_scene({cube({0, 0, 0}, 4)});
  ASSERT_TRUE(solid.view.has_value());
  EXPECT_FALSE(inside.contains(solid.view->eye, 0));
  Mesh open = room;
  open.triangles.resize(10);
  open.polygon_of.resize(10);
  const CellComplex o = build_mesh_scene({open});
  ASSERT_TRUE(o.view.has_value());
  EXPECT_FALSE(inside.contains(o.view->eye, 0));
}

TEST(SoupBsp, AnOpenCubeLetsFreeSpaceFlowInWithNoRepair) {
  Mesh m = cube({0, 0, 0}, 1);
  m.path = "open-cube.obj";
  m.triangles.resize(10);  // the last two triangles are one side
  m.polygon_of.resize(10);
  const CellComplex c = build_mesh_scene({m});
  ASSERT_EQ(cells_are_valid(c), "");
  EXPECT_TRUE(c.warnings.empty());
  EXPECT_NEAR(free_volume(c), box_volume(c.far_box), 1e-9 * box_volume(c.far_box));
  EXPECT_EQ(triangles_missing_from_export(c, {m}), 0);
  // Inside and outside are joined through the missing side: a portal between them.
  const Location in = c.locate({0, 0, 0.5}), out = c.locate({0, 2, 0.5});
  ASSERT_EQ(in.what, Location::What::Cell);
  std::vector<int> seen(c.cells.size(), 0);
  std::vector<CellId> stack{in.cell};
  seen[size_t(in.cell)] = 1;
  while (!stack.empty()) {
    const CellId k = stack.back();
    stack.pop_back();
    for (PortalId p : c.cells[size_t(k)].portals)
      if (!seen[size_t(c.portals[size_t(p)].other(k))]++) stack.push_back(c.portals[size_t(p)].other(k));
  }
  EXPECT_TRUE(seen[size_t(out.cell)]);
  // The open side's four edges are sheet lines.
  EXPECT_EQ(std::count_if(c.lines.begin(), c.lines.end(), [](const RealLine& l) { return l.kind == LineKind::Sheet; }), 4);
  expect_soup_views_agree_with_rays(c, 12, 17, 96, 64, 1);
}

// The tree's leaves are joined where their union stays convex: a grid of open boxes (a
// floor and four walls each) slices the space around it into many leaves; fewer cells come
// out, each still convex and sound, and no two cells are left that could be joined (a face
// wholly open onto one cell whose facing face is wholly open back, with every corner of each
// inside the other's other face planes).
TEST(SoupBsp, LeavesAreJoinedWhereTheUnionStaysConvex) {
  Mesh m;
  m.path = "open-boxes.obj";
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double x = 2.0 * i, y = 2.5 * j;
      const Mesh b = mesh_from({{x, y, 0}, {x + 1, y, 0}, {x + 1, y + 1, 0}, {x, y + 1, 0}, {x, y, 1}, {x + 1, y, 1},
                                {x + 1, y + 1, 1}, {x, y + 1, 1}},
                               {{0, 3, 2, 1}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}});
      const int base = int(m.vertices.size()), poly = m.polygon_of.empty() ? 0 : m.polygon_of.back() + 1;
      m.vertices.insert(m.vertices.end(), b.vertices.begin(), b.vertices.end());
      for (size_t t = 0; t < b.triangles.size(); ++t) {
        m.triangles.push_back({b.triangles[t][0] + base, b.triangles[t][1] + base, b.triangles[t][2] + base});
        m.polygon_of.push_back(poly + b.polygon_of[t]);
      }
    }
  std::vector<SoupTriangle> soup;
  for (const auto& t : m.triangles) soup.push_back({{m.vertices[size_t(t[0])], m.vertices[size_t(t[1])], m.vertices[size_t(t[2])]}});
  CellComplex direct;
  direct.far_box = {{-3, -3, -3}, {9, 11, 4}};
  const SoupBspStats stats = decompose_soup(soup, direct.far_box, direct);
  EXPECT_LT(stats.cells, stats.leaves);
  EXPECT_EQ(stats.cells, direct.cells.size());

  const CellComplex c = build_mesh_scene({m});
  ASSERT_EQ(cells_are_valid(c), "");
  EXPECT_NEAR(free_volume(c), box_volume(c.far_box), 1e-9 * box_volume(c.far_box));
  EXPECT_EQ(triangles_missing_from_export(c, {m}), 0);
  auto corners = [](const Cell& cell) {
    std::vector<Vec3> v;
    for (const Face& f : cell.faces) v.insert(v.end(), f.poly.begin(), f.poly.end());
    return v;
  };
  auto area = [](const std::vector<Vec3>& p) {
    Vec3 s{0, 0, 0};
    for (size_t i = 1; i + 1 < p.size(); ++i) s = s + cross(p[i] - p[0], p[i + 1] - p[0]);
    return length(s) / 2;
  };
  // The cell a face is wholly open onto (its portals cover it, all to that cell), else -1.
  auto open_onto = [&](CellId self, const Face& f) {
    CellId other = kNoCell;
    double covered = 0;
    for (PortalId p : f.portals) {
      const CellId o = c.portals[size_t(p)].other(self);
      if (other != kNoCell && o != other) return kNoCell;
      other = o;
      covered += area(c.portals[size_t(p)].poly);
    }
    return std::fabs(covered - area(f.poly)) < 1e-9 * std::max(1.0, area(f.poly)) ? other : kNoCell;
  };
  auto inside_others = [&](const Cell& a, const Face& shared, const Cell& b) {
    for (const Face& f : b.faces) {
      if (dot(f.plane.n, shared.plane.n) < -1 + 1e-12) continue;  // b's face on the shared plane
      for (Vec3 v : corners(a))
        if (f.plane.eval(v) > 1e-9) return false;
    }
    return true;
  };
  size_t joinable = 0;
  for (CellId i = 0; i < CellId(c.cells.size()); ++i)
    for (const Face& f : c.cells[size_t(i)].faces) {
      const CellId j = open_onto(i, f);
      if (j == kNoCell) continue;
      const Cell &a = c.cells[size_t(i)], &b = c.cells[size_t(j)];
      for (const Face& g : b.faces)
        if (dot(g.plane.n, f.plane.n) < -1 + 1e-12 && std::fabs(g.plane.d + f.plane.d) < 1e-9 && open_onto(j, g) == i &&
            inside_others(a, f, b) && inside_others(b, g, a))
          ++joinable;
    }
  EXPECT_EQ(joinable, 0u);
  expect_soup_views_agree_with_rays(c, 12, 21, 96, 64, 1);
}

// The air over a grid of open boxes is one cell. Every wall's plane, run on across the
// space above the grid, sliced it into a column over each box and each corridor, and a
// grazing view over the grid went through every one of them (8,192 cells of the 64 × 64
// grid). The far box is now first cut where the walls' tops stand (an empty-space cut).
TEST(SoupBsp, TheAirOverAGridOfOpenBoxesIsOneCell) {
  const Mesh m = avenues::testing::open_boxes(8);
  const CellComplex c = build_mesh_scene({m});
  ASSERT_EQ(cells_are_valid(c), "");
  EXPECT_NEAR(free_volume(c), box_volume(c.far_box), 1e-9 * box_volume(c.far_box));
  EXPECT_EQ(triangles_missing_from_export(c, {m}), 0);
  int above = 0;
  for (const Cell& cell : c.cells) {
    const Box3 b = cell.bounds();
    if (b.lo.z < 1 - 1e-9) continue;
    ++above;
    EXPECT_NEAR(b.lo.x, c.far_box.lo.x, 1e-9);
    EXPECT_NEAR(b.hi.x, c.far_box.hi.x, 1e-9);
    EXPECT_NEAR(b.lo.y, c.far_box.lo.y, 1e-9);
    EXPECT_NEAR(b.hi.y, c.far_box.hi.y, 1e-9);
    EXPECT_NEAR(b.hi.z, c.far_box.hi.z, 1e-9);
  }
  EXPECT_EQ(above, 1);
  expect_soup_views_agree_with_rays(c, 8, 64, 96, 64, 8);
}

// The decomposition settles its points' exact values on two threads where there are two
// (the pass before rounding): the cells come out the same, to the bit, on one thread.
TEST(SoupBsp, OneThreadOrManyMakeTheSameCellsToTheBit) {
  std::vector<Mesh> meshes;
  for (const char* f : {"meshes/alpine-cabin/house.obj", "meshes/alpine-cabin/roof.obj", "meshes/CornellBox-Original.obj"})
    meshes.push_back(load_mesh(outside_path(f)));
  auto bytes = [&](CellComplex c) {
    c.timings.clear();
    return cells_bytes(c);
  };
  const std::string many = bytes(build_mesh_scene(meshes));
  std::string one;
  {
    tbb::global_control cap(tbb::global_control::max_allowed_parallelism, 1);
    one = bytes(build_mesh_scene(meshes));
  }
  EXPECT_EQ(many.size(), one.size());
  EXPECT_TRUE(many == one);
}

// A convex cluster (a sphere's faces: each face's plane has all the others behind it) is
// halved by axis-aligned planes rather than peeled one face per level: the tree stays far
// shallower than the sphere has faces (peeling, it was nearly as deep: 2,248 levels for 2,944 faces; a sphere
// of 18,000 faces took minutes), and the cells are sound. Not asserted, because it does not
// hold yet, with halving or without: every face kept and the ray oracle. The tangent planes
// of a fine sphere leave slivers thinner than rounding beside its surface; they are dropped
// (drop_slivers), and with them a few hundred of its faces and some cells a ray sees.
TEST(SoupBsp, ASphereIsHalvedNotPeeledFaceByFaceAndKeepsEveryFaceAndView) {
  Mesh sphere;
  sphere.path = "sphere.obj";
  constexpr int kAround = 48, kRings = 20;
  sphere.vertices.push_back({0, 0, -1});
  for (int r = 1; r < kRings; ++r)
    for (int a = 0; a < kAround; ++a) {
      const double phi = std::numbers::pi * r / kRings - std::numbers::pi / 2, theta = 2 * std::numbers::pi * a / kAround;
      sphere.vertices.push_back({std::cos(phi) * std::cos(theta), std::cos(phi) * std::sin(theta), std::sin(phi)});
    }
  sphere.vertices.push_back({0, 0, 1});
  auto at = [](int r, int a) { return 1 + (r - 1) * kAround + (a % kAround); };
  const int top = int(sphere.vertices.size()) - 1;
  for (int a = 0; a < kAround; ++a) {
    sphere.triangles.push_back({0, at(1, a + 1), at(1, a)});
    for (int r = 1; r + 1 < kRings; ++r) {
      sphere.triangles.push_back({at(r, a), at(r, a + 1), at(r + 1, a + 1)});
      sphere.triangles.push_back({at(r, a), at(r + 1, a + 1), at(r + 1, a)});
    }
    sphere.triangles.push_back({at(kRings - 1, a), at(kRings - 1, a + 1), top});
  }
  ASSERT_EQ(closed_solids({sphere}).size(), 1u);  // counter-clockwise seen from outside
  std::vector<SoupTriangle> soup;
  for (const auto& t : sphere.triangles)
    soup.push_back({{sphere.vertices[size_t(t[0])], sphere.vertices[size_t(t[1])], sphere.vertices[size_t(t[2])]}});
  CellComplex direct;
  direct.far_box = {{-3, -3, -3}, {3, 3, 3}};
  const SoupBspStats stats = decompose_soup(soup, direct.far_box, direct);
  EXPECT_EQ(stats.triangles, soup.size());
  EXPECT_LT(stats.depth, 1000) << soup.size() << " triangles";

  // Its nearly coplanar neighbours (a planar quad's two triangles, not quite coplanar in
  // doubles) leave cells and portals whose rounded corners lie a few units in the last
  // place apart, the edge between them turned inward. Every face is still kept, and the
  // search still passes every portal a ray passes (it once lost whole chains of cells
  // there: the edge's plane through the eye cut away the rays the portal lets through).
  MeshSceneParams cut;  // a closed curved solid: cut into space only when asked
  cut.curved_directions = 0;
  const CellComplex c = build_mesh_scene({sphere}, cut);
  ASSERT_EQ(cells_are_valid(c), "");
  EXPECT_EQ(c.locate({0, 0, 0}).what, Location::What::Solid);
  EXPECT_EQ(c.locate({0, 0, 2}).what, Location::What::Cell);
  const int missing = visible_triangles_missing_from_export(c, {sphere});
  std::printf("  sphere: %zu triangles, depth %d, %zu cells, %d visible triangles missing from the export\n",
              soup.size(), stats.depth, c.cells.size(), missing);
  EXPECT_EQ(missing, 0);
  expect_soup_views_agree_with_rays(c, 8, 7, 96, 64, 8);
}

namespace {

/// A box of sides `size` at the origin, each face cut n × n into quads of two triangles,
/// its vertices shared: a closed solid, counter-clockwise seen from outside.
Mesh tessellated_box(int n, Vec3 size) {
  std::vector<Vec3> v;
  std::map<std::tuple<double, double, double>, int> index;
  auto vertex = [&](Vec3 p) {
    const auto [it, fresh] = index.try_emplace({p.x, p.y, p.z}, int(v.size()));
    if (fresh) v.push_back(p);
    return it->second;
  };
  std::vector<std::vector<int>> polygons;
  auto face = [&](Vec3 o, Vec3 u, Vec3 w) {  // o + i/n u + j/n w; u × w points out
    auto at = [&](int i, int j) { return vertex(o + (double(i) / n) * u + (double(j) / n) * w); };
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        polygons.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
        polygons.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
      }
  };
  const Vec3 x{size.x, 0, 0}, y{0, size.y, 0}, z{0, 0, size.z};
  face({0, 0, 0}, y, x), face(z, x, y), face({0, 0, 0}, x, z), face(y, z, x), face({0, 0, 0}, z, y), face(x, y, z);
  return mesh_from(v, polygons);
}

/// p turned by `angle` about the unit `axis` (Rodrigues), then moved by `offset`.
Vec3 turned(Vec3 p, Vec3 axis, double angle, Vec3 offset) {
  const double c = std::cos(angle), s = std::sin(angle);
  return c * p + s * cross(axis, p) + (1 - c) * dot(axis, p) * axis + offset;
}

}  // namespace

// A cube turned about an axis no coordinate plane holds: each face's four corners,
// rotated in doubles, are coplanar only to a rounding, so its two triangles lie on two
// planes a hair apart. Each plane cuts the whole cell it crosses; the wedge between them
// ran from the face's diagonal across the far box, thinner than rounding, and was dropped
// as a sliver, leaving walls in open space. Nearly coplanar triangles now take a plane
// they share (cells/shared_planes.h): no sliver, the cube's inside solid and the rest
// free. The same in floats (every format Assimp reads), whose rounding is larger.
TEST(SoupBsp, NearlyCoplanarTrianglesOfAFaceCutSpaceByOnePlane) {
  for (const bool floats : {false, true}) {
    SCOPED_TRACE(floats ? "floats" : "doubles");
    Mesh m = cube({0, 0, 0}, 2);
    m.path = "turned-cube.obj";
    const Vec3 axis = (1 / std::sqrt(14.0)) * Vec3{1, 2, 3};
    auto turn = [&](Vec3 v) { return turned(v, axis, 0.7, {3.1, -1.7, 2.3}); };
    for (Vec3& v : m.vertices) {
      v = turn(v);
      if (floats) v = to_float(v);
    }
    const CellComplex cx = build_mesh_scene({m});
    ASSERT_EQ(cells_are_valid(cx), "");
    for (const std::string& w : cx.warnings) EXPECT_EQ(w.find("slivers of free space"), std::string::npos) << w;
    EXPECT_NEAR(free_volume(cx), box_volume(cx.far_box) - closed_solids_volume({m}), 1e-9 * box_volume(cx.far_box));
    EXPECT_EQ(cx.locate(turn({0, 0, 1})).what, Location::What::Solid);  // its middle
    EXPECT_EQ(visible_triangles_missing_from_export(cx, {m}), 0);
    expect_soup_views_agree_with_rays(cx, 4, 12, 96, 64, 8);
  }
}

// The same cube with each face tessellated n × n, as a modeller or an exporter leaves a
// wall, turned and stored in floats. A face's triangles are coplanar only to a rounding,
// and a small triangle's own plane, exact through its three rounded corners, is tilted by
// that rounding over its own size: across the face it strays by n times as much, so the
// far triangles of the face fell outside its reach and cut space on planes of their own,
// crossing inside the wall: at n = 8 and 16, 323 and 1,175 slivers were closed, leaving 14
// and 18 m² of walls in open space. A face's plane is now one through corners spread
// across it. (Its 512 triangles also cost 8.9 s to cut from the leaf faces they cover,
// each fragment tried against every piece left open; now 0.6 s.)
TEST(SoupBsp, TessellatedFacesOfATurnedCubeCutSpaceByOnePlaneEach) {
  for (const int n : {3, 8, 16}) {
    SCOPED_TRACE(n);
    Mesh m = tessellated_box(n, {2, 2, 2});
    m.path = "tessellated-cube.obj";
    const Vec3 axis = (1 / std::sqrt(14.0)) * Vec3{1, 2, 3};
    auto turn = [&](Vec3 p) { return turned(p, axis, 0.7, {3.1, -1.7, 2.3}); };
    for (Vec3& p : m.vertices) p = to_float(turn(p));
    ASSERT_EQ(closed_solids({m}).size(), 1u);
    const CellComplex cx = build_mesh_scene({m});
    ASSERT_EQ(cells_are_valid(cx), "");
    for (const std::string& w : cx.warnings) EXPECT_EQ(w.find("slivers of free space"), std::string::npos) << w;
    // Each corner moves onto its face's plane by up to a rounding, over the cube's 24 m².
    EXPECT_NEAR(free_volume(cx), box_volume(cx.far_box) - closed_solids_volume({m}), 24 * snapping_reach({m}));
    EXPECT_EQ(cx.locate(turn({1, 1, 1})).what, Location::What::Solid);
    EXPECT_EQ(visible_triangles_missing_from_export(cx, {m}), 0);
    if (n == 8) expect_soup_views_agree_with_rays(cx, 4, 12, 96, 64, 8);
  }
}

// Boxes of three sizes tessellated 2 × 2 to 6 × 6 a face, turned about random axes and
// moved up to 50 m off the origin, in doubles and in floats: each stays a closed solid
// in valid cells, its faces kept, no sliver dropped, and the free space the far box less
// the box, to the corners' moves onto shared planes.
TEST(SoupBsp, RandomlyTurnedTessellatedBoxesStaySolidInDoublesAndFloats) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1, 1), angle(0.05, 3.0);
  for (int trial = 0; trial < 40; ++trial) {
    const int n = 2 + trial % 5;
    const bool floats = trial % 2 == 0;
    SCOPED_TRACE("trial " + std::to_string(trial) + (floats ? ", floats" : ", doubles"));
    Mesh m = tessellated_box(n, {2, 3, 1.5});
    m.path = "turned-box.obj";
    Vec3 axis{unit(rng), unit(rng), unit(rng)};
    axis = (1 / length(axis)) * axis;
    const double a = angle(rng);
    const Vec3 offset{50 * unit(rng), 50 * unit(rng), 50 * unit(rng)};
    for (Vec3& p : m.vertices) {
      p = turned(p, axis, a, offset);
      if (floats) p = to_float(p);
    }
    const CellComplex cx = build_mesh_scene({m});
    ASSERT_EQ(cells_are_valid(cx), "");
    for (const std::string& w : cx.warnings) EXPECT_EQ(w.find("slivers of free space"), std::string::npos) << w;
    // Each corner moves onto its face's plane by up to a rounding, over the box's 27 m².
    EXPECT_NEAR(free_volume(cx), box_volume(cx.far_box) - closed_solids_volume({m}), 27 * snapping_reach({m}));
    EXPECT_EQ(cx.locate(turned({1, 1.5, 0.75}, axis, a, offset)).what, Location::What::Solid);
    EXPECT_EQ(visible_triangles_missing_from_export(cx, {m}), 0);
  }
}

TEST(SoupBsp, CrossingTrianglesAreCutWhereTheyMeetAndADegenerateOneIsReported) {
  Mesh m;
  m.path = "crossing.obj";
  m.vertices = {{0, 0, 0}, {2, 0, 0}, {1, 0, 2}, {1, -1, 1}, {1, 1, 1}, {1, 0, -1}, {0, 0, 0}, {1, 1, 1}, {2, 2, 2}};
  m.triangles = {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}};  // two crossing at right angles, one with no area
  m.polygon_of = {0, 1, 2};
  const CellComplex c = build_mesh_scene({m});
  ASSERT_EQ(cells_are_valid(c), "");
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_NE(c.warnings[0].find("crossing.obj: 1 triangles with no area"), std::string::npos) << c.warnings[0];
  EXPECT_EQ(triangles_missing_from_export(c, {m}), 0);
  expect_soup_views_agree_with_rays(c, 12, 18, 96, 64, 1);
}

TEST(SoupBsp, ALineListAloneIsOneCellOfTheFarBox) {
  MeshSceneParams p;
  p.include.add({0, 0, 0}), p.include.add({1, 1, 1});
  const CellComplex c = build_mesh_scene({}, p);
  ASSERT_EQ(cells_are_valid(c), "");
  EXPECT_EQ(c.cells.size(), 1u);
  EXPECT_TRUE(c.portals.empty());
}

/// Each mesh from outside (../shared/outside/meshes/): valid cells filling the far box,
/// every triangle of some area present as opaque surface, and random views agreeing with
/// the ray oracle (a ray every 8 pixels of 96 × 64).
TEST(SoupBsp, EveryMeshFromOutsideKeepsAllItsFacesAndAgreesWithRayCasting) {
  struct Scene {
    const char* name;
    std::vector<std::string> files;
    int views;
  };
  const std::vector<Scene> scenes = {
      {"Cornell box", {"meshes/CornellBox-Original.obj"}, 24},
      {"Viking room", {"meshes/viking-room/viking_room.obj"}, 12},
      {"alpine cabin",
       {"meshes/alpine-cabin/house.obj", "meshes/alpine-cabin/roof.obj", "meshes/alpine-cabin/siding.obj",
        "meshes/alpine-cabin/windows.obj", "meshes/alpine-cabin/door.obj"},
       4},
  };
  for (const Scene& s : scenes) {
    SCOPED_TRACE(s.name);
    std::vector<Mesh> meshes;
    for (const std::string& f : s.files) meshes.push_back(load_mesh(outside_path(f)));
    const CellComplex c = build_mesh_scene(meshes);
    ASSERT_EQ(cells_are_valid(c), "");
    EXPECT_NEAR(free_volume(c), box_volume(c.far_box) - closed_solids_volume(meshes, &c), 1e-7 * box_volume(c.far_box));
    size_t triangles = 0;
    for (const Mesh& m : meshes) triangles += m.triangles.size();
    std::printf("  %s: %zu triangles, %zu cells, %zu portals, %zu warnings\n", s.name, triangles, c.cells.size(),
                c.portals.size(), c.warnings.size());
    EXPECT_EQ(visible_triangles_missing_from_export(c, meshes), 0);
    expect_soup_views_agree_with_rays(c, s.views, 1992, 96, 64, 8);
  }
}

// Where a portal's edges nearly run on in one line, a clip leaves a needle of no area whose
// corner, where two nearly parallel sides meet, rounds to anywhere along them: once 0.07
// across the picture, outside the mask it was clipped from, and the merged search took rays
// there into the cell beyond (Mask::settle_within now settles such a corner). Views 5 and 7
// of the Viking room's random views met such needles once; as the decomposition changed,
// they met none, and the test no longer tested what it is named for. So the views checked
// now are the first two of the room's random views where a search does settle a mask
// (VisibleSet::masks_settled), and there must be two. Their checks also cover the line
// through two hull corners 7e-7 apart that the hull check once took for a side (outside_by
// now skips sides that short).
TEST(SoupBsp, NeedleMasksOfNearlyParallelPortalEdgesSeeNothing) {
  const std::vector<Mesh> meshes{load_mesh(outside_path("meshes/viking-room/viking_room.obj"))};
  const CellComplex c = build_mesh_scene(meshes);
  ASSERT_EQ(cells_are_valid(c), "");
  int needles = 0;
  expect_soup_views_agree_with_rays(c, 64, 1992, 96, 64, 16, 0, 2, &needles);
  EXPECT_EQ(needles, 2) << "fewer than two of 64 views settle a needle mask: this test needs other views";
}

/// Scenes of Assimp's test models, each read as its format's own tools read it (COLLADA,
/// FBX, 3DS, glTF, Blender, DirectX, ASE, Irrlicht's): a house of walls and a foundation
/// (regr01), a spider of thin legs, a rock, a textured room (test1.3ds), spheres, cubes that
/// touch, a concave polygon, a vaulted cellar, and the cellar with cubes and spheres placed
/// by a scene's nodes. Each: cells valid, no face someone could see missing from the export
/// (counted), and views from random cells agreeing with rays.
TEST(SoupBsp, AssimpsTestModelsKeepTheirFacesAndAgreeWithRayCasting) {
  const std::filesystem::path models = "/usr/share/assimp/models";
  if (!std::filesystem::exists(models / "Collada/duck.dae"))
    GTEST_SKIP() << "assimp-testmodels not installed (.ci/install-deps)";
  const char* const names[] = {"Collada/regr01.dae",       "FBX/spider.fbx",          "3DS/fels.3ds",
                               "3DS/test1.3ds",            "Collada/sphere.dae",      "ASE/ThreeCubesGreen.ASE",
                               "3DS/cubes_with_alpha.3DS", "Collada/ConcavePolygon.dae", "glTF2/BoxTextured-glTF/BoxTextured.gltf",
                               "BLEND/box.blend",          "X/test.x",                "Collada/duck.dae",
                               "IRRMesh/cellar.irrmesh",   "IRR/scenegraphAnim.irr"};
  unsigned seed = 2026;
  for (const char* name : names) {
    SCOPED_TRACE(name);
    std::vector<Mesh> meshes{load_mesh((models / name).string())};
    Box3 box;
    for (Vec3 v : meshes[0].vertices) box.add(v);
    const double across = std::max({box.hi.x - box.lo.x, box.hi.y - box.lo.y, box.hi.z - box.lo.z});
    // Two are a centimetre or two across (regr01's house by its COLLADA unit, the sphere),
    // which the scene says in a warning. At that size the pictures' 1 cm near plane cuts
    // most of every view, and the hull search's masks were found to leave the merged
    // search's by up to 1e-3 (noted on issue 16): they are checked here made 100 times
    // larger, at the scale of a model Avenues is for.
    if (across < 0.1) {
      const CellComplex tiny = build_mesh_scene(meshes);
      ASSERT_EQ(cells_are_valid(tiny), "");
      EXPECT_EQ(visible_triangles_missing_from_export(tiny, meshes), 0);
      ASSERT_FALSE(tiny.warnings.empty());
      EXPECT_NE(tiny.warnings.front().find("across: Avenues works at the scale of buildings"), std::string::npos)
          << tiny.warnings.front();
      for (Vec3& v : meshes[0].vertices) v = 100.0 * v;
    }
    // As a user gets them (curved closed solids drawn as detail), and, where there are
    // some, with every closed solid cut into space: the soup BSP on a duck and spheres.
    MeshSceneParams params;
    for (int pass = 0; pass < 2; ++pass) {
      SCOPED_TRACE(pass == 0 ? "curved solids as detail" : "every solid cut into space");
      const CellComplex c = build_mesh_scene(meshes, params);
      ASSERT_EQ(cells_are_valid(c), "");
      std::printf("  %s%s: %zu triangles, %zu cells, %zu portals, %zu curved solids, %zu warnings\n", name,
                  pass == 0 ? "" : " (cut)", meshes[0].triangles.size(), c.cells.size(), c.portals.size(),
                  c.detail_solids.size(), c.warnings.size());
      EXPECT_EQ(visible_triangles_missing_from_export(c, meshes), 0);
      expect_soup_views_agree_with_rays(c, 8, seed++, 96, 64, 8);
      if (c.detail_solids.empty()) break;
      params.curved_directions = 0;
    }
  }
}

/// The duplex IFC model read as a soup (Assimp's triangles of every element, 12,718 faces
/// as Assimp exports them): its cells valid, its elements' closed solids not free space,
/// every face someone could see kept, and views agreeing with rays.
/// Its elements are closed solids that touch and overlap (walls into slabs), so their
/// volumes summed are at least what they fill together: the free volume lies between the
/// far box less that sum and the far box, and no cell is inside a solid. Faces between
/// touching solids are seen by nobody and are not kept. One face (a door jamb's, at
/// x = 6.165) once seemed missing: the opaque piece holding it has two corners a rounding
/// apart, whose edge turns inward, and the check took that edge for a side.
/// Its walls' faces meet many nearly parallel planes, where a vertex's interval can be
/// millimetres wide: a fragment covering a piece of a leaf face was once culled by the
/// middles of such intervals on one side of the face and not on the other, and the face
/// lost that part (its opaque pieces and portals no longer covered it).
TEST(SoupBsp, TheDuplexModelAsASoupKeepsEveryFaceAndItsCellsAreSound) {
  const std::string path = outside_path("ifc/duplex.ifc");
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "no " << path;
  const std::vector<Mesh> meshes{load_mesh(path)};
  const CellComplex c = build_mesh_scene(meshes);
  ASSERT_EQ(cells_are_valid(c), "");
  const double box = box_volume(c.far_box);
  EXPECT_GE(free_volume(c), box - closed_solids_volume(meshes) - 1e-7 * box);
  EXPECT_LT(free_volume(c), box - 1);  // its slabs alone are tens of cubic metres
  const std::vector<ClosedSolid> solids = closed_solids(meshes);
  EXPECT_GT(solids.size(), 50u);
  int inside = 0;
  for (const Cell& cell : c.cells) {
    Vec3 s{0, 0, 0};
    double k = 0;
    for (const Face& f : cell.faces)
      for (Vec3 p : f.poly) s = s + p, k += 1;
    inside += avenues::testing::inside_closed_solid(solids, (1.0 / k) * s);
  }
  EXPECT_EQ(inside, 0);
  const int visible_missing = visible_triangles_missing_from_export(c, meshes);
  std::printf("  duplex: %zu triangles, %zu solids, %zu cells, %zu portals, %d triangles missing from the export, %d "
              "of them visible\n",
              meshes[0].triangles.size(), solids.size(), c.cells.size(), c.portals.size(),
              triangles_missing_from_export(c, meshes), visible_missing);
  EXPECT_EQ(visible_missing, 0);
  expect_soup_views_agree_with_rays(c, 12, 2012, 96, 64, 8);
}


// The duplex's triangles written out as a plain OBJ (as a user exports a model: no
// polygons, half of its 30,914 triangles of no area): rounding the exact cells left a face
// of one cell with two corners, 3.7 m long and no wider than a rounding, which the
// invariant checks refused. Such a face bounds nothing and goes; the cells are sound.
TEST(SoupBsp, TheDuplexWrittenOutAsTrianglesGivesSoundCells) {
  const std::string path = outside_path("ifc/duplex.ifc");
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "no " << path;
  const Mesh m = load_mesh(path);
  const std::filesystem::path obj = std::filesystem::temp_directory_path() / "avenues_duplex_triangles.obj";
  {
    std::ofstream out(obj);
    out.precision(17);
    for (Vec3 v : m.vertices) out << "v " << v.x << " " << v.y << " " << v.z << "\n";
    for (const auto& t : m.triangles) out << "f " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
  }
  const std::vector<Mesh> meshes{load_mesh(obj.string())};
  std::filesystem::remove(obj);
  const CellComplex c = build_mesh_scene(meshes);
  ASSERT_EQ(cells_are_valid(c), "");
  EXPECT_GT(c.cells.size(), 10000u);
  EXPECT_EQ(visible_triangles_missing_from_export(c, meshes), 0);
}

// Slivers of free space thinner than rounding are dropped. Where one lies between two
// free cells (its two large faces back to back, a rounding apart), they are joined across
// it by portals; the other portals into it become opaque, each showing what was seen
// through the sliver (the surface on its far side) in its material. The cabin's house
// drops 13: every piece of no material left lies on the far box (once 0.57 m² of grey
// patches on a coloured house). The Viking room drops 100 and joins across a third of
// them: 0.02 m² of no material is left where slivers lie side by side (once 0.21 m²).
TEST(SoupBsp, DroppedSliversAreJoinedAcrossOrShowTheMaterialSeenThroughThem) {
  auto on_far_box = [](const CellComplex& c, const std::vector<Vec3>& poly) {
    const Box3& b = c.far_box;
    const double lo[3] = {b.lo.x, b.lo.y, b.lo.z}, hi[3] = {b.hi.x, b.hi.y, b.hi.z};
    for (int ax = 0; ax < 3; ++ax)
      for (double v : {lo[ax], hi[ax]}) {
        bool all = true;
        for (Vec3 q : poly) all = all && std::fabs((ax == 0 ? q.x : ax == 1 ? q.y : q.z) - v) < 1e-9;
        if (all) return true;
      }
    return false;
  };
  for (auto [file, most_grey, joins] : {std::tuple{"meshes/alpine-cabin/house.obj", 1e-9, false},
                                        std::tuple{"meshes/viking-room/viking_room.obj", 0.025, true}}) {
    SCOPED_TRACE(file);
    const std::vector<Mesh> meshes{load_mesh(outside_path(file))};
    const CellComplex c = build_mesh_scene(meshes);
    ASSERT_EQ(cells_are_valid(c), "");
    std::string dropped;
    for (const std::string& w : c.warnings)
      if (w.find("slivers") != std::string::npos) dropped = w;
    ASSERT_FALSE(dropped.empty()) << "the case this tests is gone: no sliver dropped";
    if (joins) {
      EXPECT_EQ(dropped.find("; 0 portals join"), std::string::npos) << dropped;
    }
    double grey = 0;
    for (const Cell& cell : c.cells)
      for (const Face& f : cell.faces)
        for (const OpaquePoly& o : f.opaque)
          if (o.material < 0 && !on_far_box(c, o.poly)) grey += polygon_area(o.poly);
    EXPECT_LT(grey, most_grey) << "m² of opaque surface of no material off the far box";
  }
}


// A slab with a grid of openings over a box: the cell under the slab meets the cell over it
// through many portals in the slab's plane (the openings, and the strips of the far box
// around the slab cut into convex pieces). The search's table holds each face's portals
// into one cell as their convex hull too (CellComplex::PortalTable::hulls): every corner
// of every such portal within it, its own corners theirs, its normal into the cell beyond.
// The hull search clips to that hull once where it would clip to each portal: it tests
// fewer portals, holds every view the merged search finds, and draws the same pictures.
TEST(SoupBsp, ThePortalsOfAFaceIntoOneCellAreOneHullToTheHullSearch) {
  // The slab z = 2 over [0, 6]², openings [1, 1.5], [2.5, 3], [4, 4.5] in x and in y: the
  // grid of rectangles between those lines, less the nine openings.
  const double at[] = {0, 1, 1.5, 2.5, 3, 4, 4.5, 6};
  std::vector<Vec3> v;
  std::vector<std::vector<int>> polygons;
  for (int i = 0; i + 1 < 8; ++i)
    for (int j = 0; j + 1 < 8; ++j) {
      if (i % 2 == 1 && j % 2 == 1) continue;  // an opening
      const int k = int(v.size());
      v.insert(v.end(), {Vec3{at[i], at[j], 2}, Vec3{at[i + 1], at[j], 2}, Vec3{at[i + 1], at[j + 1], 2},
                         Vec3{at[i], at[j + 1], 2}});
      polygons.push_back({k, k + 1, k + 2, k + 3});
    }
  Mesh slab = mesh_from(v, polygons);
  slab.path = "slab.obj";
  Mesh block = cube({2, 2, 0}, 1);
  block.path = "block.obj";
  const std::vector<Mesh> meshes{slab, block};
  const CellComplex c = build_mesh_scene(meshes);
  ASSERT_EQ(cells_are_valid(c), "");
  const CellComplex::PortalTable& t = c.portal_table;
  ASSERT_TRUE(t.fits(c));
  ASSERT_EQ(t.face_hulls.size(), t.face_seen.size());
  size_t joined = 0, largest = 0;
  for (CellId id = 0; id < CellId(c.cells.size()); ++id)
    for (int32_t face = t.cell_faces[size_t(id)]; face < t.cell_faces[size_t(id) + 1]; ++face)
      for (int32_t h = t.face_hulls[size_t(face)]; h < t.face_hulls[size_t(face) + 1]; ++h) {
        const auto& hull = t.hulls[size_t(h)];
        SCOPED_TRACE("cell " + std::to_string(id) + ", hull " + std::to_string(h));
        EXPECT_TRUE(hull.first);
        ASSERT_GE(hull.corners, 3u);
        std::vector<Vec3> corners(t.corners.begin() + hull.corner0, t.corners.begin() + hull.corner0 + hull.corners);
        // Its normal into the cell beyond, as the search reads it (corners 0, spread, spread + 1).
        const Vec3 n = cross(corners[hull.spread] - corners[0], corners[hull.spread + 1] - corners[0]);
        EXPECT_GT(dot(n, hull.plane.n), 0);
        const Box3 beyond = c.cells[size_t(hull.other)].bounds();
        EXPECT_GT(hull.plane.eval(0.5 * (beyond.lo + beyond.hi)), 0) << "the plane's normal points into the cell beyond";
        // The portals of the face into that cell: their least number, their corners.
        size_t portals = 0;
        PortalId least = -1;
        std::vector<Vec3> theirs;
        for (int32_t i = t.face_seen[size_t(face)]; i < t.face_seen[size_t(face) + 1]; ++i) {
          const auto& s = t.seen[size_t(i)];
          if (s.other != hull.other) continue;
          ++portals;
          least = least < 0 ? s.portal : std::min(least, s.portal);
          theirs.insert(theirs.end(), t.corners.begin() + s.corner0, t.corners.begin() + s.corner0 + s.corners);
        }
        EXPECT_EQ(hull.portal, least);
        for (const Vec3& k : corners)
          EXPECT_TRUE(std::any_of(theirs.begin(), theirs.end(), [&](const Vec3& q) { return q.x == k.x && q.y == k.y && q.z == k.z; }))
              << "a corner of the hull that is no portal's";
        // Every portal corner on the hull's side of each of its edges (within a rounding).
        const Vec3 unit_n = (1 / length(n)) * n;
        for (const Vec3& q : theirs)
          for (size_t e = 0; e < corners.size(); ++e) {
            const Vec3 a = corners[e], b = corners[(e + 1) % corners.size()];
            EXPECT_GE(dot(cross(b - a, q - a), unit_n), -1e-9) << "a portal's corner outside the hull";
          }
        joined += portals > 1;
        largest = std::max(largest, portals);
      }
  EXPECT_GT(joined, 0u);
  EXPECT_GE(largest, 9u) << "the nine openings into the cell over the slab";
  // The neighbours the merged search asks about (PortalTable::listed): per cell, the first
  // of each face's portals into one cell, in the order of Cell::portals, then -1s.
  for (CellId id = 0; id < CellId(c.cells.size()); ++id) {
    const int32_t f0 = t.cell_faces[size_t(id)], f1 = t.cell_faces[size_t(id) + 1];
    auto face_of = [&](int32_t entry) {
      int32_t f = f0;
      while (f + 1 < f1 && t.face_seen[size_t(f) + 1] <= entry) ++f;
      return f;
    };
    std::vector<int32_t> expected;
    std::set<std::pair<CellId, int32_t>> named;
    for (PortalId pi : c.cells[size_t(id)].portals)
      for (int32_t i = t.face_seen[size_t(f0)]; i < t.face_seen[size_t(f1)]; ++i)
        if (t.seen[size_t(i)].portal == pi) {
          if (named.insert({t.seen[size_t(i)].other, face_of(i)}).second) expected.push_back(i);
          break;
        }
    std::vector<int32_t> listed(t.listed.begin() + t.face_seen[size_t(f0)], t.listed.begin() + t.face_seen[size_t(f1)]);
    expected.resize(listed.size(), -1);
    EXPECT_EQ(listed, expected) << "cell " << id;
  }
  // From under the slab, looking up through it: the hull search with and without the
  // hulls (a copy of the complex whose table names none) finds the same cells here, with
  // fewer portals tested.
  CellComplex each = c;
  std::fill(each.portal_table.face_hulls.begin(), each.portal_table.face_hulls.end(), 0);
  const Vec3 eye{3, 0.5, 1};
  const CellId cell = c.locate(eye).cell;
  ASSERT_NE(cell, kNoCell);
  Camera cam = Camera::look_at(eye, {3, 3, 3}, 90, 96, 64);
  TraverseParams hull;
  hull.merge_pieces = hull.hull_pieces = true;
  const VisibleSet once = find_visible(c, cam, cell, hull), apart = find_visible(each, cam, cell, hull);
  EXPECT_EQ(once.cells, apart.cells);
  EXPECT_LT(once.portals_tested, apart.portals_tested);
  // Random views: Jones's and the merged search against ray casting, and the hull search
  // (through the hulls) holding the merged one's view with the same pictures.
  expect_soup_views_agree_with_rays(c, 16, 1871, 96, 64, 8);
}

// Tests of closed curved solids drawn as detail (cells/closed_surface.h, the soup's
// MeshSceneParams::curved_directions): which solids are curved, the surface's inside and
// segment tests against the sphere they approximate, the scene's cells and pictures
// against the same solid cut into space, the walker kept out of it, and a saved complex.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "cells/build_cells.h"
#include "cells/closed_surface.h"
#include "cells/mesh_scene.h"
#include "cells/soup_detail.h"
#include "detail_checks.h"
#include "picture_checks.h"
#include "render/furniture.h"
#include "render/halftone.h"
#include "render/scene_objects.h"
#include "tests/test_meshes.h"
#include "visibility/visible_set.h"
#include "visibility/walker.h"

using namespace avenues;
using avenues::testing::icosphere;
using avenues::testing::mesh_from;

namespace {

/// A closed prism of n sides about the z axis through c, radius r, from z0 to z1
/// (counter-clockwise seen from outside).
Mesh column(Vec3 c, double r, double z0, double z1, int n) {
  std::vector<Vec3> v;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * i / n;
    v.push_back({c.x + r * std::cos(a), c.y + r * std::sin(a), z0});
  }
  for (int i = 0; i < n; ++i) v.push_back({v[size_t(i)].x, v[size_t(i)].y, z1});
  std::vector<std::vector<int>> polygons;
  std::vector<int> bottom, top;
  for (int i = n - 1; i >= 0; --i) bottom.push_back(i);
  for (int i = 0; i < n; ++i) top.push_back(n + i);
  polygons.push_back(bottom);
  polygons.push_back(top);
  for (int i = 0; i < n; ++i) polygons.push_back({i, (i + 1) % n, n + (i + 1) % n, n + i});
  return mesh_from(v, polygons);
}

/// A closed flight of `steps` steps (0.25 m deep, 0.18 m high, 1 m wide) along x: a
/// building's solid, many planes facing six ways.
Mesh stair(int steps) {
  std::vector<Vec3> profile;  // in the xz-plane, counter-clockwise seen from −y
  profile.push_back({0, 0, 0});
  profile.push_back({0.25 * steps, 0, 0});
  for (int i = steps; i >= 1; --i) {
    profile.push_back({0.25 * i, 0, 0.18 * i});
    profile.push_back({0.25 * (i - 1), 0, 0.18 * i});
  }
  const int n = int(profile.size());
  std::vector<Vec3> v = profile;
  for (const Vec3& p : profile) v.push_back({p.x, 1, p.z});
  std::vector<std::vector<int>> polygons;
  // The side faces are not convex: a rectangle a step, each side.
  for (int i = 1; i <= steps; ++i) {
    const double x0 = 0.25 * (i - 1), x1 = 0.25 * i, z = 0.18 * i;
    for (double y : {0.0, 1.0}) {
      const int b = int(v.size());
      v.insert(v.end(), {{x0, y, 0}, {x1, y, 0}, {x1, y, z}, {x0, y, z}});
      if (y == 0)
        polygons.push_back({b, b + 1, b + 2, b + 3});
      else
        polygons.push_back({b, b + 3, b + 2, b + 1});
    }
  }
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    polygons.push_back({i, n + i, n + j, j});
  }
  return mesh_from(v, polygons);
}

const ClosedSolid& only_solid(const std::vector<ClosedSolid>& solids) {
  EXPECT_EQ(solids.size(), 1u);
  return solids.front();
}

}  // namespace

// A smooth surface's facets face as many ways as they lie in planes; a building's solid
// lies in many planes facing a few ways. Only the first is curved.
TEST(CurvedSolid, ManyFacetsFacingManyWaysAreCurvedManyPlanesFacingFewWaysAreNot) {
  const std::vector<ClosedSolid> sphere = closed_solids({icosphere({0, 0, 1}, 1, 2)});
  EXPECT_TRUE(is_curved(only_solid(sphere), 32));
  EXPECT_FALSE(is_curved(only_solid(sphere), 400));  // 320 facets
  EXPECT_TRUE(is_curved(only_solid(closed_solids({column({0, 0, 0}, 0.3, 0, 3, 48)})), 32));
  EXPECT_FALSE(is_curved(only_solid(closed_solids({column({0, 0, 0}, 0.3, 0, 3, 16)})), 32));
  const std::vector<ClosedSolid> flight = closed_solids({stair(30)});
  ASSERT_EQ(flight.size(), 1u);
  EXPECT_GE(flight[0].triangles.size(), 200u);
  EXPECT_FALSE(is_curved(flight[0], 32));  // 64 planes facing 6 ways
  EXPECT_FALSE(is_curved(only_solid(sphere), 0));
}

// Inside and outside, and where a segment enters, agree with the sphere the facets
// approximate (away from the thin shell between the facets and the sphere), on random
// points and on points whose rays run along the icosahedron's own symmetry.
TEST(CurvedSolid, TheSurfaceTellsInsideFromOutsideAndWhereASegmentEntersIt) {
  const Vec3 c{2, -1, 0.5};
  const double r = 1.5;
  const std::vector<ClosedSolid> solids = closed_solids({icosphere(c, r, 3)});
  ASSERT_EQ(solids.size(), 1u);
  const ClosedSurface s(solids[0].name, solids[0].triangles);
  EXPECT_EQ(s.triangles().size(), 1280u);
  const double inner = 0.99 * r;  // every facet lies between this and r from the centre
  std::mt19937 rng(18);
  std::uniform_real_distribution<double> u(-2 * r, 2 * r);
  int inside = 0, outside = 0;
  for (int i = 0; i < 4000; ++i) {
    const Vec3 p = c + Vec3{u(rng), u(rng), u(rng)};
    const double d = length(p - c);
    if (d > inner && d < r) continue;
    const bool in = d <= inner;
    EXPECT_EQ(s.holds(p), in) << "at distance " << d;
    EXPECT_EQ(winding_number(s.triangles(), p) > 0.5, in);
    (in ? inside : outside)++;
  }
  EXPECT_GT(inside, 200);
  EXPECT_GT(outside, 200);
  // Along the axes and through the icosahedron's corners: rays meet edges and corners.
  for (Vec3 d : {Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}, Vec3{0.8017837257372732, 0.5345224838248488, 0.2672612419124244}})
    for (double k : {0.0, 0.3, 0.9}) {
      EXPECT_TRUE(s.holds(c + k * r * d));
      EXPECT_FALSE(s.holds(c + 1.2 * r * d));
      EXPECT_FALSE(s.holds(c - 1.2 * r * d));
    }
  // Segments from outside towards the centre enter at the surface, its normal facing them;
  // segments leaving it, or passing beside it, are not stopped.
  for (int i = 0; i < 500; ++i) {
    Vec3 d{u(rng), u(rng), u(rng)};
    if (!(length(d) > 0.1)) continue;
    d = (1 / length(d)) * d;
    const Vec3 a = c + 2.5 * r * d, b = c + 0.5 * r * d;
    const SurfaceEntry e = s.entry(a, b);
    ASSERT_TRUE(e.hit);
    const double at = length(a + e.t * (b - a) - c);
    EXPECT_GE(at, inner - 1e-12);
    EXPECT_LE(at, r + 1e-12);
    EXPECT_GT(dot(e.normal, d), 0.9);
    EXPECT_NEAR(length(e.normal), 1, 1e-12);
    EXPECT_FALSE(s.entry(b, a).hit);               // leaving
    EXPECT_FALSE(s.entry(c, c + 0.5 * r * d).hit);  // inside all along
    const Vec3 side = cross(d, std::fabs(d.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0});
    const Vec3 off = c + (1.01 * r / length(side)) * side;
    EXPECT_FALSE(s.entry(off - 3 * r * d, off + 3 * r * d).hit);  // beside it
  }
}

// A sphere alone: it cuts no space (the far box is one cell), its facets are drawn as
// detail, the scene says so, and its pictures are those of the sphere cut into space.
TEST(CurvedSolid, ASphereAloneIsDetailInOneCellAndLooksAsWhenCutIntoSpace) {
  const Mesh sphere = avenues::testing::painted(icosphere({0, 0, 1}, 1.0, 2), "red", {0.8, 0.1, 0.1});
  const std::vector<Mesh> meshes{sphere};
  MeshSceneParams cut;
  cut.curved_directions = 0;
  const CellComplex whole = build_mesh_scene(meshes, cut);
  EXPECT_TRUE(whole.detail_solids.empty());
  EXPECT_GT(whole.cells.size(), 50u);
  const CellComplex c = build_mesh_scene(meshes);
  ASSERT_EQ(c.cells.size(), 1u);
  ASSERT_EQ(c.detail_solids.size(), 1u);
  EXPECT_EQ(c.detail_solids[0].triangles().size(), sphere.triangles.size());
  EXPECT_TRUE(c.lines.empty());  // the detail draws its own
  bool said = false;
  for (const std::string& w : c.warnings)
    said |= w.find(c.detail_solids[0].name() + " (320 triangles) is closed and curved: detail") != std::string::npos;
  EXPECT_TRUE(said);
  const Location centre = c.locate({0, 0, 1});
  EXPECT_EQ(centre.what, Location::What::Solid);
  EXPECT_EQ(centre.solid, c.detail_solids[0].name());
  EXPECT_EQ(c.locate({0, 0, 2.5}).what, Location::What::Cell);
  // A walker stands on the ground the sphere stands on, not on the far box below it.
  double lowest = HUGE_VAL;
  for (Vec3 v : sphere.vertices) lowest = std::min(lowest, v.z);
  EXPECT_NEAR(Walker(c, {0, 0, 2.5}).ground(), lowest, 1e-12);

  avenues::testing::expect_detail_looks_as_cut(whole, c, {Camera::yaw_pitch({-2.5, -1.0, 1.5}, 20, -10, 70, 240, 160),
                                                   Camera::yaw_pitch({0.5, 2.5, 2.8}, -80, -35, 70, 240, 160)});
}

// Walking or flying at a sphere that no cell ends at, the eye stops short of it (by the
// clearance) and is never inside it; sliding, it goes round it. A box beside it still cuts
// space, and an eye may not start inside either.
TEST(CurvedSolid, TheWalkerStopsAtACurvedSolidAsAtAWall) {
  const Mesh sphere = icosphere({0, 0, 1}, 1.0, 3);
  const Mesh box = avenues::testing::box_between({3, -0.5, 0}, {4, 0.5, 1});
  const CellComplex c = build_mesh_scene({sphere, box});
  ASSERT_EQ(c.detail_solids.size(), 1u);
  EXPECT_GT(c.cells.size(), 1u);  // the box cuts space
  EXPECT_EQ(c.locate({3.5, 0, 0.5}).what, Location::What::Solid);
  EXPECT_THROW(Walker(c, {0, 0.2, 1.1}), std::runtime_error);
  for (MoveMode mode : {MoveMode::Fly, MoveMode::Walk}) {
    SCOPED_TRACE(to_string(mode));
    // Fly at the sphere's centre; walk at eye height (1.6 m), above its middle.
    Walker w(c, {-2.5, 0, mode == MoveMode::Fly ? 1.0 : WalkerOptions{}.eye_height});
    w.set_mode(mode);
    double nearest = HUGE_VAL;
    for (int i = 0; i < 200; ++i) {
      w.move({0.05, 0, 0}, 1.0 / 60);
      ASSERT_EQ(c.locate(w.eye()).what, Location::What::Cell);
      nearest = std::min(nearest, length(w.eye() - Vec3{0, 0, 1}));
    }
    if (mode == MoveMode::Walk) {
      // Stopped, a step at most before the clearance short of where the eye (at 1.6 m)
      // or the knee (just above a step) would meet the sphere; the facets lie within 1 cm
      // of the sphere.
      double reach = 0;
      for (double z : {w.options().eye_height, w.options().step_height + 0.02})
        reach = std::max(reach, std::sqrt(1 - (z - 1) * (z - 1)));
      EXPECT_LE(w.eye().x, -reach - w.options().clearance + 0.01);
      EXPECT_GE(w.eye().x, -reach - w.options().clearance - 0.05 - 0.01);
      EXPECT_NEAR(w.eye().y, 0, 1e-9);
    } else {
      // Flying, it slid over the sphere's facets (as along a slanted wall: the clearance
      // is kept ahead of each move and along the horizontal axes), never into it.
      EXPECT_GT(nearest, 1.0);
      EXPECT_GT(w.eye().x, -2.4);
    }
    // Moving at it slantwise, the eye slides past it to the other side.
    Walker side(c, {-2.5, 0.3, mode == MoveMode::Fly ? 1.0 : WalkerOptions{}.eye_height});
    side.set_mode(mode);
    for (int i = 0; i < 400; ++i) {
      side.move({0.05, 0.005, 0}, 1.0 / 60);
      ASSERT_GE(length(side.eye() - Vec3{0, 0, 1}), 0.98);
    }
    EXPECT_GT(side.eye().x, 0) << "it did not slide round the sphere";
  }
}

// A saved complex keeps its detail solids, and they still keep eyes out once loaded.
TEST(CurvedSolid, ASavedComplexKeepsItsCurvedSolids) {
  const CellComplex c = build_mesh_scene({icosphere({0, 0, 1}, 1.0, 2), column({4, 0, 0}, 0.5, 0, 2, 40)});
  ASSERT_EQ(c.detail_solids.size(), 2u);
  const std::string path = (std::filesystem::temp_directory_path() / "avenues_curved_solid_test.cells").string();
  save_cells(c, path);
  const CellComplex again = load_cells(path);
  std::filesystem::remove(path);
  ASSERT_EQ(again.detail_solids.size(), 2u);
  auto sorted = [](std::vector<Triangle3> t) {  // in whatever order each surface's hierarchy keeps them
    auto key = [](const Triangle3& x) {
      return std::array{x[0].x, x[0].y, x[0].z, x[1].x, x[1].y, x[1].z, x[2].x, x[2].y, x[2].z};
    };
    std::sort(t.begin(), t.end(), [&](const Triangle3& a, const Triangle3& b) { return key(a) < key(b); });
    return t;
  };
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(again.detail_solids[i].name(), c.detail_solids[i].name());
    EXPECT_TRUE(sorted(again.detail_solids[i].triangles()) == sorted(c.detail_solids[i].triangles()));
  }
  EXPECT_EQ(again.locate({4, 0, 1}).what, Location::What::Solid);
  EXPECT_EQ(again.locate({4, 0, 1}).solid, c.detail_solids[1].name());
  EXPECT_EQ(again.objects.size(), c.objects.size());
}

// A curved solid's facets are cut to the cells around it and gathered in clusters, but it
// is one closed surface: in the line drawings no side of a cluster is an open edge (a
// side two clusters share is an edge between their facets; a cut along a cell's face is
// none). An open sheet drawn as detail keeps its own boundary, all of it, and no more.
TEST(CurvedSolid, ItsDrawingHasNoEdgeWhereItsFacetsWereCutOrClustered) {
  const Mesh sphere = icosphere({0, 0, 1}, 1.0, 4);  // 5,120 facets: many clusters
  // A box into it whose planes cut the cells around it, and a tilted sheet 1.2 m square
  // above it that is detail (its 1.44 m² under the least area asked of what cuts space,
  // 0.2 of the scene's largest face, 2.3 m²; every face of the box over it) and is cut by
  // the plane of the box's end.
  const Mesh box = avenues::testing::box_between({0.5, -1, 0}, {4, 1, 1.5});
  const Mesh sheet = mesh_from({{-0.6, -0.6, 2.3}, {0.6, -0.6, 2.3}, {0.6, 0.6, 2.2}, {-0.6, 0.6, 2.2}}, {{0, 1, 2, 3}});
  MeshSceneParams p;
  p.detail_above = 0;
  p.structural_share = 0.2;
  p.structural_area_cap = 100;
  const CellComplex c = build_mesh_scene({sphere, box, sheet}, p);
  ASSERT_EQ(c.detail_solids.size(), 1u);
  ASSERT_GT(c.cells.size(), 1u);
  const std::vector<PlacedObject> placed = place_objects(c);
  const Furniture f = furniture_of(c, placed);
  ASSERT_EQ(f.pieces.size(), c.objects.size());
  std::set<CellId> cells;
  size_t sphere_pieces = 0;
  double open_length = 0;
  for (size_t i = 0; i < f.pieces.size(); ++i) {
    const FurniturePiece& piece = f.pieces[i];
    ASSERT_GE(c.objects[i].cell, 0);
    cells.insert(c.objects[i].cell);
    bool of_sphere = false;
    for (Vec3 v : piece.mesh.vertices) of_sphere |= std::fabs(length(v - Vec3{0, 0, 1}) - 1) < 0.01;
    sphere_pieces += of_sphere;
    for (const FurnitureEdge& e : piece.edges) {
      if (e.polygon[1] >= 0) continue;
      const Vec3 a = piece.mesh.vertices[size_t(e.v[0])], b = piece.mesh.vertices[size_t(e.v[1])];
      // Only the sheet's own sides are open.
      const bool on_side = (std::fabs(a.x - b.x) < 1e-9 && std::fabs(std::fabs(a.x) - 0.6) < 1e-9) ||
                           (std::fabs(a.y - b.y) < 1e-9 && std::fabs(std::fabs(a.y) - 0.6) < 1e-9);
      EXPECT_TRUE(on_side) << "an open edge from " << a.x << "," << a.y << "," << a.z << " to " << b.x << "," << b.y
                           << "," << b.z;
      open_length += length(b - a);
    }
  }
  EXPECT_GT(sphere_pieces, 4u);
  EXPECT_GE(cells.size(), 2u);  // the detail was cut to more than one cell
  EXPECT_NEAR(open_length, 2 * 1.2 + 2 * std::hypot(1.2, 0.1), 1e-9);  // the sheet's perimeter
}

// The same 5,400 km from the origin (a model in site coordinates): the sphere is still
// curved (its planes' places, rounded to the scale of their coordinates, do not matter
// when their directions differ), an eye inside it is refused, and a walker flying at it
// never enters it.
TEST(CurvedSolid, FarFromTheOriginItIsStillDetailAndStillStopsTheWalker) {
  const Vec3 centre{5.4e6, -2.5e5, 1};
  const CellComplex c = build_mesh_scene({icosphere(centre, 1.0, 3)});
  ASSERT_EQ(c.detail_solids.size(), 1u);
  EXPECT_EQ(c.cells.size(), 1u);
  EXPECT_EQ(c.locate(centre).what, Location::What::Solid);
  EXPECT_EQ(c.locate(centre + Vec3{0, 0, 1.5}).what, Location::What::Cell);
  const Vec3 start = centre + Vec3{-2.5, 0, 0};
  Walker w(c, start);
  w.set_mode(MoveMode::Fly);
  for (int i = 0; i < 100; ++i) {
    w.move({0.05, 0, 0}, 1.0 / 60);
    ASSERT_GT(length(w.eye() - centre), 1.0);  // never into it; sliding over it as at the origin
  }
  EXPECT_GT(length(w.eye() - start), 1.0);  // it went up to the sphere
}

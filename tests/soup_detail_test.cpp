// Tests of cells/soup_detail.h: a large soup's small polygons as detail, drawn in the cells
// they cross and cutting no space. The scene: a grid of open boxes (the polygons that cut
// space) and thin bars standing in and across them, some tilted (detail), decomposed once
// whole and once split (MeshSceneParams::detail_above lowered so that a small scene
// splits). Detail must keep every bit of its area, in the cells it lies in; the search
// must stay conservative; and the pictures must be the whole soup's, up to the renderer's
// edge error.
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <string>

#include "cells/build_cells.h"
#include "cells/mesh_scene.h"
#include "cells/soup_detail.h"
#include "plans/formats/ifc_building.h"
#include "hull_checks.h"
#include "detail_checks.h"
#include "picture_checks.h"
#include "ray_oracle.h"
#include "render/halftone.h"
#include "render/scene_objects.h"
#include "tests/test_meshes.h"
#include "visibility/viewpoint.h"
#include "visibility/visible_set.h"

using namespace avenues;
using avenues::testing::icosphere;
using avenues::testing::mesh_from;

namespace {

Vec3 unit(Vec3 v) { return (1 / length(v)) * v; }

/// The materials of boxes_and_bars: grey boxes, a red bar along the first row, blue
/// upright bars, green bars along the other rows and leaning.
enum BarMaterial : MaterialId { kBox, kRowBar, kUprightBar, kLeaningBar };

/// k × k open boxes 1 m wide and high, 2 m apart (a floor and four walls each), and
/// through them bars 4 cm thick: upright in each box, lying across each row of boxes at
/// half height (crossing their walls), and one leaning across the whole grid.
std::vector<Mesh> boxes_and_bars(int k) {
  std::vector<Vec3> v;
  std::vector<std::vector<int>> polygons;
  std::vector<MaterialId> material;  // per polygon
  MaterialId now = kBox;
  auto quad = [&](Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
    const int n = int(v.size());
    v.insert(v.end(), {a, b, c, d});
    polygons.push_back({n, n + 1, n + 2, n + 3});
    material.push_back(now);
  };
  auto bar = [&](Vec3 a, Vec3 b, double t) {  // a closed square bar from a to b, t thick
    const Vec3 d = unit(b - a);
    const Vec3 u = unit(cross(d, std::fabs(d.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0}));
    const Vec3 w = cross(d, u);
    Vec3 c[8];
    for (int i = 0; i < 8; ++i)
      c[i] = (i & 4 ? b : a) + (i & 1 ? t / 2 : -t / 2) * u + (i & 2 ? t / 2 : -t / 2) * w;
    quad(c[0], c[2], c[3], c[1]), quad(c[4], c[5], c[7], c[6]);
    quad(c[0], c[1], c[5], c[4]), quad(c[2], c[6], c[7], c[3]);
    quad(c[0], c[4], c[6], c[2]), quad(c[1], c[3], c[7], c[5]);
  };
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) {
      const double x = 2.0 * i, y = 2.0 * j;
      quad({x, y, 0}, {x + 1, y, 0}, {x + 1, y + 1, 0}, {x, y + 1, 0});
      quad({x, y, 0}, {x + 1, y, 0}, {x + 1, y, 1}, {x, y, 1});
      quad({x + 1, y, 0}, {x + 1, y + 1, 0}, {x + 1, y + 1, 1}, {x + 1, y, 1});
      quad({x + 1, y + 1, 0}, {x, y + 1, 0}, {x, y + 1, 1}, {x + 1, y + 1, 1});
      quad({x, y + 1, 0}, {x, y, 0}, {x, y, 1}, {x, y + 1, 1});
      now = kUprightBar;
      bar({x + 0.3, y + 0.4, 0}, {x + 0.3, y + 0.4, 1.4}, 0.04);
      now = kBox;
    }
  for (int j = 0; j < k; ++j) {
    now = j == 0 ? kRowBar : kLeaningBar;
    bar({-0.5, 2.0 * j + 0.6, 0.5}, {2.0 * k - 0.5, 2.0 * j + 0.6, 0.5}, 0.04);
  }
  now = kLeaningBar;
  bar({-0.4, -0.4, 0.2}, {2.0 * k - 0.6, 2.0 * k - 0.6, 1.3}, 0.04);
  Mesh m = mesh_from(v, polygons);
  m.materials.resize(4);
  m.materials[kRowBar].colour = {0.8, 0.1, 0.1};
  m.materials[kUprightBar].colour = {0.1, 0.1, 0.8};
  m.materials[kLeaningBar].colour = {0.1, 0.8, 0.1};
  for (int p : m.polygon_of) m.material_of.push_back(material[size_t(p)]);
  return {m};
}

/// The split: the boxes' 10 triangles each cut space, every bar is detail.
MeshSceneParams split_params(int k) {
  MeshSceneParams p;
  p.detail_above = 0;
  p.structural_triangles = size_t(10 * k * k);
  return p;
}

double area_of(const Mesh& m) {
  double a = 0;
  for (const auto& t : m.triangles)
    a += 0.5 * length(cross(m.vertices[size_t(t[1])] - m.vertices[size_t(t[0])],
                            m.vertices[size_t(t[2])] - m.vertices[size_t(t[0])]));
  return a;
}

}  // namespace

// The largest polygons cut space up to the budget; the rest, whole polygons, are detail.
TEST(SoupDetail, TheLargestPolygonsCutSpaceUpToTheBudgetAndWholePolygonsAreDetail) {
  std::vector<SoupTriangle> soup;
  std::vector<int64_t> polygon;
  // Polygon p (0..5) is a square of side p + 1, two triangles; polygon 6 has no area.
  for (int p = 0; p < 6; ++p) {
    const double s = p + 1;
    soup.push_back({{Vec3{0, 0, double(p)}, Vec3{s, 0, double(p)}, Vec3{s, s, double(p)}}});
    soup.push_back({{Vec3{0, 0, double(p)}, Vec3{s, s, double(p)}, Vec3{0, s, double(p)}}});
    polygon.insert(polygon.end(), {p, p});
  }
  soup.push_back({{Vec3{0, 0, 9}, Vec3{1, 0, 9}, Vec3{2, 0, 9}}});
  polygon.push_back(6);
  const SoupSplit none = split_detail(soup, polygon, 12, 4);
  EXPECT_EQ(none.detail_triangles, 0u);
  EXPECT_EQ(none.structural, 12u);
  for (bool d : none.detail) EXPECT_FALSE(d);
  // Budget 5: the squares of side 6 and 5 (4 triangles); the next would make 6.
  const SoupSplit s = split_detail(soup, polygon, 11, 5);
  EXPECT_EQ(s.structural, 4u);
  EXPECT_EQ(s.detail_triangles, 8u);
  EXPECT_DOUBLE_EQ(s.smallest_structural, 25.0);
  for (size_t t = 0; t < 12; ++t) EXPECT_EQ(s.detail[t], polygon[t] < 4) << "triangle " << t;
  EXPECT_TRUE(s.detail[12]) << "a polygon with no area is no larger than any other";
}

// A polygon smaller than the least area that cuts space is detail however much of the
// budget is left; a soup of such polygons alone cuts no space.
TEST(SoupDetail, PolygonsTooSmallToHideMuchCutNoSpace) {
  std::vector<SoupTriangle> soup;
  std::vector<int64_t> polygon;
  for (int p = 0; p < 4; ++p) {  // squares of side 1, 2, 3, 4: areas 1, 4, 9, 16 m²
    const double s = p + 1;
    soup.push_back({{Vec3{0, 0, double(p)}, Vec3{s, 0, double(p)}, Vec3{s, s, double(p)}}});
    soup.push_back({{Vec3{0, 0, double(p)}, Vec3{s, s, double(p)}, Vec3{0, s, double(p)}}});
    polygon.insert(polygon.end(), {p, p});
  }
  const SoupSplit s = split_detail(soup, polygon, 0, 100, 5.0);
  EXPECT_EQ(s.structural, 4u);
  EXPECT_EQ(s.detail_triangles, 4u);
  for (size_t t = 0; t < soup.size(); ++t) EXPECT_EQ(s.detail[t], polygon[t] < 2) << "triangle " << t;
  const SoupSplit none = split_detail(soup, polygon, 0, 100, 20.0);
  EXPECT_EQ(none.structural, 0u);
  EXPECT_EQ(none.detail_triangles, 8u);
}

// A wall's face with a door in it, as BIM tools and Assimp hand it over: a fan of
// triangles, each its own polygon, some large and some small. Ranked one by one, its small
// triangles would be detail while its large ones cut: a wall with holes punched in it. Its
// flat surface is one (with a neighbour a rounding off its plane), ranked and cut whole; a
// wall at right angles sharing its edge, and a coplanar face apart from it, are surfaces
// of their own.
TEST(SoupDetail, AWallsFaceCutsSpaceWholeOrNotAtAll) {
  std::vector<SoupTriangle> soup;
  std::vector<int64_t> polygon;
  auto add = [&](Vec3 a, Vec3 b, Vec3 c) {
    polygon.push_back(int64_t(soup.size()));
    soup.push_back({{a, b, c}});
  };
  // The face y = 0, x in [0, 4], z in [0, 3], a door x in [1, 2], z in [0, 2]: six
  // triangles from 0.5 m² to 3 m² (10 m² in all).
  const Vec3 o{0, 0, 0}, p{1, 0, 0}, q{1, 0, 2}, r{2, 0, 2}, s2{2, 0, 0}, e{4, 0, 0}, f{4, 0, 3}, g{0, 0, 3};
  add(o, p, q), add(o, q, g), add(q, r, g), add(r, f, g), add(r, s2, f), add(s2, e, f);
  // A rounding off the plane: a sliver of a triangle on the door's head, sharing edge q–r.
  add(q, Vec3{1.5, 1e-13, 2.3}, r);  // 0.15 m²
  // A wall at right angles along the face's end x = 4 (4.5 m²): its own surface.
  add(e, Vec3{4, 3, 0}, f);
  // A coplanar face 10 m away along the same plane (0.5 m²): its own surface.
  add(Vec3{14, 0, 0}, Vec3{15, 0, 0}, Vec3{15, 0, 1});
  const std::vector<int64_t> surface = flat_surfaces(soup, polygon);
  ASSERT_EQ(surface.size(), soup.size());
  for (size_t t = 1; t < 7; ++t) EXPECT_EQ(surface[t], surface[0]) << "triangle " << t << " is part of the face";
  EXPECT_NE(surface[7], surface[0]) << "the wall at right angles";
  EXPECT_NE(surface[8], surface[0]) << "the coplanar face apart from it";
  EXPECT_NE(surface[7], surface[8]);
  // Triangles of one input polygon are one surface whatever their planes.
  std::vector<int64_t> joined = polygon;
  joined[8] = joined[7];
  const std::vector<int64_t> by_polygon = flat_surfaces(soup, joined);
  EXPECT_EQ(by_polygon[7], by_polygon[8]);
  EXPECT_NE(by_polygon[7], by_polygon[0]);
  // Surfaces from 2 m²: the face (10.15 m², 7 triangles) and the wall at right angles;
  // by single triangles, only 3 of the face's 6 (those of 2 m² and more) and the wall.
  const SoupSplit whole = split_detail(soup, surface, 0, 100, 2.0);
  for (size_t t = 0; t < 8; ++t) EXPECT_FALSE(whole.detail[t]) << "triangle " << t;
  EXPECT_TRUE(whole.detail[8]) << "the 0.5 m² face apart";
  EXPECT_DOUBLE_EQ(whole.smallest_structural, 4.5);
  const SoupSplit alone = split_detail(soup, polygon, 0, 100, 2.0);
  size_t face_detail = 0;
  for (size_t t = 0; t < 6; ++t) face_detail += alone.detail[t];
  EXPECT_EQ(face_detail, 3u) << "ranked one by one, the face would be cut with holes in it";
  // The budget takes a surface whole or not at all. Of 7 triangles: the face, and then the
  // wall would make 8, so nothing smaller is taken.
  const SoupSplit seven = split_detail(soup, surface, 0, 7, 0.0);
  for (size_t t = 0; t < 7; ++t) EXPECT_FALSE(seven.detail[t]) << "triangle " << t;
  EXPECT_TRUE(seven.detail[7]);
  EXPECT_TRUE(seven.detail[8]);
  EXPECT_EQ(seven.structural, 7u);
  // Of 6: the face alone is more than the whole budget and is passed over (it never could
  // cut); the surfaces after it are taken.
  const SoupSplit six = split_detail(soup, surface, 0, 6, 0.0);
  for (size_t t = 0; t < 7; ++t) EXPECT_TRUE(six.detail[t]) << "triangle " << t;
  EXPECT_FALSE(six.detail[7]);
  EXPECT_FALSE(six.detail[8]);
  EXPECT_EQ(six.structural, 2u);
}

// A finely faceted object alone (a sculpture subdivided into a quarter of a million
// facets, Assimp's sample_subdiv.ac: 22,831 cells and two minutes before) cuts no space:
// the far box is one cell, the object its detail, and its pictures are those of the
// object decomposed whole.
TEST(SoupDetail, AFinelyFacetedObjectAloneIsDetailInOneCellAndLooksTheSame) {
  const Mesh sphere = avenues::testing::painted(icosphere({0, 0, 1}, 1.0, 2), "red", {0.8, 0.1, 0.1});  // 320 triangles of about 0.04 m²
  const std::vector<Mesh> meshes{sphere};
  MeshSceneParams cut;  // the sphere is closed and curved: cut into space only when asked
  cut.curved_directions = 0;
  const CellComplex whole = build_mesh_scene(meshes, cut);
  EXPECT_TRUE(whole.objects.empty());
  EXPECT_GT(whole.cells.size(), 50u);
  MeshSceneParams p = cut;
  p.detail_above = 0;
  p.structural_share = 0.05;  // the box's largest face is 4 m²: facets under 0.2 m² do not cut
  p.structural_area_cap = 1;
  const CellComplex split = build_mesh_scene(meshes, p);
  ASSERT_EQ(split.cells.size(), 1u);
  ASSERT_FALSE(split.objects.empty());
  bool said = false;
  for (const std::string& w : split.warnings)
    said |= w.find("none of its polygons is large enough to cut space") != std::string::npos &&
            w.find("drawn in the one cell they cross") != std::string::npos;
  EXPECT_TRUE(said);
  double pieces = 0;
  for (const Object& o : split.objects) pieces += area_of(*o.model);
  EXPECT_NEAR(pieces, area_of(meshes[0]), 1e-9 * area_of(meshes[0]));
  avenues::testing::expect_detail_looks_as_cut(whole, split, {Camera::yaw_pitch({-2.5, -1.0, 1.5}, 20, -10, 70, 240, 160),
                                                   Camera::yaw_pitch({0.5, 2.5, 2.8}, -80, -35, 70, 240, 160)});
}

// Every detail triangle is kept, cut to the cells it crosses: the pieces cover its area,
// each lies in its own cell, and the split complex is sound and says what it did.
TEST(SoupDetail, DetailIsCutToTheCellsItCrossesAndKeepsEveryBitOfItsArea) {
  const int k = 3;
  const std::vector<Mesh> meshes = boxes_and_bars(k);
  const CellComplex whole = build_mesh_scene(meshes);
  const CellComplex split = build_mesh_scene(meshes, split_params(k));
  EXPECT_TRUE(whole.objects.empty());
  EXPECT_LT(split.cells.size(), whole.cells.size()) << "the bars no longer cut space";
  ASSERT_FALSE(split.objects.empty());
  bool said = false;
  for (const std::string& w : split.warnings) said |= w.find("are detail") != std::string::npos;
  EXPECT_TRUE(said);
  // The bars' area: every polygon but the boxes' 5 k² unit squares.
  double bars = area_of(meshes[0]) - 5.0 * k * k;
  double pieces = 0;
  for (const Object& o : split.objects) {
    ASSERT_GE(o.cell, 0);
    ASSERT_LT(size_t(o.cell), split.cells.size());
    ASSERT_TRUE(o.model);
    EXPECT_LE(o.model->triangles.size(), 256u) << o.name << ": clusters are compact";
    EXPECT_FALSE(o.model->closed);
    pieces += area_of(*o.model);
    for (Vec3 p : o.model->vertices) EXPECT_TRUE(split.cells[size_t(o.cell)].contains(p, 1e-9)) << o.name;
  }
  EXPECT_NEAR(pieces, bars, 1e-9 * bars);
  // Saved and loaded, each object keeps its cell.
  const CellComplex again = cells_from_bytes(cells_bytes(split), "split.cells");
  ASSERT_EQ(again.objects.size(), split.objects.size());
  for (size_t i = 0; i < again.objects.size(); ++i) {
    EXPECT_EQ(again.objects[i].cell, split.objects[i].cell);
    ASSERT_TRUE(again.objects[i].model);
    EXPECT_EQ(again.objects[i].model->triangles.size(), split.objects[i].model->triangles.size());
  }
}

// A cell holding much detail holds it in compact clusters, each an object with its own
// box: at most 256 triangles each, every input polygon's pieces in one, all of the area
// kept, each cluster spanning part of the cloud, the same clusters every time.
TEST(SoupDetail, ACellsDetailComesInCompactClusters) {
  // A floor 12 m square (the only polygon that cuts space) and 900 small tilted squares
  // (bolts, plates) scattered over 10 × 10 × 3 m above it, one input polygon each.
  std::vector<Vec3> v{{-1, -1, 0}, {11, -1, 0}, {11, 11, 0}, {-1, 11, 0}};
  std::vector<std::vector<int>> polygons{{0, 1, 2, 3}};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> at(0, 10), up(0.5, 3), turn(0, 6.283);
  for (int i = 0; i < 900; ++i) {
    const Vec3 c{at(rng), at(rng), up(rng)};
    const double a = turn(rng), b = 0.3 * turn(rng);
    const Vec3 e1{0.05 * std::cos(a), 0.05 * std::sin(a), 0}, e2{-0.05 * std::sin(a) * std::cos(b), 0.05 * std::cos(a) * std::cos(b), 0.05 * std::sin(b)};
    const int n = int(v.size());
    v.insert(v.end(), {c - e1 - e2, c + e1 - e2, c + e1 + e2, c - e1 + e2});
    polygons.push_back({n, n + 1, n + 2, n + 3});
  }
  const std::vector<Mesh> meshes{mesh_from(v, polygons)};
  MeshSceneParams params;
  params.detail_above = 0;
  params.structural_triangles = 2;
  const CellComplex split = build_mesh_scene(meshes, params);
  ASSERT_FALSE(split.objects.empty());
  double area = 0, cloud_side = 0;
  Box3 cloud;
  for (size_t i = 1; i < polygons.size(); ++i)
    for (int k : polygons[i]) cloud.add(v[size_t(k)]);
  cloud_side = std::max({cloud.hi.x - cloud.lo.x, cloud.hi.y - cloud.lo.y, cloud.hi.z - cloud.lo.z});
  std::map<CellId, int> clusters_in;
  std::map<std::pair<CellId, std::array<double, 3>>, std::string> cluster_of;  // (cell, polygon's light point): the object
  for (const Object& o : split.objects) {
    ASSERT_TRUE(o.model);
    const Mesh& m = *o.model;
    EXPECT_LE(m.triangles.size(), 256u) << o.name;
    ++clusters_in[o.cell];
    area += area_of(m);
    Box3 box;
    for (Vec3 p : m.vertices) box.add(p);
    EXPECT_LE(std::max({box.hi.x - box.lo.x, box.hi.y - box.lo.y, box.hi.z - box.lo.z}), 0.75 * cloud_side) << o.name;
    for (Vec3 l : m.polygon_light) {
      const auto [it, added] = cluster_of.try_emplace({o.cell, {l.x, l.y, l.z}}, o.name);
      EXPECT_TRUE(added || it->second == o.name) << "an input polygon's pieces in one cell are split between "
                                                 << it->second << " and " << o.name;
    }
  }
  int most = 0;
  for (const auto& [cell, n] : clusters_in) most = std::max(most, n);
  EXPECT_GE(most, 4) << "900 squares (1,800 triangles) in few cells come in several clusters";
  EXPECT_NEAR(area, 900 * 0.01, 1e-9 * 9) << "every square's area is kept";
  const CellComplex again = build_mesh_scene(meshes, params);
  ASSERT_EQ(again.objects.size(), split.objects.size());
  for (size_t i = 0; i < again.objects.size(); ++i) {
    EXPECT_EQ(again.objects[i].name, split.objects[i].name);
    EXPECT_EQ(again.objects[i].model->triangles.size(), split.objects[i].model->triangles.size());
  }
}

// From eyes in free space, the split complex's search misses no cell a ray reaches, and
// its pictures (merged and hull searches) are the whole soup's, differing only on edges.
TEST(SoupDetail, ThePicturesAreTheWholeSoupsAndTheSearchMissesNoCell) {
  const int k = 3;
  const std::vector<Mesh> meshes = boxes_and_bars(k);
  const CellComplex whole = build_mesh_scene(meshes);
  const CellComplex split = build_mesh_scene(meshes, split_params(k));
  const std::vector<PlacedObject> no_objects, detail = place_objects(split);
  std::mt19937 rng(16);
  std::uniform_real_distribution<double> x(-1.5, 2.0 * k + 0.5), z(0.1, 2.5), yaw(0, 360), pitch(-50, 30);
  int views = 0;
  long pixels = 0, differ = 0, polygons_dropping = 0, polygons_all = 0;
  while (views < 12) {
    const Vec3 eye{x(rng), x(rng), z(rng)};
    const Location in_whole = whole.locate(eye), in_split = split.locate(eye);
    if (in_whole.what != Location::What::Cell) continue;  // inside a bar
    ASSERT_EQ(in_split.what, Location::What::Cell);
    const Camera cam = Camera::yaw_pitch(eye, yaw(rng), pitch(rng), 70, 240, 160);
    SCOPED_TRACE("eye " + std::to_string(eye.x) + "," + std::to_string(eye.y) + "," + std::to_string(eye.z));
    ++views;
    // Lit by ambient light alone, each sample shows its surface's material as it is: the
    // pictures say which surface is seen where, and nothing of how a shade was found.
    HalftoneOptions o;
    o.threads = 1;
    o.shading.back = 1;
    TraverseParams merged;
    merged.merge_pieces = true;
    Image truth;
    render_view(whole, no_objects, cam, find_visible(whole, cam, in_whole.cell, merged), o, truth);
    for (bool hull : {false, true}) {
      SCOPED_TRACE(hull ? "hull search" : "merged search");
      TraverseParams p = merged;
      p.hull_pieces = hull;
      const VisibleSet vs = find_visible(split, cam, in_split.cell, p);
      EXPECT_EQ(avenues::testing::check_visible_set(split, cam, vs, 4).missing, 0);
      Image pic;
      RenderStats dropping;
      render_view(split, detail, cam, vs, o, pic, &dropping);
      if (hull) {
        // Resolved by depth alone, dropping what lies behind polygons already drawn
        // changes no byte of the picture.
        HalftoneOptions every = o;
        every.drop_hidden = false;
        Image reference;
        RenderStats all;
        render_view(split, detail, cam, vs, every, reference, &all);
        EXPECT_TRUE(pic.data == reference.data) << "dropping hidden polygons changed the picture";
        polygons_dropping += dropping.polygons, polygons_all += all.polygons;
      }
      const avenues::testing::PictureDifference d = avenues::testing::compare_off_edges(truth, pic);
      EXPECT_EQ(d.off_edges, 0) << "the pictures differ in " << d.off_edges << " pixels away from every edge";
      EXPECT_LE(d.differ, d.pixels / 200) << "the pictures differ in " << d.differ << " pixels";
      pixels += d.pixels, differ += d.differ;
    }
  }
  RecordProperty("pixels_differ", std::to_string(differ) + " of " + std::to_string(pixels));
  // Bars behind the boxes' walls and behind each other: many are dropped.
  EXPECT_LT(polygons_dropping, polygons_all);
  RecordProperty("polygons", std::to_string(polygons_dropping) + " of " + std::to_string(polygons_all));
}

// Each piece of a detail polygon is lit from the whole polygon's centroid: a bar lying
// across the cells of a row of boxes shows one shade on each of its faces, with no seam
// where it passes from one cell to the next. Lit piece by piece, it would show seams.
// (The whole soup's picture shows as many shades, not quite the same ones: it lights
// coplanar faces of one material as one surface, so the three row bars' tops as one.)
TEST(SoupDetail, APolygonCutIntoManyCellsTakesOneShade) {
  const int k = 3;
  const std::vector<Mesh> meshes = boxes_and_bars(k);
  const CellComplex whole = build_mesh_scene(meshes);
  const CellComplex split = build_mesh_scene(meshes, split_params(k));
  const Camera cam = Camera::yaw_pitch({2.5, -1.0, 2.2}, 90, -50, 80, 320, 200);
  std::vector<PlacedObject> piecewise = place_objects(split);
  for (PlacedObject& o : piecewise) o.mesh.polygon_light.clear();
  auto red_shades = [&](const CellComplex& c, const std::vector<PlacedObject>& objects) {
    const Location at = c.locate(cam.eye);
    EXPECT_EQ(at.what, Location::What::Cell);
    TraverseParams p;
    p.merge_pieces = true;
    HalftoneOptions o;
    o.threads = 1;
    Image pic;
    render_view(c, objects, cam, find_visible(c, cam, at.cell, p), o, pic);
    std::set<std::array<uint8_t, 3>> red;
    for (size_t i = 0; i + 2 < pic.data.size(); i += 3)
      if (pic.data[i] > 2 * pic.data[i + 1] + 8 && pic.data[i] > 2 * pic.data[i + 2] + 8)
        red.insert({pic.data[i], pic.data[i + 1], pic.data[i + 2]});
    return red;
  };
  const auto whole_shades = red_shades(whole, {});
  const auto split_shades = red_shades(split, place_objects(split));
  const auto piece_shades = red_shades(split, piecewise);
  EXPECT_GE(whole_shades.size(), 2u) << "two faces of the row bar are in view";
  EXPECT_EQ(split_shades.size(), whole_shades.size()) << "one shade per face";
  EXPECT_GT(piece_shades.size(), split_shades.size()) << "lit piece by piece, the pieces differ";
}

// A soup under the count that splits a large one, whose planes cut space into more pieces
// than the decomposition is given (cluttered), is split too: the first try is abandoned,
// and a quarter of its triangles cut space at each try until the tree fits.
TEST(SoupDetail, AClutteredSoupIsSplitTooAndSaysSo) {
  const int k = 3;
  const std::vector<Mesh> meshes = boxes_and_bars(k);
  MeshSceneParams whole_params;
  whole_params.leaf_budget = 0;
  const CellComplex whole = build_mesh_scene(meshes, whole_params);
  EXPECT_TRUE(whole.objects.empty());
  MeshSceneParams p;
  p.leaf_budget = 40;
  const CellComplex split = build_mesh_scene(meshes, p);
  ASSERT_FALSE(split.objects.empty());
  EXPECT_LT(split.cells.size(), whole.cells.size());
  bool said = false, abandoned = false;
  for (const std::string& w : split.warnings) said |= w.find("into more than 40 pieces") != std::string::npos;
  for (const StageTime& t : split.timings) abandoned |= t.stage == "decompose, abandoned";
  EXPECT_TRUE(said);
  EXPECT_TRUE(abandoned);
  // The try that fitted made at most 40 leaves, so at most 40 cells; nothing of the
  // abandoned tries is left in the complex (build_mesh_scene checks its invariants).
  EXPECT_LE(split.cells.size(), 40u);
  double pieces = 0;
  for (const Object& o : split.objects) pieces += area_of(*o.model);
  EXPECT_GT(pieces, area_of(meshes[0]) - 5.0 * k * k - 1e-9) << "every bar is detail, and more";
}

// A Tekla structural model from outside (ISSUE_021: piles, caps, beams, a profiled deck; no
// walls), read as its faces, as `avenues` reads it: 257,118 triangles, split into the
// polygons that cut space and detail. Its large cells of clustered detail are halved at the
// median of their fragments, placed from the fragments' corners as doubles; deep in the
// tree a corner where nearly parallel planes met can have an interval hundreds of metres
// wide, whose middle once put a halving plane outside its cell: "a splitting plane misses
// its cell", with another choice of the polygons that cut (one no option reaches, so that
// failure has no test of its own), and here planes placed metres off (6,448 cells, now
// 6,194). Such corners no longer place it. Its cells are valid, its detail is in them, and
// the eye's place under the deck is in free space.
TEST(SoupDetail, AStructuralModelReadAsItsFacesDecomposesIntoValidCells) {
  const std::filesystem::path file = std::filesystem::path(AVENUES_OUTSIDE_DIR) / "ifc" / "ISSUE_021_Mini_Project.ifc";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << "no " << file;
  std::shared_ptr<const Mesh> faces;
  try {
    (void)read_ifc_building(file.string());
  } catch (const IfcWithoutWalls& e) {
    faces = e.faces;
  }
  ASSERT_TRUE(faces) << "read as a building";
  const CellComplex c = build_mesh_scene({*faces});
  EXPECT_EQ(cells_are_valid(c), "");
  // Its slabs' faces cut space whole (flat_surfaces): about a hundred cells, not the
  // 6,194 of its triangles ranked one by one.
  EXPECT_GT(c.cells.size(), 20u);
  EXPECT_LT(c.cells.size(), 1000u);
  EXPECT_GT(c.objects.size(), 1000u) << "its detail, in the cells it crosses";
  const Vec3 eye = default_viewpoint(c).eye;
  EXPECT_EQ(c.locate(eye).what, Location::What::Cell);
}

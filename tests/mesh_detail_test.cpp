// Tests of coarser mesh levels (plans/mesh_detail.h) and their use in pictures: each level
// has far fewer triangles than a finely tessellated mesh, lies within its tolerance of every
// vertex of the original, keeps each triangle's polygon and material, a mesh too small is
// left alone; a furnished home's walkthrough picture drawn with them differs from the one in
// full only along edges, by the stated fraction of a sample. The walkthrough's last budget
// steps leave out objects beyond a reach of the eye, and only those.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "cells/build_cells.h"
#include "plans/formats/sweet_home.h"
#include "plans/mesh_detail.h"
#include "render/halftone.h"
#include "render/scene_screen.h"
#include "render/scene_objects.h"
#include "visibility/visible_set.h"

using namespace avenues;
namespace fs = std::filesystem;

namespace {

/// A sphere of radius r cut into a latitude-longitude grid of n × 2n quads (two triangles
/// each, one at the poles), the northern half material 0 and the southern material 1.
Mesh sphere(double r, int n) {
  Mesh m;
  m.path = "sphere";
  m.materials = {Material{}, Material{}};
  auto at = [&](int i, int j) { return i == 0 ? 0 : i == n ? 1 + (n - 1) * 2 * n : 1 + (i - 1) * 2 * n + (j % (2 * n)); };
  m.vertices.push_back({0, 0, r});
  for (int i = 1; i < n; ++i)
    for (int j = 0; j < 2 * n; ++j) {
      const double th = M_PI * i / n, ph = M_PI * j / n;
      m.vertices.push_back({r * std::sin(th) * std::cos(ph), r * std::sin(th) * std::sin(ph), r * std::cos(th)});
    }
  m.vertices.push_back({0, 0, -r});
  int polygon = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < 2 * n; ++j) {
      const int a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      const MaterialId mat = i < n / 2 ? 0 : 1;
      auto add = [&](std::array<int, 3> t) {
        m.triangles.push_back(t);
        m.polygon_of.push_back(polygon);
        m.material_of.push_back(mat);
      };
      if (i > 0) add({a, b, d});
      if (i < n - 1) add({d, b, c});
      ++polygon;
    }
  m.closed = true;
  smooth_corner_normals(m);
  return m;
}

double point_triangle_distance(Vec3 p, Vec3 a, Vec3 b, Vec3 c) {
  // The closest point by the triangle's Voronoi regions (Ericson, Real-Time Collision Detection, 5.1.5).
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return length(p - a);
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return length(p - b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return length(p - (a + (d1 / (d1 - d3)) * ab));
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return length(p - c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return length(p - (a + (d2 / (d2 - d6)) * ac));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) return length(p - (b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b)));
  const double denom = 1 / (va + vb + vc);
  return length(p - (a + (vb * denom) * ab + (vc * denom) * ac));
}

double distance_to(const Mesh& m, Vec3 p) {
  double best = HUGE_VAL;
  for (const auto& t : m.triangles)
    best = std::min(best, point_triangle_distance(p, m.vertices[size_t(t[0])], m.vertices[size_t(t[1])],
                                                  m.vertices[size_t(t[2])]));
  return best;
}

}  // namespace

TEST(MeshDetail, AFineSphereHasCoarserLevelsWithinTheirTolerances) {
  const Mesh fine = sphere(0.5, 40);  // 6,240 triangles, edges about 4 cm
  const std::vector<MeshLevel> levels = coarser_levels(fine, {0.001, 0.004, 0.016});
  ASSERT_EQ(levels.size(), 3u);
  size_t before = fine.triangles.size();
  for (const MeshLevel& l : levels) {
    SCOPED_TRACE("tolerance " + std::to_string(l.tolerance));
    EXPECT_LT(4 * l.mesh.triangles.size(), 3 * before);  // each at least a quarter smaller
    before = l.mesh.triangles.size();
    ASSERT_EQ(l.mesh.polygon_of.size(), l.mesh.triangles.size());
    ASSERT_EQ(l.mesh.material_of.size(), l.mesh.triangles.size());
    ASSERT_EQ(l.mesh.corner_normals.size(), 3 * l.mesh.triangles.size());
    EXPECT_TRUE(l.mesh.closed);
    // Every vertex of the original lies within the tolerance of the level's surface (the
    // levels are made in one pass, so this holds for the last as for the first).
    double worst = 0;
    for (const Vec3& v : fine.vertices) worst = std::max(worst, distance_to(l.mesh, v));
    EXPECT_LE(worst, l.tolerance * (1 + 1e-9)) << worst;
    // Triangles keep their polygon's material: the north stays 0, the south 1.
    for (size_t t = 0; t < l.mesh.triangles.size(); ++t) {
      Vec3 c{0, 0, 0};
      for (int k = 0; k < 3; ++k) c = c + (1.0 / 3) * l.mesh.vertices[size_t(l.mesh.triangles[t][size_t(k)])];
      if (std::fabs(c.z) > 0.05) {
        EXPECT_EQ(l.mesh.material_of[t], c.z > 0 ? 0 : 1) << "triangle " << t;
      }
    }
    std::printf("  tolerance %.3f m: %zu of %zu triangles, farthest original vertex %.5f m away\n", l.tolerance,
                l.mesh.triangles.size(), fine.triangles.size(), worst);
  }
  EXPECT_LT(levels.back().mesh.triangles.size(), fine.triangles.size() / 10);
}

TEST(MeshDetail, AMeshWithFewTrianglesOrNoneToSpareHasNoLevels) {
  EXPECT_TRUE(coarser_levels(sphere(0.5, 4), {0.001, 0.01}).empty());  // 48 triangles, under the minimum
  // A tolerance far below the tessellation's error removes (almost) nothing: no level.
  EXPECT_TRUE(coarser_levels(sphere(0.5, 40), {1e-9}).empty());
  EXPECT_TRUE(coarser_levels(Mesh{}, {0.01}).empty());
}

// A furnished home (Sweet Home 3D's round-wall apartment: 221,187 furniture triangles) in
// the walkthrough's picture, 1280 × 720, from its stored camera and from three more eyes:
// with coarser furniture where it moves the picture by under half a sample, fewer polygons
// are drawn, and the picture differs from the one in full only in a few samples along edges.
TEST(MeshDetail, AFurnishedHomeDrawnWithCoarserFurnitureDiffersOnlyAlongEdges) {
  const fs::path home = fs::path(AVENUES_SH3D_EXAMPLES) / "1BedroomApartmentWithRoundWall.xml";
  if (!fs::exists(home)) GTEST_SKIP() << "no " << home;
  const CellComplex c = build_cells(read_sweet_home(home.string()));
  const std::vector<PlacedObject> full = place_objects(c), coarse = place_objects(c, nullptr, true);
  size_t levels = 0;
  for (const PlacedObject& o : coarse) levels += o.coarser.size();
  EXPECT_GT(levels, 20u);
  ASSERT_TRUE(c.view.has_value());
  const Viewpoint& vp = *c.view;
  std::vector<Camera> cams{Camera::look_at(vp.eye, vp.look, vp.fov_deg, 1280, 720)};
  for (double yaw : {0.0, 120.0, 240.0}) cams.push_back(Camera::yaw_pitch(vp.eye, yaw, -10, 60, 1280, 720));
  long polygons_full = 0, polygons_coarse = 0;
  for (size_t k = 0; k < cams.size(); ++k) {
    SCOPED_TRACE("view " + std::to_string(k));
    const Camera& cam = cams[k];
    const Location at = c.locate(cam.eye, cam.forward);
    ASSERT_EQ(at.what, Location::What::Cell);
    const VisibleSet vs = find_visible(c, cam, at.cell);
    HalftoneOptions o;
    o.threads = 1;
    o.lights = Lights::Eye;
    Image a, b;
    RenderStats sa, sb;
    render_view(c, full, cam, vs, o, a, &sa);
    o.detail_samples = 0.5;
    render_view(c, coarse, cam, vs, o, b, &sb);
    polygons_full += sa.polygons, polygons_coarse += sb.polygons;
    ASSERT_EQ(a.data.size(), b.data.size());
    long differ = 0, off = 0;  // pixels that differ at all; samples more than 2 levels off
    double squares = 0;
    for (size_t i = 0; i < a.data.size(); i += 3) {
      differ += a.data[i] != b.data[i] || a.data[i + 1] != b.data[i + 1] || a.data[i + 2] != b.data[i + 2];
      for (size_t ch = 0; ch < 3; ++ch) {
        const int d = int(a.data[i + ch]) - int(b.data[i + ch]);
        squares += double(d * d);
        off += std::abs(d) > 2;
      }
    }
    const long pixels = long(a.data.size() / 3);
    const double rms = std::sqrt(squares / double(a.data.size()));
    std::printf("  view %zu: %ld and %ld polygons; %ld of %ld pixels differ, %.3f %% of samples > 2 levels off, RMS %.2f levels\n",
                k, sa.polygons, sb.polygons, differ, pixels, 100.0 * double(off) / double(a.data.size()), rms);
    // Half a sample of movement changes samples along silhouettes and creases, and a
    // triangle's flat shade where its polygon's was: under 0.5 % of the samples by more
    // than 2 levels, within the renderer's own sampling error (docs/ACCURACY.md §2).
    EXPECT_LE(off, long(a.data.size()) / 200);
    EXPECT_LE(rms, 2.0);
  }
  EXPECT_LT(polygons_coarse, polygons_full);
}

// The frame budget's last steps (app/frame_budget.h) draw no object whose box lies farther
// from the eye than a reach (HalftoneOptions::objects_within). A furnished home from its
// stored eye and three more headings, searched exactly and by the walk's hull search: with
// a reach of 4 m, every object polygon drawn comes from an object within 4 m, every such
// object is drawn with the polygons it had without a reach, and the cells' faces are the same.
TEST(ObjectReach, ObjectsBeyondTheReachAreLeftOutAndNoOthers) {
  const fs::path home = fs::path(AVENUES_SH3D_EXAMPLES) / "1BedroomApartmentWithRoundWall.xml";
  if (!fs::exists(home)) GTEST_SKIP() << "no " << home;
  const CellComplex c = build_cells(read_sweet_home(home.string()));
  const std::vector<PlacedObject> objects = place_objects(c);
  ASSERT_TRUE(c.view.has_value());
  const Viewpoint& vp = *c.view;
  constexpr double kReach = 4;
  auto distance = [](const Box3& b, Vec3 e) {
    const Vec3 q{std::clamp(e.x, b.lo.x, b.hi.x), std::clamp(e.y, b.lo.y, b.hi.y), std::clamp(e.z, b.lo.z, b.hi.z)};
    return length(q - e);
  };
  long left_out = 0, kept = 0;
  for (const bool hull : {false, true})
    for (double yaw : {-1.0, 0.0, 120.0, 240.0}) {
      SCOPED_TRACE(std::string(hull ? "hull" : "exact") + " search, yaw " + std::to_string(yaw));
      const Camera cam = yaw < 0 ? Camera::look_at(vp.eye, vp.look, vp.fov_deg, 640, 360)
                                 : Camera::yaw_pitch(vp.eye, yaw, -10, 60, 640, 360);
      const Location at = c.locate(cam.eye, cam.forward);
      ASSERT_EQ(at.what, Location::What::Cell);
      TraverseParams tp;
      tp.hull_pieces = hull;
      const VisibleSet vs = find_visible(c, cam, at.cell, tp);
      SceneOptions so;
      so.drop_hidden = false;  // what is drawn depends on nothing else drawn
      const ScreenScene all = screen_scene_of_view(c, objects, cam, vs, so);
      so.objects_within = kReach;
      const ScreenScene near = screen_scene_of_view(c, objects, cam, vs, so);
      std::map<int, long> per_all, per_near;  // object polygons, by object
      long faces_all = 0, faces_near = 0;
      for (const PolygonSource& s : all.sources)
        s.kind == PolygonSource::Kind::Object ? ++per_all[s.mesh] : ++faces_all;
      for (const PolygonSource& s : near.sources)
        s.kind == PolygonSource::Kind::Object ? ++per_near[s.mesh] : ++faces_near;
      EXPECT_EQ(faces_near, faces_all);
      for (const auto& [o, n] : per_all) {
        const bool within = distance(objects[size_t(o)].bounds, cam.eye) <= kReach;
        EXPECT_EQ(per_near.count(o) ? per_near[o] : 0, within ? n : 0) << objects[size_t(o)].name;
        (within ? kept : left_out) += n;
      }
    }
  std::printf("  %ld object polygons within %.0f m kept, %ld beyond left out\n", kept, kReach, left_out);
  EXPECT_GT(kept, 0);
  EXPECT_GT(left_out, 0);
}

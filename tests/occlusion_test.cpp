// Tests of render/occlusion_buffer.h and the scene builder's use of it (drop_hidden): what
// the buffer says is hidden must be hidden at every sample centre, by the polygons drawn,
// checked against a brute force over every centre; and a picture drawn with what is hidden
// dropped must be the picture drawn without dropping, byte for byte.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "cells/mesh_scene.h"
#include "render/halftone.h"
#include "render/occlusion_buffer.h"
#include "render/scene_screen.h"
#include "tests/test_meshes.h"
#include "visibility/camera.h"
#include "visibility/visible_set.h"

using namespace avenues;

namespace {

FixedPoint fixed(double x, double y) { return {std::llround(x * kSubpixelOne), std::llround(y * kSubpixelOne)}; }

/// The convex hull of points (monotone chain), counter-clockwise, no three in line.
std::vector<FixedPoint> hull_of(std::vector<FixedPoint> p) {
  std::sort(p.begin(), p.end(), [](FixedPoint a, FixedPoint b) { return a.x != b.x ? a.x < b.x : a.y < b.y; });
  p.erase(std::unique(p.begin(), p.end()), p.end());
  auto turn = [](FixedPoint o, FixedPoint a, FixedPoint b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
  };
  std::vector<FixedPoint> h(2 * p.size() + 1);
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && turn(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && turn(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k > 0 ? k - 1 : 0);
  return h;
}

/// Whether the centre of sample (i, j) lies strictly inside a convex outline (exact).
bool centre_inside(const std::vector<FixedPoint>& outline, int i, int j) {
  const int64_t x = int64_t(i) * kSubpixelOne + kSubpixelOne / 2, y = int64_t(j) * kSubpixelOne + kSubpixelOne / 2;
  int sign = 0;
  for (size_t k = 0; k < outline.size(); ++k) {
    const FixedPoint a = outline[k], b = outline[(k + 1) % outline.size()];
    const int64_t t = (b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x);
    const int s = t > 0 ? 1 : t < 0 ? -1 : 0;
    if (s == 0 || (sign != 0 && s != sign)) return false;
    sign = s;
  }
  return true;
}

struct Drawn {
  std::vector<FixedPoint> outline, clip;
  RasterPlane depth;
};

}  // namespace

// A square drawn at 1/Z = 0.5 hides what lies behind it where it covers whole pixels, and
// nothing in front of it, nothing beside it, nothing on pixels its edge passes through.
TEST(Occlusion, ASquareHidesWhatLiesBehindItsWholePixelsOnly) {
  OcclusionBuffer b;
  b.reset(64, 48, 1);
  const std::vector<FixedPoint> square{fixed(10.5, 10.25), fixed(40.75, 10.25), fixed(40.75, 30.5), fixed(10.5, 30.5)};
  b.cover(square, nullptr, -1, RasterPlane{0, 0, 0.5});
  EXPECT_TRUE(b.hides({15, 15}, {20, 20}, 0.4));
  EXPECT_TRUE(b.hides({11, 11}, {40, 29}, 0.49));
  EXPECT_FALSE(b.hides({15, 15}, {20, 20}, 0.5));         // as near: not hidden
  EXPECT_FALSE(b.hides({15, 15}, {20, 20}, 0.4999999));   // within the margin of 1e-6
  EXPECT_FALSE(b.hides({35, 15}, {45, 20}, 0.1));         // reaches past its side
  // Its left side passes through the centres of column 10 (x = 10.5): the scan may or may
  // not give them to the square, so they are not counted as covered.
  EXPECT_FALSE(b.hides({10.2, 15}, {10.8, 20}, 0.1));
  EXPECT_TRUE(b.hides({11.2, 15}, {11.8, 20}, 0.1));
  // Row 30's centres (y = 30.5) lie on its bottom side: not covered either.
  EXPECT_FALSE(b.hides({15, 30.2}, {20, 30.8}, 0.1));
  // A box holding no sample centre of the raster hides trivially; one off the raster too.
  EXPECT_TRUE(b.hides({100, 100}, {120, 120}, 0.1));
  // The next picture starts with nothing drawn.
  b.reset(64, 48, 1);
  EXPECT_FALSE(b.hides({15, 15}, {20, 20}, 0.1));
  EXPECT_EQ(b.covered(), 0);
}

// A polygon covers only what its clip region lets it draw.
TEST(Occlusion, APolygonCoversOnlyInsideItsClipRegion) {
  OcclusionBuffer b;
  b.reset(64, 64, 1);
  const std::vector<FixedPoint> all{fixed(0, 0), fixed(64, 0), fixed(64, 64), fixed(0, 64)};
  const std::vector<FixedPoint> left{fixed(0, 0), fixed(32, 0), fixed(20, 64), fixed(0, 64)};
  b.cover(all, &left, 3, RasterPlane{0, 0, 1});
  EXPECT_TRUE(b.hides({2, 2}, {15, 60}, 0.5));
  EXPECT_FALSE(b.hides({2, 2}, {25, 60}, 0.5));  // past the region's slanted side lower down
  EXPECT_TRUE(b.hides({2, 2}, {25, 10}, 0.5));   // where the region is still that wide
  EXPECT_FALSE(b.hides({40, 2}, {50, 10}, 0.5));
}

// Random convex polygons on random planes, cut by random clip regions, at one and four
// samples a pixel: wherever the buffer says a box is hidden at 1/Z, every sample centre in
// the box is strictly inside some polygon drawn (and its clip region) whose plane there
// is nearer. And it does say so: a box well inside the nearest of them is found hidden.
TEST(Occlusion, WhatTheBufferHidesIsHiddenAtEverySampleCentre) {
  std::mt19937 rng(18);
  long claims = 0, tested = 0;
  for (int per_side : {1, 2}) {
    const int w = 96 * per_side, h = 64 * per_side;
    for (int picture = 0; picture < 40; ++picture) {
      OcclusionBuffer b;
      b.reset(w, h, per_side);
      std::uniform_real_distribution<double> px(-10, w + 10), py(-10, h + 10), slope(-0.004, 0.004), base(0.2, 1.0);
      std::vector<Drawn> drawn;
      const int n = 1 + int(rng() % 12);
      for (int k = 0; k < n; ++k) {
        Drawn d;
        std::vector<FixedPoint> pts, clip_pts;
        const double cx = px(rng), cy = py(rng), r = 4 + double(rng() % 60);
        for (int q = 0; q < 7; ++q) {
          const double a = 2 * M_PI * double(rng() % 1000) / 1000;
          pts.push_back(fixed(cx + r * std::cos(a), cy + r * std::sin(a)));
          clip_pts.push_back(fixed(px(rng), py(rng)));
        }
        d.outline = hull_of(pts);
        if (rng() % 2) d.clip = hull_of(clip_pts);
        d.depth = {slope(rng), slope(rng), base(rng)};
        if (d.outline.size() < 3 || (!d.clip.empty() && d.clip.size() < 3)) continue;
        b.cover(d.outline, d.clip.empty() ? nullptr : &d.clip, d.clip.empty() ? -1 : k, d.depth);
        drawn.push_back(d);
      }
      // The nearest 1/Z drawn at each sample centre (0: nothing).
      std::vector<double> nearest(size_t(w) * size_t(h), 0);
      for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i)
          for (const Drawn& d : drawn)
            if (centre_inside(d.outline, i, j) && (d.clip.empty() || centre_inside(d.clip, i, j)))
              nearest[size_t(j) * size_t(w) + size_t(i)] =
                  std::max(nearest[size_t(j) * size_t(w) + size_t(i)], d.depth.at(i + 0.5, j + 0.5));
      std::uniform_real_distribution<double> qx(-2, w + 2), qy(-2, h + 2), size(0, 12), inv(0.05, 1.2);
      for (int q = 0; q < 400; ++q) {
        const Vec2 lo{qx(rng), qy(rng)};
        const Vec2 hi{lo.x + size(rng) * per_side, lo.y + size(rng) * per_side};
        const double z = inv(rng);
        ++tested;
        if (!b.hides(lo, hi, z)) continue;
        ++claims;
        // The centres the box (grown by the 1/64 of a sample hides() allows for rounding) holds.
        constexpr double reach = 1.0 / 64;
        for (int j = std::max(0, int(std::ceil(lo.y - reach - 0.5))); j < h && j + 0.5 <= hi.y + reach; ++j)
          for (int i = std::max(0, int(std::ceil(lo.x - reach - 0.5))); i < w && i + 0.5 <= hi.x + reach; ++i)
            ASSERT_GT(nearest[size_t(j) * size_t(w) + size_t(i)], z)
                << "sample (" << i << ", " << j << ") of picture " << picture << " is not hidden";
      }
    }
  }
  EXPECT_GT(claims, tested / 20) << "the buffer hid almost nothing";
  RecordProperty("hidden", std::to_string(claims) + " of " + std::to_string(tested));
}

// Meshes alone are resolved by depth: a wall in front of a crowd of small triangles hides
// those behind it, which are not put on the raster; those in front and beside it are. The
// picture is the same byte for byte.
TEST(Occlusion, AWallDropsTheTrianglesBehindItAndThePictureStaysTheSame) {
  std::vector<Vec3> v;
  std::vector<std::vector<int>> polygons;
  auto quad = [&](Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
    const int n = int(v.size());
    v.insert(v.end(), {a, b, c, d});
    polygons.push_back({n, n + 1, n + 2, n + 3});
  };
  quad({-3, 5, -2}, {3, 5, -2}, {3, 5, 2}, {-3, 5, 2});  // the wall, 5 m ahead
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> x(-4, 4), z(-2.5, 2.5), y(2, 12);
  for (int k = 0; k < 300; ++k) {
    const Vec3 c{x(rng), y(rng), z(rng)};
    const int n = int(v.size());
    v.insert(v.end(), {c, c + Vec3{0.2, 0.05, 0}, c + Vec3{0.05, 0.1, 0.2}});
    polygons.push_back({n, n + 1, n + 2});
  }
  const Mesh m = avenues::testing::mesh_from(v, polygons);
  const Camera cam = Camera::look_at({0, 0, 0}, {0, 1, 0}, 70, 160, 120);
  for (int samples : {1, 4}) {
    HalftoneOptions dropping, every;
    dropping.threads = every.threads = 1;
    dropping.samples = every.samples = samples;
    every.drop_hidden = false;
    RenderStats sd, se;
    const Image a = render_meshes({m}, cam, dropping, &sd);
    const Image b = render_meshes({m}, cam, every, &se);
    EXPECT_TRUE(a.data == b.data) << samples << " samples: dropping hidden triangles changed the picture";
    EXPECT_LT(sd.polygons, se.polygons - 50) << "few triangles behind the wall were dropped";
  }
}

// ScreenSceneBuilder::cell_faces_hidden, which the picture of a hull search asks before it
// adds a cell's pieces one by one: across a grid of open boxes from its corner at the height
// of their walls, most cells lie behind the near walls. Every piece of a cell it calls hidden
// must be one add_face drops, and it must count them as add_face does (the picture decides
// from those counts whether remembering pays); the picture is then the same bytes with and
// without what is hidden dropped.
TEST(Occlusion, ACellWhoseFacesAreHiddenHasEveryPieceDroppedOneByOne) {
  // A ramp beside the grid rising to the walls' tops, so that the air over them is cut into
  // columns by their planes (as it is where anything but walls stands at that height: the
  // soup is cut at the walls' tops only where every surface there stands steeply, see
  // SoupBsp.TheAirOverAGridOfOpenBoxesIsOneCell), and the search reaches the cells behind
  // the near walls through those columns; over a grid alone it reaches few such cells.
  const Mesh ramp = avenues::testing::mesh_from({{30, -1.5, 0.5}, {31, -1.5, 1}, {31, -1, 1}, {30, -1, 0.5}}, {{0, 1, 2, 3}});
  const CellComplex c = build_mesh_scene({avenues::testing::open_boxes(12), ramp});
  for (const int samples : {1, 4}) {
    SCOPED_TRACE(std::to_string(samples) + " samples");
    const Camera cam = Camera::yaw_pitch({-1.0, -0.3, 0.6}, 45, 0, 88, 322, 181);
    TraverseParams p;
    p.merge_pieces = p.hull_pieces = true;
    const VisibleSet vs = find_visible(c, cam, c.locate(cam.eye).cell, p);
    ASSERT_TRUE(vs.conservative);
    ScreenScene scene;
    SceneOptions o;
    o.per_side = samples == 4 ? 2 : 1;
    ScreenSceneBuilder b(cam, o, scene);
    b.drop_hidden();
    long hidden_cells = 0, kept_in_hidden = 0, dropped = 0, pieces = 0;
    for (size_t i = 0; i < vs.avenues.size(); ++i) {
      const Avenue& a = vs.avenues[i];
      const double grow = a.depth == 0 ? 0 : 1.0 / 64;
      const Cell& cell = c.cells[size_t(a.cell)];
      const bool hidden = b.cell_faces_hidden(cell, a.mask, grow);
      const int32_t clip = b.add_clip(a.mask, grow);
      if (clip < 0) continue;
      hidden_cells += hidden;
      for (size_t k = 0; k < cell.faces.size(); ++k) {
        const Face& f = cell.faces[k];
        if (f.opaque.empty() || !(f.plane.eval(cam.eye) < 0)) continue;
        PolygonSource source;
        source.kind = PolygonSource::Kind::Face;
        source.cell = a.cell;
        source.face = int(k);
        for (const OpaquePoly& piece : f.opaque) {
          const bool added = b.add_face(piece.poly, f.plane, Material{}, {clip, 0, 0, PolygonRole::Object}, source);
          ++pieces;
          dropped += !added;
          if (hidden && added) ++kept_in_hidden;
        }
      }
    }
    EXPECT_EQ(kept_in_hidden, 0) << "a piece of a cell called hidden was added";
    EXPECT_GT(hidden_cells, long(vs.avenues.size()) / 3) << hidden_cells << " of " << vs.avenues.size() << " cells";
    EXPECT_LT(long(scene.polygons.size()), pieces / 4);
    // The picture of the view, with what is hidden dropped and without: the same bytes.
    HalftoneOptions with, without;
    with.threads = without.threads = 1;
    with.samples = without.samples = samples;
    without.drop_hidden = false;
    Image pw, po;
    render_view(c, {}, cam, vs, with, pw);
    render_view(c, {}, cam, vs, without, po);
    EXPECT_TRUE(pw.data == po.data);
  }
}

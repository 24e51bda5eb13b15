// Tests of the scanline engine (render/scanline.h): the fill rule, bands, hidden surfaces,
// implicitly defined lines — against independent references (brute-force ray casting).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <set>

#include "cells/build_cells.h"
#include "render/halftone.h"
#include "render/scanline.h"
#include "render/scene_screen.h"
#include "render/scenes.h"
#include "tests/ray_oracle.h"
#include "tests/test_meshes.h"
#include "visibility/traverse.h"
#include "visibility/viewpoint.h"

namespace fs = std::filesystem;
using namespace avenues;
using avenues::testing::mesh_from;
using avenues::testing::nearest_triangle;

namespace {

FixedPoint fixed(double x, double y) { return {std::llround(x * kSubpixelOne), std::llround(y * kSubpixelOne)}; }

ScreenPolygon polygon(std::vector<FixedPoint> outline, RasterPlane depth = {0, 0, 1}) {
  ScreenPolygon p;
  p.outline = std::move(outline);
  p.depth = depth;
  return p;
}

/// A face of avenue `group` at depth `rank`, cut by clip region `clip` (-1: none).
ScreenPolygon face(std::vector<FixedPoint> outline, int32_t group, int32_t rank, int32_t clip = -1) {
  ScreenPolygon p = polygon(std::move(outline));
  p.role = PolygonRole::Face;
  p.group = group;
  p.rank = rank;
  p.clip = clip;
  return p;
}

/// Row y's spans as `want` has them.
void expect_same_spans(const SpanRow& got, const SpanRow& want, int y) {
  ASSERT_EQ(got.size(), want.size()) << "row " << y;
  for (size_t k = 0; k < want.size(); ++k) {
    EXPECT_EQ(got[k].x0, want[k].x0) << "row " << y;
    EXPECT_EQ(got[k].x1, want[k].x1) << "row " << y;
    EXPECT_EQ(got[k].polygon, want[k].polygon) << "row " << y;
  }
}

/// How many polygons cover each sample (their own spans, before hiding), every row.
std::vector<int> coverage_counts(int w, int h, const std::vector<ScreenPolygon>& polys) {
  EdgeTable table(w, h, polys, {});
  ScanlineEngine engine(table);
  engine.start(0);
  std::vector<int> count(size_t(w) * size_t(h), 0);
  for (int y = 0; y < h; ++y) {
    engine.scan();
    for (const Span& s : engine.coverage())
      for (int x = s.x0; x < s.x1; ++x) ++count[size_t(y) * size_t(w) + size_t(x)];
  }
  return count;
}

/// A grid of n × n cells over [x0, x0 + n·cw] × [y0, y0 + n·ch], interior vertices jittered
/// by up to `jitter` of a cell (below ¼, so no triangle folds over), each cell cut into two
/// triangles along alternating diagonals.
std::vector<ScreenPolygon> triangle_grid(int n, double x0, double y0, double cw, double ch, double jitter,
                                         unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter, jitter);
  std::vector<FixedPoint> v;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const bool inner = i > 0 && i < n && j > 0 && j < n;
      v.push_back(fixed(x0 + cw * (i + (inner ? u(rng) : 0)), y0 + ch * (j + (inner ? u(rng) : 0))));
    }
  auto at = [&](int i, int j) { return v[size_t(j) * size_t(n + 1) + size_t(i)]; };
  std::vector<ScreenPolygon> polys;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if ((i + j) % 2 == 0) {
        polys.push_back(polygon({at(i, j), at(i + 1, j), at(i + 1, j + 1)}));
        polys.push_back(polygon({at(i, j), at(i + 1, j + 1), at(i, j + 1)}));
      } else {
        polys.push_back(polygon({at(i, j), at(i + 1, j), at(i, j + 1)}));
        polys.push_back(polygon({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)}));
      }
    }
  return polys;
}

/// Checks a tiling of [x0, x1] × [y0, y1]: every sample centre inside is covered exactly
/// once, every one outside not at all.
void expect_exactly_once(int w, int h, const std::vector<ScreenPolygon>& polys, double x0, double y0, double x1,
                         double y1) {
  const std::vector<int> count = coverage_counts(w, h, polys);
  int wrong = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const bool inside = x + 0.5 > x0 && x + 0.5 < x1 && y + 0.5 > y0 && y + 0.5 < y1;
      wrong += count[size_t(y) * size_t(w) + size_t(x)] != (inside ? 1 : 0);
    }
  EXPECT_EQ(wrong, 0);
}

/// Compares the item buffer's depth at every pixel centre with a reference distance along
/// the ray (whose forward component is 1, so distance = Z). Returns the fraction that
/// agree; every disagreeing pixel must have a neighbour seeing another polygon (an edge).
double agreement(const ScreenScene& scene, const std::vector<int32_t>& items, const Camera& cam,
                 const std::function<double(Vec3 dir)>& reference, int& off_edge) {
  const int w = scene.raster.width, h = scene.raster.height;
  long agree = 0;
  off_edge = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int32_t id = items[size_t(y) * size_t(w) + size_t(x)];
      const double t = reference(cam.ray_through_raster({x + 0.5, y + 0.5}));
      const double z = id < 0 ? std::numeric_limits<double>::infinity()
                              : 1 / scene.polygons[size_t(id)].depth.at(x + 0.5, y + 0.5);
      const bool same = std::isinf(t) ? std::isinf(z) : std::fabs(z - t) <= 1e-6 * t + 1e-9;
      if (same) {
        ++agree;
        continue;
      }
      bool edge = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx >= 0 && yy >= 0 && xx < w && yy < h && items[size_t(yy) * size_t(w) + size_t(xx)] != id) edge = true;
        }
      off_edge += !edge;
    }
  return double(agree) / (double(w) * double(h));
}

/// agreement() against rays cast at the complex's faces and the meshes drawn: every sample
/// agrees but for a thousandth, each beside an edge.
void expect_rays_agree(const ScreenScene& scene, const std::vector<int32_t>& items, const Camera& cam,
                       const CellComplex& c, const std::vector<Mesh>& drawn) {
  int off_edge = 0;
  const double a = agreement(
      scene, items, cam,
      [&](Vec3 d) { return std::min(avenues::testing::first_hit(c, cam.eye, d), nearest_triangle(drawn, cam.eye, d)); },
      off_edge);
  EXPECT_GE(a, 0.999);
  EXPECT_EQ(off_edge, 0);
}

}  // namespace

// --- the fill rule ---------------------------------------------------------------------

TEST(FillRule, TiesGoToTheLeftAndTopEdges) {
  // Two squares sharing a vertical edge through sample centres (x = 20.5), two sharing a
  // horizontal one (y = 15.5): the column and the row on the line go right and down.
  std::vector<ScreenPolygon> polys{
      polygon({fixed(10.5, 5.5), fixed(20.5, 5.5), fixed(20.5, 15.5), fixed(10.5, 15.5)}),
      polygon({fixed(20.5, 5.5), fixed(30.5, 5.5), fixed(30.5, 15.5), fixed(20.5, 15.5)}),
      polygon({fixed(10.5, 15.5), fixed(30.5, 15.5), fixed(30.5, 25.5), fixed(10.5, 25.5)})};
  EdgeTable table(40, 30, polys, {});
  ScanlineEngine engine(table);
  engine.start(0);
  for (int y = 0; y < 30; ++y) {
    engine.scan();
    for (const Span& s : engine.coverage()) {
      const int want_x0[] = {10, 20, 10}, want_x1[] = {20, 30, 30};
      EXPECT_EQ(s.x0, want_x0[s.polygon]);
      EXPECT_EQ(s.x1, want_x1[s.polygon]);
      EXPECT_TRUE(s.polygon <= 1 ? y >= 5 && y < 15 : y >= 15 && y < 25) << "row " << y;
    }
  }
}

TEST(FillRule, FineTriangleGridCoversEverySampleExactlyOnce) {
  // 50 × 50 cells of 4 samples, jittered: 5000 triangles, every sample once.
  expect_exactly_once(220, 220, triangle_grid(50, 10.3, 10.3, 4, 4, 0.22, 1969), 10.3, 10.3, 210.3, 210.3);
}

TEST(FillRule, LongThinTrianglesCoverEverySampleExactlyOnce) {
  // 50 × 50 cells of 7 × 0.3 samples: slivers whose long edges are shared across many rows.
  expect_exactly_once(380, 30, triangle_grid(50, 3.7, 4.2, 7, 0.3, 0.22, 1967), 3.7, 4.2, 353.7, 19.2);
}

// Pieces of light and shadow are grown by a square of 1/64 sample (scene_screen.h): in one
// pass, not by a hull of four times their corners. Against that hull (core/geometry.h), on
// random convex outlines of either orientation, from triangles to 60 corners, slivers, and
// tiny outlines that rounding to the grid left a hair concave or crossing themselves.
TEST(GrowConvex, IsTheHullOfTheCornersMovedByTheSquare) {
  std::mt19937_64 rng(20261207);
  std::uniform_real_distribution<double> unit(0, 1);
  int checked = 0;
  for (int k = 0; k < 3000; ++k) {
    const int corners = 3 + int(unit(rng) * 58);
    const double r = k % 3 == 0 ? 3.0 : 5000.0 * unit(rng) + 1;
    const double squash = k % 5 == 0 ? 1e-3 : 1;
    const Vec2 c{unit(rng) * 1e5, unit(rng) * 1e5};
    std::vector<double> angles;
    for (int i = 0; i < corners; ++i) angles.push_back(unit(rng) * 2 * M_PI);
    std::sort(angles.begin(), angles.end());
    std::vector<FixedPoint> v;
    for (double a : angles) {
      const FixedPoint f{std::llround(c.x + r * std::cos(a)), std::llround(c.y + squash * r * std::sin(a))};
      if (v.empty() || !(v.back() == f)) v.push_back(f);
    }
    while (v.size() > 1 && v.front() == v.back()) v.pop_back();
    if (k % 2) std::reverse(v.begin(), v.end());
    const int64_t g = k % 7 == 0 ? 1 : 4;
    std::vector<Vec2> moved, given;
    for (const FixedPoint& f : v) {
      given.push_back({double(f.x), double(f.y)});
      for (int64_t dx : {-g, g})
        for (int64_t dy : {-g, g}) moved.push_back({double(f.x + dx), double(f.y + dy)});
    }
    std::vector<FixedPoint> out;
    const bool grown = grow_convex(v, g, out);
    if (convex_hull(given).size() < 3) {  // no area (rounded onto a line)
      EXPECT_FALSE(grown);
      continue;
    }
    const std::vector<Vec2> want = convex_hull(moved);
    ASSERT_TRUE(grown);
    std::vector<Vec2> got;
    for (const FixedPoint& f : out) got.push_back({double(f.x), double(f.y)});
    EXPECT_GT(signed_area(got), 0) << k;  // counter-clockwise as stored
    EXPECT_EQ(convex_hull(got), want) << k;
    ++checked;
  }
  EXPECT_GT(checked, 1500);
}

TEST(Scanline, ABandStartedMidPictureScansWhatAFullScanDoes) {
  const std::vector<ScreenPolygon> polys = triangle_grid(30, 2.2, 1.7, 9, 7, 0.22, 7);
  EdgeTable table(300, 220, polys, {});
  ScanlineEngine full(table);
  full.start(0);
  std::vector<SpanRow> rows(220);
  for (auto& r : rows) r = full.scan();
  for (int start : {1, 37, 101, 150, 219}) {
    ScanlineEngine band(table);
    band.start(start);
    for (int y = start; y < std::min(220, start + 20); ++y) expect_same_spans(band.scan(), rows[size_t(y)], y);
  }
}

TEST(Scanline, ARowLikeTheOneAboveIsRepeatedNotScannedAgain) {
  // Upright rectangles (walls seen by a level eye), one of them a deeper avenue's face cut
  // by a clip region; a triangle over rows 40-59 whose sloped edges step every row; and two
  // objects over rows 70-89 resolved by depth, whose implicit line slants. Scanned from the
  // top, rows alike are repeated, and the triangle's rows, whose span ends keep their order,
  // are seen as the row before saw them; each row scanned by an engine started there is
  // neither. The spans are the same either way.
  std::vector<ScreenPolygon> polys{
      face({fixed(0, 0), fixed(120, 0), fixed(120, 100), fixed(0, 100)}, 0, 0),
      face({fixed(30.3, 10.2), fixed(90.7, 10.2), fixed(90.7, 95.1), fixed(30.3, 95.1)}, 1, 1, 0),
      face({fixed(50, 40.5), fixed(80, 59.5), fixed(40, 59.5)}, 2, 2)};
  ScreenPolygon a = polygon({fixed(10, 70), fixed(60, 70), fixed(60, 90), fixed(10, 90)}, {0.01, 0.002, 0.5});
  ScreenPolygon b = polygon({fixed(20, 70), fixed(70, 70), fixed(70, 90), fixed(20, 90)}, {-0.01, 0.001, 0.9});
  a.group = b.group = 1, a.rank = b.rank = 1;
  polys.push_back(a);
  polys.push_back(b);
  const std::vector<ClipRegion> clips{{{fixed(25.5, 5.5), fixed(100.5, 5.5), fixed(100.5, 97.5), fixed(25.5, 97.5)}}};
  EdgeTable table(120, 100, polys, clips);
  ScanlineEngine one(table);
  one.start(0);
  std::vector<int> repeated;
  ScanCounters fresh_counters;
  for (int y = 0; y < 100; ++y) {
    ScanlineEngine fresh(table);
    fresh.start(y);
    const SpanRow& own = fresh.scan();
    EXPECT_FALSE(fresh.repeated());
    fresh_counters.add(fresh.counters());
    expect_same_spans(one.scan(), own, y);
    if (one.repeated()) repeated.push_back(y);
  }
  auto repeats = [&](int y) { return std::find(repeated.begin(), repeated.end(), y) != repeated.end(); };
  for (int y : {20, 30, 65, 99}) EXPECT_TRUE(repeats(y)) << "row " << y << " is the row above again";
  for (int y = 41; y < 60; ++y) EXPECT_FALSE(repeats(y)) << "the triangle's edges step on row " << y;
  for (int y = 71; y < 90; ++y) EXPECT_FALSE(repeats(y)) << "row " << y << " is resolved by depth";
  EXPECT_EQ(one.counters().spans, fresh_counters.spans);
  EXPECT_EQ(one.counters().intersections, fresh_counters.intersections);
}

TEST(Scanline, OneEngineScanningBandsInAnyOrderScansWhatAFullScanDoes) {
  // A painter's engine scans whatever bands its thread is handed, in any order: what it
  // keeps from row to row (the row above's spans, the ends' order and what each end saw,
  // the extents) must not outlive a band.
  std::vector<ScreenPolygon> polys = triangle_grid(12, 40.2, 30.7, 9, 7, 0.22, 11);
  for (ScreenPolygon& p : polys) p.role = PolygonRole::Face, p.group = 2, p.rank = 2;
  polys.push_back(face({fixed(0, 0), fixed(200, 0), fixed(200, 150), fixed(0, 150)}, 0, 0, -1));
  polys.push_back(face({fixed(20.3, 10.2), fixed(170.7, 10.2), fixed(170.7, 140.1), fixed(20.3, 140.1)}, 1, 1, 0));
  polys.push_back(face({fixed(150, 5.5), fixed(190, 60.5), fixed(150, 120.5)}, 3, 3, 1));
  const std::vector<ClipRegion> clips{{{fixed(10.5, 5.5), fixed(180.5, 5.5), fixed(180.5, 147.5), fixed(10.5, 147.5)}},
                                      {{fixed(140.5, 20.5), fixed(199.5, 20.5), fixed(199.5, 100.5), fixed(140.5, 100.5)}}};
  EdgeTable table(200, 150, polys, clips);
  ScanlineEngine full(table);
  full.start(0);
  std::vector<SpanRow> rows(150);
  for (auto& r : rows) r = full.scan();
  ScanlineEngine engine(table);
  for (int band : {5, 0, 20, 13, 1, 19, 7, 12, 2, 18, 9, 3, 14, 6, 17, 4, 11, 8, 15, 10, 16}) {
    engine.start(band * 7);
    for (int y = band * 7; y < std::min(150, band * 7 + 7); ++y) expect_same_spans(engine.scan(), rows[size_t(y)], y);
  }
}

TEST(Scanline, SpansTileEachRowAndMergeRunsOfOnePolygon) {
  // A square in front of a larger one: three spans on the middle rows, and no depth sort
  // outside the overlap.
  std::vector<ScreenPolygon> polys{
      polygon({fixed(5, 5), fixed(35, 5), fixed(35, 25), fixed(5, 25)}, {0, 0, 0.5}),
      polygon({fixed(15, 10), fixed(25, 10), fixed(25, 20), fixed(15, 20)}, {0, 0, 1.0})};
  EdgeTable table(40, 30, polys, {});
  ScanlineEngine engine(table);
  engine.start(0);
  for (int y = 0; y < 30; ++y) {
    const SpanRow& spans = engine.scan();
    ASSERT_FALSE(spans.empty());
    EXPECT_EQ(spans.front().x0, 0);
    EXPECT_EQ(spans.back().x1, 40);
    for (size_t k = 1; k < spans.size(); ++k) {
      EXPECT_EQ(spans[k].x0, spans[k - 1].x1);
      EXPECT_NE(spans[k].polygon, spans[k - 1].polygon);
    }
    if (y == 15) {
      ASSERT_EQ(spans.size(), 5u);  // background, big, small, big, background
      EXPECT_EQ(spans[2].polygon, 1);
      EXPECT_EQ(spans[2].x0, 15);
      EXPECT_EQ(spans[2].x1, 25);
    }
  }
  EXPECT_EQ(engine.counters().implicit_lines, 0);
  EXPECT_EQ(engine.counters().depth_sorts, 10 * 2);  // each overlapped row: at the left end, then the right
}

TEST(Scanline, ThousandsOfSpansThatBeginEndAndCrossSeeTheNearestOnEveryRow) {
  // The hull search's pictures: thousands of polygons whose rows cover most of the raster,
  // each cut to a small clip region, so that its span begins and ends far inside its rows,
  // and long thin triangles whose spans cross from row to row (the sorted span lists change
  // a lot between rows, in one band more than an insertion sort should take on). Each at a
  // depth of its own: on every sample the nearest polygon whose own span (coverage(), found
  // before any sorting) holds it must be the one seen.
  std::mt19937 rng(16);
  std::uniform_real_distribution<double> x(-20, 220), y(-20, 140), size(1, 12);
  std::vector<ScreenPolygon> polys;
  std::vector<ClipRegion> clips;
  for (int k = 0; k < 1500; ++k) {
    const double cx = x(rng), cy = y(rng), r = size(rng);
    clips.push_back({{fixed(cx - r, cy), fixed(cx, cy - r), fixed(cx + r, cy), fixed(cx, cy + r)}});
    ScreenPolygon p = polygon({fixed(x(rng), -30), fixed(x(rng), 150), fixed(cx + 2 * r, cy)});
    p.clip = int32_t(clips.size() - 1);
    polys.push_back(std::move(p));
  }
  for (int k = 0; k < 500; ++k) {
    const double x0 = x(rng), x1 = x(rng), w = 0.5 + size(rng) / 4;
    polys.push_back(polygon({fixed(x0, -10), fixed(x0 + w, -10), fixed(x1, 130)}));
  }
  // And a band of rows where a thousand of them all cross: too many moves for insertion.
  for (int k = 0; k < 1000; ++k) {
    const double x0 = x(rng), x1 = x(rng), w = 0.5 + size(rng) / 4;
    polys.push_back(polygon({fixed(x0, 40), fixed(x0 + w, 40), fixed(x1, 52)}));
  }
  std::vector<int32_t> order(polys.size());
  for (size_t k = 0; k < polys.size(); ++k) order[k] = int32_t(k);
  std::shuffle(order.begin(), order.end(), rng);
  for (size_t k = 0; k < polys.size(); ++k) polys[size_t(order[k])].depth = {0, 0, 1 + double(k) / 1024};
  const int w = 200, h = 120;
  EdgeTable table(w, h, polys, clips);
  ScanlineEngine engine(table);
  engine.start(0);
  long wrong = 0, seen = 0;
  for (int row = 0; row < h; ++row) {
    const SpanRow& spans = engine.scan();
    std::vector<int32_t> nearest(size_t(w), -1);
    for (const Span& c : engine.coverage())
      for (int s = c.x0; s < c.x1; ++s) {
        int32_t& n = nearest[size_t(s)];
        if (n < 0 || polys[size_t(c.polygon)].depth.c > polys[size_t(n)].depth.c) n = c.polygon;
      }
    for (const Span& sp : spans)
      for (int s = sp.x0; s < sp.x1; ++s) {
        wrong += sp.polygon != nearest[size_t(s)];
        seen += sp.polygon >= 0;
      }
  }
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(seen, w * h / 2);  // the picture is mostly covered: the test looks at something
  EXPECT_GT(engine.counters().active_max, 500);
}

// --- hidden surfaces against ray casting ---------------------------------------------------

TEST(Scanline, ItemBufferAgreesWithRayCastingOnThePapersScenes) {
  for (const PaperScene& s : paper_scenes()) {
    SCOPED_TRACE(s.name);
    Camera cam = s.camera;
    cam.width = cam.height = 256;
    const std::vector<Mesh> meshes{mesh_of(s)};
    SceneOptions so;
    so.cull_back_faces = false;
    const ScreenScene scene = screen_scene_of_meshes(meshes, {s.paint}, cam, so);
    Image picture;
    std::vector<int32_t> items;
    render_scene(scene, {}, picture, nullptr, &items);
    int off_edge = 0;
    const double a = agreement(scene, items, cam, [&](Vec3 d) { return nearest_triangle(meshes, cam.eye, d); },
                               off_edge);
    EXPECT_GE(a, 0.999);
    EXPECT_EQ(off_edge, 0);
  }
}

TEST(Scanline, ItemBufferAgreesWithRayCastingOnTheBundledPlans) {
  for (const auto& entry : fs::directory_iterator(fs::path(AVENUES_SOURCE_DIR) / "plans")) {
    if (entry.path().extension() != ".toml") continue;
    SCOPED_TRACE(entry.path().filename().string());
    const CellComplex c = build_cells(read_plan(entry.path().string()));
    const Viewpoint vp = default_viewpoint(c);
    const Camera cam = Camera::look_at(vp.eye, vp.look, vp.fov_deg, 256, 144);
    const VisibleSet vs = find_visible(c, cam, c.locate(vp.eye).cell);
    const std::vector<PlacedObject> objects = place_objects(c);
    std::vector<Mesh> drawn;  // objects meeting some cell are drawn (PlacedObject::cells)
    for (const PlacedObject& o : objects)
      if (o.cell != kNoCell) drawn.push_back(o.mesh);
    const ScreenScene scene = screen_scene_of_view(c, objects, cam, vs, {});
    Image picture;
    std::vector<int32_t> items;
    RenderStats stats;
    render_scene(scene, {}, picture, &stats, &items);
    expect_rays_agree(scene, items, cam, c, drawn);
    if (objects.empty()) {
      EXPECT_EQ(stats.depth_sorts, 0) << "cells alone need no depth";
    }
    EXPECT_EQ(stats.pixels, long(cam.width) * cam.height) << "the avenues' masks tile the picture";
  }
}

TEST(Scanline, ItemBufferAgreesWithRayCastingFromRandomEyes) {
  // Eyes anywhere in rooms and outside, looking anywhere: masks of every shape and depth.
  std::mt19937 rng(1971);
  for (const auto& entry : fs::directory_iterator(fs::path(AVENUES_SOURCE_DIR) / "plans")) {
    if (entry.path().extension() != ".toml") continue;
    const CellComplex c = build_cells(read_plan(entry.path().string()));
    for (int v = 0; v < 3; ++v) {
      std::uniform_int_distribution<size_t> pick(0, c.cells.size() - 1);
      std::uniform_real_distribution<double> u(0.05, 0.95), yaw(0, 360), pitch(-30, 30), fov(40, 110);
      CellId cell = CellId(pick(rng));
      while (c.cells[size_t(cell)].kind != CellKind::Room && c.cells[size_t(cell)].kind != CellKind::Outside)
        cell = CellId(pick(rng));
      const Cell& k = c.cells[size_t(cell)];
      Vec2 p{0, 0};
      double sum = 0;
      std::vector<double> w(k.footprint.size());
      for (double& x : w) sum += (x = u(rng));
      for (size_t i = 0; i < w.size(); ++i) p = p + (w[i] / sum) * k.footprint[i];
      const Vec3 eye{p.x, p.y, k.z0 + u(rng) * (k.z1 - k.z0)};
      const Camera cam = Camera::yaw_pitch(eye, yaw(rng), pitch(rng), fov(rng), 240, 150);
      SCOPED_TRACE(entry.path().filename().string() + " view " + std::to_string(v));
      const VisibleSet vs = find_visible(c, cam, cell);
      const ScreenScene scene = screen_scene_of_view(c, {}, cam, vs, {});
      Image picture;
      std::vector<int32_t> items;
      render_scene(scene, {}, picture, nullptr, &items);
      int off_edge = 0;
      EXPECT_GE(agreement(scene, items, cam, [&](Vec3 d) { return avenues::testing::first_hit(c, cam.eye, d); },
                          off_edge),
                0.999);
      EXPECT_EQ(off_edge, 0);
    }
  }
}

TEST(Scanline, ObjectsInACellResolveDepthAgainstItsFaces) {
  // Jones's house with Wylie's cube and tetrahedron set in the living room.
  CellComplex c = build_cells(read_plan(std::string(AVENUES_SOURCE_DIR) + "/plans/jones-house.toml"));
  Object cube;
  cube.mesh = std::string(AVENUES_SOURCE_DIR) + "/plans/scenes/wylie-cube.off";
  cube.position = {3.0, 3.4, 0.5};
  cube.scale = {0.3, 0.3, 0.3};
  cube.rotation_deg = {0, 0, 30};
  Object tetra = cube;
  tetra.mesh = std::string(AVENUES_SOURCE_DIR) + "/plans/scenes/wylie-tetrahedron.off";
  tetra.position = {3.2, 2.5, 1.0};
  c.objects = {cube, tetra};
  const Camera cam = Camera::look_at({1.5, 3.0, 1.6}, {5.0, 3.0, 1.0}, 60, 256, 144);
  const VisibleSet vs = find_visible(c, cam, c.locate(cam.eye).cell);
  const std::vector<PlacedObject> objects = place_objects(c);
  ASSERT_EQ(objects.size(), 2u);
  std::vector<Mesh> drawn{objects[0].mesh, objects[1].mesh};
  for (int smooth = 0; smooth < 2; ++smooth) {
    SceneOptions so;
    so.shading.model = smooth ? ShadingModel::Smooth : ShadingModel::Flat;
    const ScreenScene scene = screen_scene_of_view(c, objects, cam, vs, so);
    Image picture;
    std::vector<int32_t> items;
    RenderStats stats;
    render_scene(scene, {}, picture, &stats, &items);
    EXPECT_GT(stats.depth_sorts, 0);
    expect_rays_agree(scene, items, cam, c, drawn);
  }
}

// Jones's house with a bench standing through the door between the living room and the
// dining room (its centroid in the living room, a metre of it in the dining room) and a
// cube in the dining room beside it. Jones's cells are the space between walls, so an
// object need not lie in one: each part of the bench shows where a ray meets it first,
// seen from either room, through the door or not, in every search. (Drawn only in the
// cell holding its centroid, the bench's part in the dining room was missing wherever
// the door did not frame it.)
TEST(Scanline, ObjectsReachingBeyondTheirCellShowWhereARayMeetsThemFirst) {
  CellComplex c = build_cells(read_plan(std::string(AVENUES_SOURCE_DIR) + "/plans/jones-house.toml"));
  Object bench;
  bench.name = "bench";
  bench.mesh = std::string(AVENUES_SOURCE_DIR) + "/plans/scenes/wylie-cube.off";
  bench.position = {4.4, 1.65, 0.25};
  bench.scale = {1.6, 0.2, 0.25};  // x 2.8 to 6.0 through the door (y 1.2 to 2.1)
  Object cube = bench;
  cube.name = "cube";
  cube.position = {6.4, 1.0, 0.4};
  cube.scale = {0.3, 0.3, 0.3};
  c.objects = {bench, cube};
  const std::vector<PlacedObject> objects = place_objects(c);
  ASSERT_EQ(objects.size(), 2u);
  ASSERT_EQ(objects[0].cells.size(), 2u) << "the bench meets both rooms";
  EXPECT_FALSE(objects[0].cells[0].whole);
  EXPECT_FALSE(objects[0].cells[1].whole);
  EXPECT_EQ(objects[0].cell, c.locate({4.4, 1.65, 0.25}).cell) << "its home holds its centroid";
  ASSERT_EQ(objects[1].cells.size(), 1u);
  EXPECT_TRUE(objects[1].cells[0].whole);
  const std::vector<Mesh> drawn{objects[0].mesh, objects[1].mesh};
  const std::vector<Camera> views = {
      Camera::look_at({8.0, 0.5, 1.6}, {5.2, 1.65, 0.3}, 70, 240, 135),  // the dining room's end of it
      Camera::look_at({1.0, 0.6, 1.4}, {7.0, 1.9, 0.3}, 70, 240, 135),   // from the living room, through the door
      Camera::look_at({2.0, 4.5, 1.7}, {5.0, 1.6, 0.3}, 80, 240, 135)};  // the door edge-on
  for (size_t v = 0; v < views.size(); ++v)
    for (int search = 0; search < 3; ++search) {
      SCOPED_TRACE("view " + std::to_string(v) + (search == 0 ? ", Jones's" : search == 1 ? ", merged" : ", hull"));
      const Camera& cam = views[v];
      TraverseParams p;
      p.merge_pieces = search > 0;
      p.hull_pieces = search > 1;
      const VisibleSet vs = find_visible(c, cam, c.locate(cam.eye).cell, p);
      const ScreenScene scene = screen_scene_of_view(c, objects, cam, vs, {});
      Image picture;
      std::vector<int32_t> items;
      render_scene(scene, {}, picture, nullptr, &items);
      long bench_samples = 0;
      for (int32_t id : items)
        bench_samples += id >= 0 && scene.sources[size_t(id)].kind == PolygonSource::Kind::Object &&
                         scene.sources[size_t(id)].mesh == 0;
      EXPECT_GT(bench_samples, 500) << "the bench is in view";
      expect_rays_agree(scene, items, cam, c, drawn);
    }
}

TEST(Scanline, PolygonsSmallerThanASampleColourTheSamplesTheyHoldAndNoOthers) {
  // Triangles far smaller than a sample (the far detail of a steel frame), each its own
  // polygon: some hold one sample's centre, some hold none, some lie across the raster's
  // edge or wholly beyond it. A polygon that holds a centre on the raster must colour that
  // sample, however little of the sample it covers; the others must not be drawn at all
  // (ScreenSceneBuilder drops them before shading them).
  const Camera cam = Camera::look_at({0, -10, 0}, {0, 0, 0}, 50, 64, 48);
  const int w = cam.width, h = cam.height;
  std::mt19937 rng(20261205);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Vec3> vertices;
  std::vector<std::vector<int>> polygons;
  auto at = [&](Vec2 raster, double depth) {
    const Vec2 p = cam.image_from_raster(raster);
    return cam.eye + depth * (p.x * cam.right + p.y * cam.up + cam.forward);
  };
  // A triangle around the raster point c, every corner within `reach` of it (in samples),
  // at a depth of its own.
  auto triangle_around = [&](Vec2 c, double reach) {
    const double depth = 5 + 10 * u(rng), turn = 6.283185307179586 * u(rng);
    for (int k = 0; k < 3; ++k) {
      const double a = turn + 2.0943951023931953 * k, r = reach * (0.6 + 0.4 * u(rng));
      vertices.push_back(at({c.x + r * std::cos(a), c.y + r * std::sin(a)}, depth));
    }
    const int n = int(vertices.size());
    polygons.push_back({n - 3, n - 2, n - 1});
  };
  // Samples (i, j) each held by one triangle, from one row and column beyond the raster on
  // every side; and triangles between four centres, holding none.
  std::map<int, std::pair<int, int>> holds;  // polygon -> the sample whose centre it holds
  for (int j = -1; j <= h; ++j)
    for (int i = -1; i <= w; ++i) {
      if (u(rng) < 0.3) {
        holds[int(polygons.size())] = {i, j};
        triangle_around({i + 0.5 + 0.05 * (u(rng) - 0.5), j + 0.5 + 0.05 * (u(rng) - 0.5)}, 0.2 + 0.25 * u(rng));
      } else if (u(rng) < 0.4) {
        triangle_around({i + 1.0 + 0.1 * (u(rng) - 0.5), j + 1.0 + 0.1 * (u(rng) - 0.5)}, 0.1 + 0.3 * u(rng));
      }
    }
  SceneOptions so;
  so.cull_back_faces = false;
  const ScreenScene scene = screen_scene_of_meshes({mesh_from(vertices, polygons)}, {}, cam, so);
  Image picture;
  std::vector<int32_t> items;
  render_scene(scene, {}, picture, nullptr, &items);
  long on_raster = 0, right = 0;
  for (const auto& [polygon, sample] : holds) {
    const auto [i, j] = sample;
    if (i < 0 || j < 0 || i >= w || j >= h) continue;
    ++on_raster;
    const int32_t id = items[size_t(j) * size_t(w) + size_t(i)];
    right += id >= 0 && scene.sources[size_t(id)].polygon == polygon;
  }
  EXPECT_GT(on_raster, w * h / 5);  // the test looks at something
  EXPECT_EQ(right, on_raster);
  // Exactly the polygons that hold a sample's centre on the raster were put on it.
  EXPECT_EQ(long(scene.polygons.size()), on_raster);
}

TEST(Scanline, ObjectsAreCulledByTheSidesOfTheirAvenuesClipRegionNotOfItsMask) {
  // A mask with a notch a rounding deep, as the masks of Mini_Project's corner view have
  // (reflex turns between corners 1e-8 apart): the side into the notch points along -x,
  // and taken as a side of the mask it would cut away the upper half. Polygons inside the
  // mask must be kept; those beyond one of its sides (inside its box) must go before they
  // are projected.
  const Camera cam = Camera::look_at({0, -10, 0}, {0, 0, 0}, 100, 1280, 720);
  // A square 54 samples across, turned by 30 degrees so that points beyond its sides lie in
  // its box; the notch on its right side.
  std::vector<Vec2> mask;
  for (Vec2 p : std::vector<Vec2>{{0, 0}, {0.1, 0}, {0.1, 0.05}, {0.1 - 1e-9, 0.05}, {0.1, 0.05 + 2e-9}, {0.1, 0.1}, {0, 0.1}}) {
    const double c = std::cos(0.5235987755982988), s = std::sin(0.5235987755982988);
    mask.push_back({c * (p.x - 0.05) - s * (p.y - 0.05), s * (p.x - 0.05) + c * (p.y - 0.05)});
  }
  ScreenScene scene;
  ScreenSceneBuilder b(cam, {}, scene);
  const int32_t clip = b.add_clip(mask, 1.0 / 64);
  ASSERT_GE(clip, 0);
  b.cull_outside(clip, 2);
  const double step = scene.raster.step;  // picture-plane units per sample
  std::vector<Vec3> vertices;
  std::vector<std::vector<int>> polygons;
  // A triangle about the picture-plane point c, `r` samples across, 5 m from the eye.
  auto triangle_at = [&](Vec2 c, double r) {
    for (int k = 0; k < 3; ++k) {
      const double a = 2.0943951023931953 * k;
      const Vec2 p{c.x + r * step * std::cos(a), c.y + r * step * std::sin(a)};
      vertices.push_back(cam.eye + 5.0 * (p.x * cam.right + p.y * cam.up + cam.forward));
    }
    const int n = int(vertices.size());
    polygons.push_back({n - 3, n - 2, n - 1});
  };
  Vec2 centre{0, 0};
  for (Vec2 m : mask) centre = centre + (1.0 / double(mask.size())) * m;
  triangle_at(centre, 1.5);
  for (Vec2 m : mask) triangle_at(centre + 0.6 * (m - centre), 1.5);  // inside, towards each corner
  const size_t inside = polygons.size();
  // Beyond each side of some length, five samples out from its middle: wholly beyond the
  // side grown by the two samples' margin. Those whose centre lies in the mask's box grown
  // by the margin are for the sides to cull, not the box.
  Vec2 lo{HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL};
  for (Vec2 m : mask) lo = {std::min(lo.x, m.x), std::min(lo.y, m.y)}, hi = {std::max(hi.x, m.x), std::max(hi.y, m.y)};
  size_t in_box = 0;
  for (size_t i = 0; i < mask.size(); ++i) {
    const Vec2 p = mask[i], q = mask[(i + 1) % mask.size()], d = q - p;
    const double len = std::hypot(d.x, d.y);
    if (len < 10 * step) continue;
    const Vec2 out{d.y / len, -d.x / len};  // to the right of p -> q: outside, the mask turning counter-clockwise
    const Vec2 c = 0.5 * (p + q) + 5 * step * out;
    triangle_at(c, 1);
    in_box += c.x > lo.x - 2 * step && c.x < hi.x + 2 * step && c.y > lo.y - 2 * step && c.y < hi.y + 2 * step;
  }
  ASSERT_GE(in_box, 2u);
  // The mask's own sides (its notch's among them) would cut away some triangle inside it.
  size_t cut_by_the_notch = 0;
  for (size_t k = 0; k < inside; ++k)
    for (size_t i = 0; i < mask.size(); ++i) {
      const Vec2 p = mask[i], d = mask[(i + 1) % mask.size()] - p;
      bool all_right = true;  // every corner to the right of p -> p + d
      for (int v : polygons[k]) {
        const Vec3 c = cam.camera_from_world(vertices[size_t(v)]);
        all_right &= cross(d, Vec2{c.x / c.z, c.y / c.z} - p) < 0;
      }
      cut_by_the_notch += all_right;
    }
  ASSERT_GT(cut_by_the_notch, 0u);
  const Mesh mesh = mesh_from(vertices, polygons);
  ScreenSceneBuilder::Placement where;
  where.clip = clip;
  PolygonSource source;
  source.kind = PolygonSource::Kind::Object;
  b.add_mesh(mesh, {}, where, source);
  std::set<int> kept;
  for (const PolygonSource& s : scene.sources) kept.insert(s.polygon);
  for (size_t k = 0; k < inside; ++k) EXPECT_TRUE(kept.count(int(k))) << "inside triangle " << k << " was culled";
  for (size_t k = inside; k < polygons.size(); ++k) EXPECT_FALSE(kept.count(int(k))) << "triangle " << k << " beyond a side was kept";
}

// --- implicitly defined lines ---------------------------------------------------------------

namespace {

/// Two large quadrilaterals in front of the camera at (0, -d, 0) looking along +y, on the
/// planes given by a point and a normal, rendered with an item buffer.
struct Pair {
  Camera cam = Camera::look_at({0, -10, 0}, {0, 0, 0}, 50, 320, 240);
  std::vector<Mesh> meshes;
  ScreenScene scene;
  std::vector<int32_t> items;
  Pair(Vec3 n1, Vec3 n2) {
    for (Vec3 n : {n1, n2}) {
      // A big square through the origin on the plane with normal n.
      const Vec3 a = length(cross(n, {0, 0, 1})) > 1e-3 ? cross(n, {0, 0, 1}) : cross(n, {1, 0, 0});
      const Vec3 u = (1 / length(a)) * a, v0 = cross(n, u), v = (1 / length(v0)) * v0;
      meshes.push_back(mesh_from({-20 * u - 20 * v, 20 * u - 20 * v, 20 * u + 20 * v, -20 * u + 20 * v}, {{0, 1, 2, 3}}));
    }
    SceneOptions so;
    so.cull_back_faces = false;
    scene = screen_scene_of_meshes(meshes, {}, cam, so);
    Image picture;
    render_scene(scene, {}, picture, nullptr, &items);
  }
  int32_t at(int x, int y) const { return items[size_t(y) * size_t(cam.width) + size_t(x)]; }
};

/// The picture-plane x where the two planes through the origin with normals n1, n2 are at
/// one depth on row y (centre): n·(x·right + y·up + forward)·Z = n·(o − eye) on both.
double analytic_x(const Pair& p, Vec3 n1, Vec3 n2, int row) {
  const Camera& c = p.cam;
  const Vec2 pp = c.image_from_raster({0, row + 0.5});
  // 1/Z_k = n_k·(x·r + y·u + f) / (n_k·(0 − eye)), equal for k = 1, 2: linear in x.
  auto coef = [&](Vec3 n) {
    const double s = 1 / dot(n, (-1) * c.eye);
    return std::pair<double, double>{dot(n, c.right) * s, (pp.y * dot(n, c.up) + dot(n, c.forward)) * s};
  };
  const auto [a1, b1] = coef(n1);
  const auto [a2, b2] = coef(n2);
  const double x = (b2 - b1) / (a1 - a2);
  return c.raster_from_image({x, pp.y}).x;
}

}  // namespace

TEST(ImplicitLines, TheSplitLiesWithinHalfASampleOfTheAnalyticLine) {
  const Vec3 n1{0.3, -1, 0.2}, n2{-0.4, -1, -0.1};
  const Pair p(n1, n2);
  int rows = 0;
  for (int y = 0; y < p.cam.height; ++y) {
    int switch_at = -1, switches = 0;
    for (int x = 1; x < p.cam.width; ++x)
      if (p.at(x, y) != p.at(x - 1, y)) switch_at = x, ++switches;
    const double want = analytic_x(p, n1, n2, y);
    if (want < 1 || want > p.cam.width - 1) continue;
    ++rows;
    ASSERT_EQ(switches, 1) << "row " << y;
    // Sample switch_at is the first whose centre sees the other plane: the line crosses
    // the row between the centres of switch_at − 1 and switch_at.
    EXPECT_LE(std::fabs(switch_at - want), 0.5 + 1e-9) << "row " << y;
  }
  EXPECT_GT(rows, 100);
}

TEST(ImplicitLines, NearlyParallelPlanesSplitOnceAndMonotonically) {
  // Two planes 1e-7 rad apart meeting in the view: each row switches once, and the switch
  // moves one way down the picture — no speckle.
  const Vec3 n1{0, -1, 0.3}, n2{1e-7, -1, 0.3};
  const Pair p(n1, n2);
  int last = -1, direction = 0, rows = 0;
  for (int y = 0; y < p.cam.height; ++y) {
    int switch_at = -1, switches = 0;
    for (int x = 1; x < p.cam.width; ++x)
      if (p.at(x, y) != p.at(x - 1, y)) switch_at = x, ++switches;
    ASSERT_LE(switches, 1) << "row " << y;
    if (switches == 0) continue;
    ++rows;
    if (last >= 0 && switch_at != last) {
      const int d = switch_at > last ? 1 : -1;
      if (direction == 0) direction = d;
      EXPECT_EQ(d, direction) << "row " << y;
    }
    last = switch_at;
  }
  EXPECT_GT(rows, 0);
}

TEST(ImplicitLines, TheRippleTorusCrossesThem) {
  for (const PaperScene& s : paper_scenes()) {
    if (s.name != "ripple-torus") continue;
    HalftoneOptions o;
    o.cull_back_faces = false;
    RenderStats stats;
    render_meshes({mesh_of(s)}, {s.paint}, s.camera, o, &stats);
    EXPECT_GT(stats.implicit_lines, 1000);
    EXPECT_GT(stats.depth_sorts, stats.implicit_lines);
  }
}

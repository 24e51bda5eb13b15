// Tests of visibility/strips.h: the hull search of one view with its window cut into strips
// searched side by side. (The hull checks, hull_checks.h, also search every view of the
// plans, homes and soups they try in strips, against the ray oracle and the picture.)
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "cells/build_cells.h"
#include "cells/mesh_scene.h"
#include "ray_oracle.h"
#include "render/halftone.h"
#include "render/scene_screen.h"
#include "test_meshes.h"
#include "test_plans.h"
#include "visibility/strips.h"
#include "visibility/viewpoint.h"

using namespace avenues;
using avenues::testing::check_visible_set;
using avenues::testing::plan_path;

namespace {

TraverseParams hull_search() {
  TraverseParams p;
  p.merge_pieces = p.hull_pieces = true;
  return p;
}

/// An avenue of no cell in particular whose mask is a small square about (x, 0).
Avenue avenue_at(double x) {
  Avenue a;
  a.cell = 0;
  a.mask = {{x - 0.01, -0.01}, {x + 0.01, -0.01}, {x + 0.01, 0.01}, {x - 0.01, 0.01}};
  return a;
}

}  // namespace

TEST(Strips, WithoutAViewBeforeTheWindowIsCutEvenly) {
  const Camera cam = Camera::yaw_pitch({0, 0, 1.6}, 0, 0, 90, 640, 360);  // the window is x in [-1, 1]
  const std::vector<double> three = strip_edges(cam, 3);
  ASSERT_EQ(three.size(), 2u);
  EXPECT_NEAR(three[0], -1.0 / 3, 1e-12);
  EXPECT_NEAR(three[1], 1.0 / 3, 1e-12);
  EXPECT_TRUE(strip_edges(cam, 1).empty());
  EXPECT_TRUE(strip_edges(Camera::parallel({0, 0, 1.6}, {1, 0, 1.6}, 10, 640, 360), 2).empty());
  // A view before with too few avenues to say where the work lies: evenly too.
  VisibleSet few;
  for (int k = 0; k < 5; ++k) few.avenues.push_back(avenue_at(0.9));
  EXPECT_NEAR(strip_edges(cam, 2, &few)[0], 0.0, 1e-12);
}

TEST(Strips, TheCutsFollowWhereTheAvenuesOfTheViewBeforeLay) {
  const Camera cam = Camera::yaw_pitch({0, 0, 1.6}, 0, 0, 90, 640, 360);
  VisibleSet last;
  for (int k = 0; k < 90; ++k) last.avenues.push_back(avenue_at(-0.8 + 0.001 * k));  // crowded on the left
  for (int k = 0; k < 10; ++k) last.avenues.push_back(avenue_at(0.5));
  const std::vector<double> two = strip_edges(cam, 2, &last);
  ASSERT_EQ(two.size(), 1u);
  EXPECT_NEAR(two[0], -0.8 + 0.001 * 50, 1e-9);  // half the avenues on each side
  // Searched in two strips, the left's avenues three times as costly as the right's: the
  // cut moves left until each side holds half the cost.
  VisibleSet timed;
  for (int k = 0; k < 100; ++k) timed.avenues.push_back(avenue_at(-0.9 + 0.018 * k));
  timed.strips = {0, 50};
  timed.strip_micros = {300, 100};
  const std::vector<double> weighed = strip_edges(cam, 2, &timed);
  ASSERT_EQ(weighed.size(), 1u);
  EXPECT_NEAR(weighed[0], -0.9 + 0.018 * 33, 1e-9);  // 33 avenues of weight 6 before it: 198 of 400
  // All on one side: each strip still a tenth of its even width.
  VisibleSet edge;
  for (int k = 0; k < 100; ++k) edge.avenues.push_back(avenue_at(-1.5));  // beyond the window: at its edge
  const std::vector<double> cuts = strip_edges(cam, 4, &edge);
  ASSERT_EQ(cuts.size(), 3u);
  EXPECT_NEAR(cuts[0], -1 + 0.05, 1e-12);
  EXPECT_NEAR(cuts[1], -1 + 0.10, 1e-12);
  EXPECT_NEAR(cuts[2], -1 + 0.15, 1e-12);
}

TEST(Strips, OnlyAPerspectiveHullSearchIsCut) {
  const CellComplex c = build_cells(read_plan(plan_path("jones-house.toml")));
  const Camera cam = Camera::look_at({1.0, 0.5, 1.2}, {6, 3, 1.2}, 100, 400, 300);
  const CellId cell = c.locate(cam.eye).cell;
  TraverseParams merged;
  merged.merge_pieces = true;
  const VisibleSet whole = find_visible(c, cam, cell, merged);
  const VisibleSet cut = find_visible_in_strips(c, cam, cell, merged, strip_edges(cam, 2), 2);
  ASSERT_EQ(cut.avenues.size(), whole.avenues.size());
  for (size_t a = 0; a < whole.avenues.size(); ++a) {
    EXPECT_EQ(cut.avenues[a].cell, whole.avenues[a].cell);
    EXPECT_EQ(cut.avenues[a].mask, whole.avenues[a].mask);
  }
  EXPECT_FALSE(cut.conservative);
  // Edges outside the window cut nothing.
  const VisibleSet hull = find_visible(c, cam, cell, hull_search());
  const VisibleSet outside = find_visible_in_strips(c, cam, cell, hull_search(), {-5.0, 7.0}, 2);
  EXPECT_EQ(outside.avenues.size(), hull.avenues.size());
  // Cut in two, the eye's cell is a root of each strip.
  const VisibleSet two = find_visible_in_strips(c, cam, cell, hull_search(), strip_edges(cam, 2), 2);
  int roots = 0;
  for (const Avenue& a : two.avenues) roots += a.parent < 0;
  EXPECT_EQ(roots, 2);
  EXPECT_TRUE(two.conservative);
}

// Over a 12 × 12 grid of open boxes from its corner at the height of their walls' tops, as
// the walk sees the grids: the strips, on one thread or two, join the same avenues in the
// same order; no ray's cell is missing; and the picture is the whole window's, at one
// sample a pixel and at four, wherever the window is cut.
TEST(Strips, AGridOfOpenBoxesSearchedInStripsIsDrawnAsTheWholeWindowIs) {
  const CellComplex c = build_mesh_scene({avenues::testing::open_boxes(12)});
  const Camera cam = Camera::yaw_pitch({-1.0, -0.3, 1.6}, 40, -5, 70, 320, 180);
  const CellId cell = c.locate(cam.eye).cell;
  ASSERT_NE(cell, kNoCell);
  const VisibleSet whole = find_visible(c, cam, cell, hull_search());
  ASSERT_GT(whole.cells.size(), 200u);
  const std::vector<PlacedObject> objects = place_objects(c);
  for (int samples : {1, 4}) {
    HalftoneOptions o;
    o.samples = samples;
    Image reference;
    render_view(c, objects, cam, whole, o, reference);
    for (const std::vector<double>& edges :
         {strip_edges(cam, 2), strip_edges(cam, 2, &whole), strip_edges(cam, 5, &whole), std::vector<double>{-0.5}}) {
      SCOPED_TRACE(std::to_string(samples) + " samples, " + std::to_string(edges.size() + 1) + " strips from " +
                   std::to_string(edges[0]));
      const VisibleSet two = find_visible_in_strips(c, cam, cell, hull_search(), edges, 2);
      const VisibleSet one = find_visible_in_strips(c, cam, cell, hull_search(), edges, 1);
      ASSERT_EQ(one.avenues.size(), two.avenues.size());
      for (size_t a = 0; a < two.avenues.size(); ++a) {
        EXPECT_EQ(one.avenues[a].cell, two.avenues[a].cell);
        EXPECT_EQ(one.avenues[a].parent, two.avenues[a].parent);
        EXPECT_EQ(one.avenues[a].mask, two.avenues[a].mask);
        EXPECT_LT(two.avenues[a].parent, int(a));
      }
      if (samples == 1) {
        EXPECT_EQ(check_visible_set(c, cam, two, 2).missing, 0);
      }
      Image in_strips;
      render_view(c, objects, cam, two, o, in_strips);
      EXPECT_TRUE(in_strips.data == reference.data);
    }
  }
}

// Every bundled plan from its own viewpoint, lit by its own lights where it has them (the
// scene's light terms and their pieces of light joined from each strip's part), with its
// objects: the hull search in strips, its scene built strip by strip on two threads where
// no object is drawn whole across cells, draws the whole window's picture.
TEST(Strips, EveryBundledPlanSearchedInStripsIsDrawnAsTheWholeWindowIs) {
  int built_in_parts = 0, lit_in_parts = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(AVENUES_SOURCE_DIR) / "plans")) {
    if (entry.path().extension() != ".toml") continue;
    SCOPED_TRACE(entry.path().filename().string());
    const CellComplex c = build_cells(read_plan(entry.path().string()));
    const Viewpoint vp = default_viewpoint(c);
    const Camera cam = Camera::look_at(vp.eye, vp.look, vp.fov_deg, 480, 270);
    const CellId cell = c.locate(cam.eye).cell;
    const std::vector<PlacedObject> objects = place_objects(c);
    HalftoneOptions o;
    o.threads = 2;
    const VisibleSet whole = find_visible(c, cam, cell, hull_search());
    Image reference;
    render_view(c, objects, cam, whole, o, reference);
    for (int strips : {2, 3}) {
      const VisibleSet cut = find_visible_in_strips(c, cam, cell, hull_search(), strip_edges(cam, strips), 2);
      ASSERT_EQ(cut.strips.size(), size_t(strips));
      Image picture;
      RenderStats stats;
      render_view(c, objects, cam, cut, o, picture, &stats);
      EXPECT_TRUE(picture.data == reference.data) << strips << " strips";
      SceneOptions so = scene_options(o);
      const ScreenScene scene = screen_scene_of_view(c, objects, cam, cut, so);
      built_in_parts += !scene.parts.empty();
      lit_in_parts += !scene.parts.empty() && stats.light_pieces > 0;
    }
  }
  EXPECT_GE(built_in_parts, 4);  // the plans without objects across cells, in 2 and 3 strips
  EXPECT_GE(lit_in_parts, 2);    // among them one lit by its own lamps, with their shadows
}

// A walk's searches one after another (FrameSearches): the first whole; after one that took
// at least the mark, on both threads in strips cut where its avenues lay, the same cells
// seen (on one thread when no cut falls inside the window); after short ones, whole again.
// A stereo pair's eyes likewise side by side.
TEST(Strips, AWalksSearchesGoSideBySideAfterALongOne) {
  const CellComplex c = build_mesh_scene({avenues::testing::open_boxes(12)});
  const Camera cam = Camera::yaw_pitch({-1.0, -0.3, 1.6}, 40, -5, 70, 320, 180);
  const CellId cell = c.locate(cam.eye).cell;
  FrameSearches searches(2, 0);  // every search is long enough
  const VisibleSet first = searches.find(c, cam, cell, hull_search());
  EXPECT_EQ(searches.threads_used(), 1);
  EXPECT_TRUE(first.strips.empty());
  const VisibleSet second = searches.find(c, cam, cell, hull_search());
  EXPECT_EQ(searches.threads_used(), 2);
  EXPECT_EQ(second.strips.size(), 2u);
  EXPECT_EQ(second.cells, find_visible_in_strips(c, cam, cell, hull_search(), strip_edges(cam, 2, &first), 2).cells);
  // Lines take exact masks: the merged search is never cut.
  TraverseParams merged;
  merged.merge_pieces = true;
  EXPECT_TRUE(searches.find(c, cam, cell, merged).strips.empty());
  EXPECT_EQ(searches.threads_used(), 1);
  VisibleSet left, right;
  searches.find_pair(c, cam, cell, cam, cell, hull_search(), left, right);
  EXPECT_EQ(searches.threads_used(), 2);
  EXPECT_EQ(left.cells, right.cells);
  // Cut where the last search's avenues lay, but none of those cuts inside a narrower
  // window: searched whole, on one thread, and said so.
  (void)searches.find(c, cam, cell, hull_search());
  const Camera narrow = Camera::yaw_pitch({-1.0, -0.3, 1.6}, 40, -5, 0.5, 320, 180);
  EXPECT_TRUE(searches.find(c, narrow, cell, hull_search()).strips.empty());
  EXPECT_EQ(searches.threads_used(), 1);
  // A mark no search reaches: whole, one after another.
  FrameSearches quick(2, 1e12);
  quick.find(c, cam, cell, hull_search());
  EXPECT_TRUE(quick.find(c, cam, cell, hull_search()).strips.empty());
  EXPECT_EQ(quick.threads_used(), 1);
}

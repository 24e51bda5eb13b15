// Tests of the hull search for a half-tone (TraverseParams::samples_per_side): a piece of
// view whose bounds hold no sample's centre is not followed. A polygon covers a sample
// only where the sample's centre lies in its clip region, so the pictures (resolved by
// depth) must be the same, byte for byte, with and without it, at one sample a pixel and
// at four; the cells found are a subset of those found without it; and on a grazing view
// over a grid of open boxes, whose far cells are seen through slivers thinner than a
// sample, fewer. The merged search ignores it.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "cells/build_cells.h"
#include "cells/mesh_scene.h"
#include "render/halftone.h"
#include "render/scene_objects.h"
#include "test_plans.h"
#include "tests/test_meshes.h"
#include "visibility/visible_set.h"

using namespace avenues;

namespace {

struct Counts {
  long avenues_whole = 0, avenues_sampled = 0, between = 0;
};

/// The view's hull-search pictures with and without the pruning, at 1 and 4 samples a
/// pixel: the same bytes, and no cell found that the whole search does not find. The merged
/// search is not pruned.
void expect_same_pictures(const CellComplex& c, const std::vector<PlacedObject>& objects, const Camera& cam,
                          CellId cell, Counts& n) {
  for (bool hull : {true, false})
    for (int samples : {1, 4}) {
      SCOPED_TRACE(std::string(hull ? "hull" : "merged") + " search, " + std::to_string(samples) + " samples");
      TraverseParams whole;
      whole.merge_pieces = true;
      whole.hull_pieces = hull;
      TraverseParams sampled = whole;
      sampled.samples_per_side = samples_per_side(samples);
      const VisibleSet a = find_visible(c, cam, cell, whole), b = find_visible(c, cam, cell, sampled);
      EXPECT_TRUE(std::includes(a.cells.begin(), a.cells.end(), b.cells.begin(), b.cells.end()));
      HalftoneOptions o;
      o.threads = 1;
      o.samples = samples;
      Image pa, pb;
      render_view(c, objects, cam, a, o, pa);
      render_view(c, objects, cam, b, o, pb);
      ASSERT_TRUE(pa.data == pb.data) << "the pictures differ";
      if (!hull) {
        EXPECT_EQ(b.between_samples, 0);
        EXPECT_EQ(a.avenues.size(), b.avenues.size());
        continue;
      }
      n.avenues_whole += long(a.avenues.size());
      n.avenues_sampled += long(b.avenues.size());
      n.between += b.between_samples;
    }
}

}  // namespace

// The walk's grazing view over a grid of open boxes (docs/PERFORMANCE.md): the far boxes
// and the corridors between them are seen from the air above through slivers of their
// openings; at a quarter of the window's size most hold no sample.
TEST(SamplePruning, AGrazingViewOverAGridFollowsFarFewerPiecesAndDrawsTheSame) {
  const CellComplex c = build_mesh_scene({avenues::testing::open_boxes(16)});
  const std::vector<PlacedObject> objects = place_objects(c);
  Counts n;
  for (int width : {320, 640}) {
    SCOPED_TRACE(std::to_string(width) + " px across");
    const Camera cam = Camera::yaw_pitch({-1.0, -0.3, 1.6}, 44, 0, 88.8, width, width * 9 / 16);
    const Location at = c.locate(cam.eye);
    ASSERT_EQ(at.what, Location::What::Cell);
    expect_same_pictures(c, objects, cam, at.cell, n);
  }
  RecordProperty("avenues", std::to_string(n.avenues_whole) + " whole, " + std::to_string(n.avenues_sampled) +
                                " sampled, " + std::to_string(n.between) + " pieces between samples");
  EXPECT_GT(n.between, 0);
  EXPECT_LT(n.avenues_sampled, n.avenues_whole);
}

// Random views of the bundled plans at small sizes, where masks between samples are many,
// and of a Sweet Home house: the same pictures.
TEST(SamplePruning, RandomViewsOfPlansDrawTheSame) {
  Counts n;
  for (const char* name : {"two-storey-house.toml", "curved-walls.toml", "office-corridor.toml"}) {
    SCOPED_TRACE(name);
    const CellComplex c = build_cells(read_plan(avenues::testing::plan_path(name)));
    const std::vector<PlacedObject> objects = place_objects(c);
    std::mt19937 rng(18);
    std::uniform_real_distribution<double> yaw(0, 360), pitch(-40, 40);
    for (int v = 0; v < 6; ++v) {
      CellId cell = kNoCell;
      const Vec3 eye = avenues::testing::random_eye(c, rng, cell);
      const Camera cam = Camera::yaw_pitch(eye, yaw(rng), pitch(rng), 90, 96, 54);
      const Location at = c.locate(cam.eye);
      if (at.what != Location::What::Cell) continue;
      expect_same_pictures(c, objects, cam, at.cell, n);
    }
  }
  RecordProperty("avenues", std::to_string(n.avenues_whole) + " whole, " + std::to_string(n.avenues_sampled) +
                                " sampled, " + std::to_string(n.between) + " pieces between samples");
}

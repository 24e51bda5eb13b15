// Avenues tests — a soup's detail (small polygons of a large soup, closed curved solids)
// drawn in the cells it crosses, against the same meshes cut into space.
#pragma once

#include <gtest/gtest.h>

#include <vector>

#include "cells/cell_complex.h"
#include "picture_checks.h"
#include "render/halftone.h"
#include "render/scene_objects.h"
#include "visibility/visible_set.h"

namespace avenues::testing {

/// From each camera (its eye in free space in both complexes), the picture of `detailed`
/// (its detail drawn, by the hull search) is that of `whole` (the same meshes cut into
/// space, by the merged search), lit by ambient light alone, up to the renderer's edge
/// error: no pixel differs away from an edge, at most 0.5 % on edges. The detail must be
/// in view: the picture without it differs in a tenth of the pixels at least.
inline void expect_detail_looks_as_cut(const CellComplex& whole, const CellComplex& detailed,
                                       const std::vector<Camera>& cameras) {
  const std::vector<PlacedObject> no_objects, detail = place_objects(detailed);
  HalftoneOptions o;
  o.threads = 1;
  o.shading.back = 1;
  TraverseParams merged;
  merged.merge_pieces = true;
  TraverseParams hull = merged;
  hull.hull_pieces = true;
  for (const Camera& cam : cameras) {
    const Location in_whole = whole.locate(cam.eye), in_detailed = detailed.locate(cam.eye);
    ASSERT_EQ(in_whole.what, Location::What::Cell);
    ASSERT_EQ(in_detailed.what, Location::What::Cell);
    Image truth, pic, empty;
    render_view(whole, no_objects, cam, find_visible(whole, cam, in_whole.cell, merged), o, truth);
    const VisibleSet vs = find_visible(detailed, cam, in_detailed.cell, hull);
    render_view(detailed, detail, cam, vs, o, pic);
    render_view(detailed, no_objects, cam, vs, o, empty);
    EXPECT_GT(compare_off_edges(truth, empty).differ, truth.width * truth.height / 10);
    const PictureDifference d = compare_off_edges(truth, pic);
    EXPECT_EQ(d.off_edges, 0) << "the pictures differ in " << d.off_edges << " pixels away from every edge";
    EXPECT_LE(d.differ, d.pixels / 200) << "the pictures differ in " << d.differ << " pixels";
  }
}

}  // namespace avenues::testing

// Avenues tests — checks of the hull search (TraverseParams::hull_pieces) against the merged
// one from the same eye, shared by avenue_pruning_test.cpp (plans, homes, a Doom map) and
// soup_checks.h (the soups): it is conservative (every cell the merged search finds, every
// mask inside a hull mask of its cell, no ray's cell missing), its half-tone resolved by
// depth is the merged search's picture within the renderer's edge error, and line drawings
// refuse it.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "picture_checks.h"
#include "ray_oracle.h"
#include "render/halftone.h"
#include "render/view_lines.h"
#include "visibility/strips.h"
#include "visibility/visible_set.h"

namespace avenues::testing {

/// How far p lies outside the convex counter-clockwise polygon m: the largest distance to
/// the outside of one of its sides' lines (0 or less: inside). Sides shorter than a
/// millionth of the mask's reach are skipped: two corners a rounding apart (of an exact
/// mask in doubles, or where a hull's nearly parallel sides meet) give a side whose
/// direction is their rounding, and the line along it can pass anywhere a little way off
/// (as cone_planes skips such sides in the search). Skipping one only grows the polygon
/// by the sliver between its neighbours' lines.
inline double outside_by(const std::vector<Vec2>& m, Vec2 p) {
  double reach = 0;
  for (Vec2 v : m) reach = std::max({reach, std::fabs(v.x), std::fabs(v.y)});
  double most = 0;
  for (size_t k = 0; k < m.size(); ++k) {
    const Vec2 a = m[k], b = m[(k + 1) % m.size()];
    const double len = std::hypot(b.x - a.x, b.y - a.y);
    if (!(len > 1e-6 * (1 + reach))) continue;
    most = std::max(most, -((b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x)) / len);
  }
  return most;
}

/// What the hull searches of a run found, against the merged ones.
struct HullTally {
  long merged_avenues = 0, hull_avenues = 0, merged_cells = 0, hull_cells = 0;
  int pictures = 0;
  long pixels = 0, pixels_differ = 0;  ///< of the pictures compared
  /// Polygons the hull search's pictures put on the raster with what is hidden dropped
  /// (HalftoneOptions::drop_hidden), and without.
  long polygons_dropping = 0, polygons_all = 0;
  /// The hull search in strips searched side by side (strips.h): its avenues.
  long strips_avenues = 0;
};

/// The hull search from `cam` in kernel k against `merged` (the merged search from the same
/// eye and kernel). With `objects` (double only) the two half-tones are compared too.
inline void expect_hull_holds_merged(const CellComplex& c, const Camera& cam, CellId cell, Kernel k,
                                     const VisibleSet& merged, const std::vector<PlacedObject>* objects,
                                     HullTally& t) {
  SCOPED_TRACE(std::string("hull, ") + to_string(k));
  TraverseParams p;
  p.kernel = k;
  p.merge_pieces = p.hull_pieces = true;
  const VisibleSet hull = find_visible(c, cam, cell, p);
  EXPECT_TRUE(hull.conservative);
  EXPECT_FALSE(merged.conservative);
  t.merged_avenues += long(merged.avenues.size()), t.hull_avenues += long(hull.avenues.size());
  t.merged_cells += long(merged.cells.size()), t.hull_cells += long(hull.cells.size());
  EXPECT_TRUE(std::includes(hull.cells.begin(), hull.cells.end(), merged.cells.begin(), merged.cells.end()))
      << "the hull search lost a cell the merged search sees";
  // Every vertex of every merged mask inside a hull mask of its cell, within a thousandth
  // of a pixel (float: 1/200 of the picture plane's unit, its masks' own error): the two searches clip by
  // the same lines in different orders, and a vertex where nearly parallel lines meet
  // moves with the rounding of each.
  const double tol = k == Kernel::Float ? 5e-3 : 1e-3 * 2 * cam.half_width() / cam.width;
  // The hull masks of each cell, so that a vertex is held against its own cell's only
  // (looked up through every hull avenue, a soup's thousands of avenues took most of a test).
  std::vector<std::vector<const std::vector<Vec2>*>> hull_masks(c.cells.size());
  for (const Avenue& h : hull.avenues) hull_masks[size_t(h.cell)].push_back(&h.mask);
  // How far v lies outside the nearest hull mask of `in` (HUGE_VAL: it has none).
  auto outside_hull = [&](CellId in, Vec2 v) {
    double least = HUGE_VAL;
    for (const std::vector<Vec2>* m : hull_masks[size_t(in)]) least = std::min(least, outside_by(*m, v));
    return least;
  };
  auto held = [&](const Avenue& a) {
    for (Vec2 v : a.mask)
      if (!(outside_hull(a.cell, v) <= tol)) return false;
    return true;
  };
  for (const Avenue& a : merged.avenues) {
    if (held(a)) continue;
    Vec2 worst = a.mask[0];
    for (Vec2 v : a.mask)
      if (outside_hull(a.cell, v) > outside_hull(a.cell, worst)) worst = v;
    // Where along its avenue the merged view first left the hull search's.
    std::string chain;
    for (int up = int(&a - merged.avenues.data()); up >= 0; up = merged.avenues[size_t(up)].parent) {
      const Avenue& x = merged.avenues[size_t(up)];
      chain = " -> cell " + std::to_string(x.cell) + " via portal " + std::to_string(x.portal) +
              (held(x) ? " (held)" : " (NOT held)") + chain;
    }
    ADD_FAILURE() << "cell " << a.cell << " (eye's: " << cell << "): a vertex (" << worst.x << ", " << worst.y
                  << ") of its view lies " << outside_hull(a.cell, worst)
                  << " outside its nearest hull mask; its avenue:" << chain;
    return;
  }
  if (k != Kernel::Double) return;
  const OracleResult r = check_visible_set(c, cam, hull, 2);
  EXPECT_EQ(r.missing, 0);  // conservative: extra avenues are what it may have
  EXPECT_THROW(draw_view(c, prepare_line_scene(c), cam, hull), std::invalid_argument);
  if (!objects) return;
  HalftoneOptions o;
  o.threads = 1;
  Image by_masks, by_depth;
  render_view(c, *objects, cam, merged, o, by_masks);
  render_view(c, *objects, cam, hull, o, by_depth);
  ASSERT_EQ(by_masks.data.size(), by_depth.data.size());
  ++t.pictures;
  // The masked picture cuts each cell's faces at its masks (grown by 1/64 of a sample); the
  // one resolved by depth at the nearest surface's own edges: a sample centred on such an
  // edge may go either way, so a pixel may differ only on an edge, and few do: one in 200
  // of the picture, or one in 50 of its edge pixels where edges fill the picture (the
  // duplex's stair seen through its balusters at 96 × 64: 41 % of the pixels on an edge,
  // 35 differing; at 384 × 256 the count grew with the edges' length, 122, not their area).
  const PictureDifference d = compare_off_edges(by_masks, by_depth);
  t.pixels_differ += d.differ, t.pixels += d.pixels;
  EXPECT_EQ(d.off_edges, 0) << "the half-tones differ in " << d.off_edges << " pixels away from every edge";
  EXPECT_LE(d.differ, std::max(d.pixels / 200, d.edges / 50))
      << "the half-tones differ in " << d.differ << " pixels (" << d.edges << " on an edge)";
  // Dropping what lies behind polygons already drawn changes no byte of the picture.
  RenderStats dropping, all;
  Image every;
  HalftoneOptions reference = o;
  reference.drop_hidden = false;
  render_view(c, *objects, cam, hull, o, by_depth, &dropping);
  render_view(c, *objects, cam, hull, reference, every, &all);
  EXPECT_TRUE(by_depth.data == every.data) << "dropping hidden polygons changed the picture";
  EXPECT_LE(dropping.polygons, all.polygons);
  t.polygons_dropping += dropping.polygons, t.polygons_all += all.polygons;
  // The window in strips searched side by side, cut evenly in two, and in three where the
  // whole window's avenues lie: no ray's cell missing, and the same picture, byte for byte,
  // its scene built strip by strip on two threads where it can be (SceneOptions::threads).
  for (const std::vector<double>& edges : {strip_edges(cam, 2), strip_edges(cam, 3, &hull)}) {
    SCOPED_TRACE("the window in " + std::to_string(edges.size() + 1) + " strips");
    const VisibleSet strips = find_visible_in_strips(c, cam, cell, p, edges, 2);
    EXPECT_TRUE(strips.conservative);
    EXPECT_EQ(check_visible_set(c, cam, strips, 2).missing, 0);
    for (size_t a = 0; a < strips.avenues.size(); ++a) EXPECT_LT(strips.avenues[a].parent, int(a));
    t.strips_avenues += long(strips.avenues.size());
    Image in_strips;
    HalftoneOptions two = o;
    two.threads = 2;
    render_view(c, *objects, cam, strips, two, in_strips);
    EXPECT_TRUE(in_strips.data == by_depth.data)
        << "the picture of the search in strips differs from the whole window's in "
        << compare_off_edges(by_depth, in_strips).differ << " pixels";
  }
}

}  // namespace avenues::testing

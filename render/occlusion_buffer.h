// Avenues — what is already drawn, pixel by pixel: a polygon wholly behind it need not be.
//
// A view resolved by depth alone (a conservative visible set, everything in one group:
// scene_view.cpp; or meshes alone) puts every polygon that might show on the raster, and
// the scan finds the nearest along each sample's ray. Seen through a hull search's avenue
// down a bay of a steel frame, that can be forty thousand detail polygons in a strip sixty
// pixels wide, most of them behind the nearer members. This is a conservative depth of what
// is drawn, built as the polygons are added (near avenues come first), and tested before
// a polygon is lit and put on the raster: Greene's hierarchical Z-buffer and Zhang's
// occlusion maps, at two levels.
//   - A cell per pixel (per_side × per_side samples) holds the largest 1/Z that some
//     polygon already drawn is known to reach or exceed at every sample centre of the
//     cell, 0 where nothing is known.
//   - A tile of 8 × 8 cells holds the least of its cells, so that a large polygon is
//     tested a tile at a time, and a floor that every cell reaches, so that a polygon
//     covering a tile whole is remembered in one value, not 64: a wall across the window
//     costs a few thousand tiles. A tile not touched since the last reset() counts as
//     empty, so a frame clears only what it draws on.
// A polygon whose 1/Z at any sample it could colour is below every cell it could colour is
// nearer nowhere: the scan would never show it.
//
// Exactness, step by step:
//   - A cell is covered by a polygon only where every sample centre of it lies strictly
//     inside the polygon's rounded outline and its clip region (by 1e-6 of a sample, far
//     above the rounding of this arithmetic on the fixed point). The scan colours such a
//     centre with the polygon or something nearer, whatever its fill rule does on edges.
//   - There the polygon's 1/Z (its raster plane, affine) is at least its least over the
//     centres' rectangle (a cell's or a tile's), at one of its corners; stored a little
//     below it (2.5e-7, more than a float's rounding).
//   - A tested polygon's 1/Z at a sample it colours is at most its largest at a corner plus
//     its slope over the 1/128 of a sample its rounded outline may reach past the corners
//     (the caller's bound); the test wants a relative margin of 1e-6 on top.
//   - Planes the scan's arithmetic does not hold to 1e-8 (seen within about 1e-8 of
//     edge-on) are neither occluders nor culled (the caller's check).
#pragma once

#include <cstdint>
#include <vector>

#include "core/geometry.h"
#include "render/raster_map.h"
#include "render/scanline.h"

namespace avenues {

class OcclusionBuffer {
 public:
  static constexpr int kTile = 8;  ///< [cells] along each side of a tile

  /// A width × height raster of `per_side` × `per_side` samples a pixel, nothing drawn;
  /// keeps the storage of the last picture (a walkthrough's frames clear only what they touch).
  void reset(int width, int height, int per_side);
  /// A polygon is drawn: its rounded outline (convex), cut by its clip region's outline
  /// (convex; nullptr: the raster) whose number in this picture is `clip_key` (-1: none
  /// to remember it by), with 1/Z on the raster `depth`.
  void cover(const std::vector<FixedPoint>& outline, const std::vector<FixedPoint>* clip, int32_t clip_key,
             const RasterPlane& depth);

  /// A convex outline's two chains of sides from its highest corner to its lowest [samples].
  struct Chains {
    std::vector<Vec2> side[2];
    std::vector<double> slope[2];  ///< per side: dx/dy of each of its sides (0 where level)
    double top = 0, bottom = 0;
    void build(const std::vector<FixedPoint>& outline);
  };
  /// Whether a polygon whose rounded outline lies within the box [lo, hi] [samples] and
  /// whose 1/Z at any sample centre it holds is at most `inv_z` is nearer than what is
  /// drawn nowhere on the raster (true for a box with no sample centre on the raster).
  bool hides(Vec2 lo, Vec2 hi, double inv_z) const;

  /// Cells covered so far (for tests).
  long covered() const;

 private:
  /// Makes tile t current (its floor and least cleared if it was last touched before this reset).
  void touch(size_t t);
  /// The same, and its cells (cleared if they were last written before this reset).
  void touch_cells(size_t t);
  /// Tile t's least over its cells, found again if cells were written since.
  float least(size_t t) const;
  /// The cells [first, last] of a row whose sample centres, grown by 1e-6, lie inside the
  /// interval (l, r) [samples]; false if none.
  bool inside_run(double l, double r, int& first, int& last) const;
  /// Whether the tile's cells in columns [c0, c1] and rows [r0, r1] (the tile's own
  /// numbering) all hold more than `need`.
  bool cells_above(size_t t, int c0, int c1, int r0, int r1, double need) const;

  int per_side_ = 1, across_ = 0, down_ = 0;  ///< cells along the raster
  int tiles_across_ = 0, tiles_down_ = 0;
  uint32_t generation_ = 0;
  std::vector<float> cells_;          ///< tile by tile, kTile × kTile cells each, row by row within
  mutable std::vector<float> least_;     ///< per tile: the least of its cells (least(), current tiles only)
  mutable std::vector<uint8_t> unsettled_;  ///< per tile: cells written since least_ was found
  std::vector<float> floor_;          ///< per tile: a value every cell of it reaches (a polygon covering it whole)
  std::vector<uint32_t> stamp_;       ///< per tile: the generation it was last touched in
  std::vector<uint32_t> cell_stamp_;  ///< per tile: the generation its cells were last written in
  Chains shape_, region_;            ///< cover(): the outline's sides, and the clip region's
  int32_t region_key_ = -1;          ///< the clip region region_ was made of, in
  uint32_t region_generation_ = 0;   ///< this picture
};

}  // namespace avenues

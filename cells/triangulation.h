// Avenues — pass 2 of build_cells: one exact constrained triangulation of all outlines.
//
// The plan decomposition's CGAL-heavy translation unit sits behind this header
// (triangulate.cpp; mesh scenes have their own, mesh_scene.cpp).
// What comes out is plain arrays (Recast style): vertices rounded once to doubles,
// counter-clockwise triangles with their neighbours, and for each triangle and edge
// what covers it. Why a triangulation and not Boolean operations plus a partition:
// CGAL's Boolean set operations drop walls of no thickness (they have no area), and
// Partition_2 refuses holes; one constrained Delaunay triangulation with exact
// intersections (Epeck + Exact_intersections_tag) takes thick walls, walls of no
// thickness, openings, stairwells and every storey at once, never misses a crossing,
// and its triangles are the common refinement on which bands, merging, stacked
// portals and real lines are all computed by index, with no further geometry.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "cells/outline.h"

namespace avenues::detail {

struct Triangulation {
  std::vector<Vec2> vert;                    ///< [m] rounded from the exact construction
  std::vector<std::array<int32_t, 3>> tri;   ///< counter-clockwise vertex indices
  std::vector<std::array<int32_t, 3>> nbr;   ///< neighbour opposite vertex i; -1 beyond the far box
  // Compressed lists (CSR): regions covering triangle t are region_items[region_start[t] ..
  // region_start[t+1]); sheets lying on half-edge h = 3t+i likewise; holes containing t likewise.
  std::vector<int32_t> region_start, region_items;
  std::vector<int32_t> sheet_start, sheet_items;
  std::vector<int32_t> hole_start, hole_items;
  std::vector<int32_t> label_tri;            ///< triangle holding each queried point, -1 if none

  int size() const { return int(tri.size()); }
  /// Edge i of triangle t runs from vertex (i+1)%3 to (i+2)%3 (opposite vertex i).
  Vec2 edge_from(int t, int i) const { return vert[size_t(tri[size_t(t)][size_t((i + 1) % 3)])]; }
  Vec2 edge_to(int t, int i) const { return vert[size_t(tri[size_t(t)][size_t((i + 2) % 3)])]; }
};

/// Triangulates the outline (far box, region outlines, sheets, holes) and locates `points`.
Triangulation triangulate(const Outline& outline, const std::vector<Vec2>& points);

/// Exact orientation of (a, b, c) on the rounded doubles: +1 left turn, 0 collinear, -1 right.
int orientation(Vec2 a, Vec2 b, Vec2 c);

}  // namespace avenues::detail

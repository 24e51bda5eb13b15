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
#include <memory>
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
  /// Bands whose cuts (see Cut) lie on half-edge h: cut_items[cut_start[h] .. cut_start[h+1]);
  /// empty (no cuts) when the triangulation was never cut.
  std::vector<int32_t> cut_start, cut_items;
  /// Per vertex: made where a cut crossed an edge (a point on both, exactly, rounded once),
  /// so a corner there is straight up to its rounding (corners_of). Empty when never cut.
  std::vector<uint8_t> cut_made;
  std::vector<int32_t> label_tri;            ///< triangle holding each queried point, -1 if none

  int size() const { return int(tri.size()); }
  /// Edge i of triangle t runs from vertex (i+1)%3 to (i+2)%3 (opposite vertex i).
  Vec2 edge_from(int t, int i) const { return vert[size_t(tri[size_t(t)][size_t((i + 1) % 3)])]; }
  Vec2 edge_to(int t, int i) const { return vert[size_t(tri[size_t(t)][size_t((i + 2) % 3)])]; }
};

/// A cut of one band's free space (pass 3b, cells/band_cuts.cpp): a segment between two
/// vertices of the triangulation (indices into Triangulation::vert), across which that
/// band's pieces are not merged.
struct Cut {
  int32_t a = -1, b = -1;
  int32_t band = -1;
};

/// The exact triangulation behind a Triangulation, kept so that it can be cut.
class ExactTriangulation {
 public:
  /// Triangulates the outline (far box, region outlines, sheets, holes) and locates `points`.
  ExactTriangulation(const Outline& outline, const std::vector<Vec2>& points);
  ~ExactTriangulation();
  ExactTriangulation(const ExactTriangulation&) = delete;
  ExactTriangulation& operator=(const ExactTriangulation&) = delete;

  /// The triangulation rounded once to doubles.
  const Triangulation& rounded() const { return rounded_; }

  /// Adds the cuts as constraints. The half-edges `keep` marks (per half-edge of rounded(),
  /// the edges between triangles the caller tells apart) are kept too, split where a cut
  /// crosses them, exactly; elsewhere edges may flip. Returns, per triangle after, the
  /// triangle before that holds its centroid (within the kept edges, every triangle before
  /// it overlaps is alike); rounded() is then the cut triangulation, with its cut_items.
  std::vector<int32_t> cut(const std::vector<Cut>& cuts, const std::vector<uint8_t>& keep);

 private:
  struct Exact;
  std::unique_ptr<Exact> exact_;
  const Outline& outline_;
  std::vector<Vec2> points_;
  Triangulation rounded_;
};

/// A constrained triangulation of segments between given points and nothing else (the
/// free space of one region of one band, cut afresh): vert[i] is points[i]; per half-edge,
/// whether it lies on a segment. `crossed` (and nothing else) where two segments cross or
/// two points are one: that would need points of its own.
struct SegmentTriangulation {
  Triangulation T;
  std::vector<uint8_t> constrained;
  bool crossed = false;
};
SegmentTriangulation triangulate_segments(const std::vector<Vec2>& points,
                                          const std::vector<std::array<int32_t, 2>>& segments);

/// Exact orientation of (a, b, c) on the rounded doubles: +1 left turn, 0 collinear, -1 right.
int orientation(Vec2 a, Vec2 b, Vec2 c);

}  // namespace avenues::detail

// Avenues — a polygon soup's free space as the leaves of a BSP of its own polygons.
//
// Teller 1992 (§3, "Spatial subdivision"): split space by the planes of the scene's
// polygons until every polygon lies on the boundary of a leaf; the leaves are convex
// cells, and the parts of leaf boundaries that no polygon covers are the portals. Every
// polygon is an opaque surface seen from both sides; nothing needs to be closed,
// oriented or free of intersections: coincident and crossing polygons are cut where they
// meet, exactly. Only soup_bsp.cpp sees CGAL (exact planes, vertices as the meeting of
// three planes, so no coordinate grows with the depth of the tree); what leaves it are
// Avenues' own structs, rounded to double once.
#pragma once

#include <array>
#include <cstddef>
#include <stdexcept>
#include <vector>

#include "cells/cell_complex.h"

namespace avenues {

/// One input triangle of the soup.
struct SoupTriangle {
  std::array<Vec3, 3> p;    ///< [m] its corners (either orientation: both sides are opaque)
  MaterialId material = -1; ///< carried onto the opaque pieces it covers
};

/// What the decomposition did, for benchmarks and messages.
struct SoupBspStats {
  size_t triangles = 0;      ///< non-degenerate triangles used
  std::vector<size_t> degenerate;  ///< input triangles with no area (collinear corners), dropped
  size_t nodes = 0;          ///< splitting planes in the tree
  size_t leaves = 0;         ///< leaves of the tree
  size_t cells = 0;          ///< cells made of them (leaves joined where the union stays convex)
  size_t fragments = 0;      ///< pieces of triangles in leaves (triangles cut by splits)
  int depth = 0;             ///< deepest leaf
  size_t snapped = 0;        ///< triangles put on a plane not their own (cells/shared_planes.h)
  double largest_snap = 0;   ///< [m] the farthest a corner moved onto such a plane
  /// Halving planes (a large cell's fragments parted at their median) that missed their
  /// cell, placed by a corner's wide interval, and were replaced by a fragment's plane.
  size_t halvings_missed = 0;
};

/// A soup whose planes cut space into more leaves than the decomposition was given
/// (decompose_soup's leaf_budget): cluttered, it would take minutes and gigabytes.
class SoupTooCluttered : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Decomposes `far_box` (which must hold every triangle strictly inside) into the
/// convex leaves of a BSP of the triangles' planes. Fills out.cells (Cell::prism =
/// false, CellKind::Outside) and out.portals (PortalKind::Open, convex pieces of the
/// leaf boundaries no triangle covers); opaque pieces are the parts covered by a
/// triangle and the far box's faces. Splitting planes: the triangles' own planes, chosen
/// at each node by a cheap cost (splits and balance on a sample of the node's
/// triangles, axis-aligned planes preferred); where a cell holds 1,024 or more triangles
/// and none of their planes divides them (a convex cluster: a sphere), an axis-aligned
/// plane through their median halves it instead. Leaves are then joined across faces that
/// hold nothing wherever the union stays convex, exactly: one cell is then several leaves.
/// Nearly coplanar triangles are cut on a plane they share (cells/shared_planes.h);
/// where a corner so moved is shared with a triangle on another plane, the two no longer
/// meet along their edge but leave a crack as wide as the move: an open piece of a leaf
/// face no wider than twice the largest move and a rounding (1e-9 of the far box's scale,
/// drop_slivers' sliver) stays opaque on both sides, as a piece that rounds to no area does,
/// and no leaves are joined across it.
/// With a leaf_budget, a tree that grows more leaves throws SoupTooCluttered, having added
/// nothing to `out` but the time it took (a "decompose" timing).
SoupBspStats decompose_soup(const std::vector<SoupTriangle>& triangles, const Box3& far_box, CellComplex& out,
                            size_t leaf_budget = 0);

}  // namespace avenues

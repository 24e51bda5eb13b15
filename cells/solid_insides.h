// Avenues — the insides of closed solids in a soup: not free space.
//
// A soup's polygons are opaque from both sides (cells/soup_bsp.h), so the BSP makes free
// cells inside a closed block too. Where a part of the input is a closed,
// consistently and outwards oriented surface (a solid as modelling tools write one: a
// chair's leg, a statue, a wall slab), its inside can never be seen and nobody can stand
// in it: its surface is seen from outside only.
//
// The BSP leaves no cell crossed by an input polygon, and no portal either, so the cells
// joined by portals (a region) lie wholly inside or wholly outside every closed surface:
// one point of each region tells. The test is the generalized winding number (Jacobson et
// al. 2013) about the closed, outward surfaces only: 1 inside one, 0 outside, whatever
// open sheets or inward surfaces (a room modelled from inside) stand around it; a region
// whose number is over ½ is inside a solid.
#pragma once

#include <string>
#include <vector>

#include "cells/cell_complex.h"
#include "cells/closed_surface.h"
#include "plans/mesh.h"

namespace avenues {

/// One closed, consistently oriented surface of positive volume (counter-clockwise seen
/// from outside), a connected component of one mesh with its vertices welded by position.
struct ClosedSolid {
  std::string name;                     ///< "FILE: solid N" (N from 1, in the file's order)
  std::vector<Triangle3> triangles;     ///< counter-clockwise seen from outside
  size_t mesh = 0;                      ///< the mesh it is part of (its index in the meshes)
  std::vector<size_t> source;           ///< per triangle, its index in that mesh's triangles
  Box3 box;                             ///< the bounds of its corners
  double volume = 0;                    ///< [m³] > 0
};

/// The closed solids of the meshes: each mesh's connected components (triangles joined by
/// corners at the same position) in which every edge is used as often in one direction as
/// in the other (closed and consistently oriented; solids welded where they touch along a
/// face or an edge are one component and still closed) and which enclose a positive
/// volume. Components that are open, have a triangle turned the wrong way, or are turned
/// inwards are not solids: their surfaces stay two-sided.
std::vector<ClosedSolid> closed_solids(const std::vector<Mesh>& meshes);

/// Per cell of a soup scene's complex: the index in `solids` of a closed solid it lies
/// inside, or -1 for free space. Decided per region of cells joined by portals, at the
/// middle of the region's largest cell; the region holding the far box's corner is free.
std::vector<int> cells_inside_solids(const CellComplex& complex, const std::vector<ClosedSolid>& solids);

}  // namespace avenues

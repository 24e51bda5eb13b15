// Avenues — a large soup's detail: small polygons drawn in the cells they cross, cutting no space.
//
// A soup's free space is cut by the planes of all its polygons (cells/soup_bsp.h). A model
// of a few hundred thousand small polygons in clutter (a steel structure's members, plates
// and bolts, exported from a BIM tool) makes that grow much faster than its size: each
// member's planes cut its neighbours, the cells multiply into slivers, and the
// decomposition runs out of time and memory before it ends. Quake's qbsp met the same
// growth and answered it with detail brushes: they are drawn, but the tree that vis reads
// is built from the structural brushes alone. Here the split is made by size, not by
// hand: where a soup holds more triangles than a decomposition takes in seconds, or its
// planes cut space into more pieces than that (cells/mesh_scene.h: MeshSceneParams), its
// largest flat surfaces (the slabs, walls and broad plates that hide most) cut space, up
// to a budget of triangles, and every other polygon is detail. A surface is ranked whole,
// not by its polygons: BIM tools and Assimp hand over a wall's face with its openings as
// a fan of triangles, each its own polygon, and ranked one by one its small triangles fell
// below the budget while its large ones cut: the wall cut space with holes punched in it,
// and every plane cut space where the wall's area hardly hid anything more (a precast
// concrete model: 6,194 cells, against 105 when its faces are ranked whole; docs/
// PERFORMANCE.md). Each detail polygon is cut to
// the convex cells it crosses and drawn there as part of one of that cell's detail
// objects (compact clusters of a few hundred triangles, each with its own box), by depth,
// as furniture is (render/scene_view.cpp, render/furniture.h). The search sees through
// detail (its visible set is conservative there: a cell behind a member is still found),
// the picture is exact, and the walker stops at it as at a wall (CellComplex::detail_boxes,
// visibility/walker.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "cells/cell_complex.h"
#include "cells/solid_insides.h"
#include "cells/soup_bsp.h"

namespace avenues {

/// Which triangles of a soup are detail.
struct SoupSplit {
  std::vector<bool> detail;        ///< per soup triangle
  size_t structural = 0;           ///< triangles with area that cut space
  size_t detail_triangles = 0;     ///< triangles with area that are detail
  double smallest_structural = 0;  ///< [m²] the area of the smallest surface that cuts space
  size_t curved = 0;               ///< of detail_triangles, those of curved closed solids
};

/// Whether a closed solid is curved: its triangles lie in at least `directions` planes of
/// different directions, and as many directions as planes, nearly (at least ¾): a smooth
/// surface's facets (a duck, a column, a vase), not a building's walls and slabs, whose
/// many planes face a few ways. Free space around it would need a cell per facet
/// (cells/closed_surface.h); it is drawn as detail instead.
bool is_curved(const ClosedSolid& solid, size_t directions);

/// With at most `above` triangles of non-zero area, none is detail. With more, the
/// surfaces (`surface`: one number per triangle, shared by the triangles of one surface,
/// flat_surfaces' or the input polygons) of at least `least_area` [m²] are taken largest
/// area first, ties by number, while their triangles with area number at most `budget`
/// (passing over a surface of more triangles than the whole budget, which never could);
/// the triangles of every other surface are detail. (A surface smaller than `least_area`
/// hides too little to be worth the cells its plane makes: a smooth surface's facets, a
/// bolt. A soup of such surfaces alone cuts no space at all; a sculpture subdivided into a
/// quarter of a million facets cuts it only where facets lie flat together: Assimp's
/// sample_subdiv.ac, by 48 triangles into 3 cells, the rest detail.)
/// Triangles marked in `curved` (the curved closed solids', when not empty) are detail
/// whatever the rest, and are not counted against `above` or `budget`.
SoupSplit split_detail(const std::vector<SoupTriangle>& soup, const std::vector<int64_t>& surface, size_t above,
                       size_t budget, double least_area = 0, const std::vector<bool>& curved = {});

/// Per soup triangle, the flat surface it is part of, numbered by its first triangle: the
/// triangles of one input polygon (`polygon`), and triangles on one plane of
/// shared_planes (cells/shared_planes.h: coplanar, or nearly so, as the decomposition cuts
/// them) that share an edge (its two corners at the same positions), are one surface.
std::vector<int64_t> flat_surfaces(const std::vector<SoupTriangle>& soup, const std::vector<int64_t>& polygon);

/// Cuts each detail triangle to every cell of `out` it crosses (in double: the pieces are
/// drawn, not part of the complex's exact geometry) and appends, for each cell that holds
/// pieces, one Object per compact cluster of them (at most a few hundred triangles, an
/// input polygon's pieces in one cluster): its model the pieces in world coordinates,
/// welded by position, one polygon per input polygon (`polygon`) so that a polygon's own
/// diagonals are no edges; Object::cell that cell; named "detail in cell N" (or "detail in
/// cell N, part K" where the cell has several), its model's path "`source`: " and that
/// name. Each model carries the materials of out.materials its triangles use.
/// Uses out's spatial index (CellComplex::index), and lists the detail objects in its
/// CellComplex::detail_boxes (index_detail). Returns the area [m²] the pieces cover.
double add_detail_objects(CellComplex& out, const std::vector<SoupTriangle>& detail,
                          const std::vector<int64_t>& polygon, const std::string& source);

}  // namespace avenues

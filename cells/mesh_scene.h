// Avenues — meshes as whole scenes: the free space around a set of polygons as convex cells.
//
// Jones 1971 leaves the general case open: "the scene ... may ... be a set of unconnected
// objects". Plans become prism cells (cells/build_cells.h); a scene given only as meshes
// (the papers' test scenes, Crow's objects, any OBJ a user has) has no storeys, walls or
// rooms to extrude, so its free space is cut up in 3D instead, into cells with
// Cell::prism == false. By default (MeshSceneMethod::Bsp) the triangles are taken as a
// soup, every one opaque from both sides, and the far box is cut by a BSP of their own
// planes (cells/soup_bsp.h, after Teller 1992); the former path (MeshSceneMethod::Nef)
// takes each connected component as a closed solid, the far box minus their union as
// exact CGAL Nef polyhedra, decomposed by CGAL::convex_decomposition_3. Either way every
// face between two cells is a portal, and coordinates are rounded to double once, at the end.
#pragma once

#include <string>
#include <vector>

#include "cells/cell_complex.h"
#include "plans/mesh.h"

namespace avenues {

/// How a mesh scene's free space is cut into cells.
enum class MeshSceneMethod : uint8_t {
  /// A BSP of the polygons themselves (cells/soup_bsp.h): every polygon an opaque surface
  /// seen from both sides unless it belongs to a closed, outward-oriented solid (seen from
  /// outside only: its inside is not free space, cells/solid_insides.h), nothing closed or
  /// repaired; free space is all the rest of the far box.
  Bsp,
  /// The far box minus the meshes as closed solids (CGAL Nef polyhedra), open parts
  /// repaired into hulls and plates: the former path, kept for comparison.
  Nef,
};

struct MeshSceneParams {
  MeshSceneMethod method = MeshSceneMethod::Bsp;
  double margin = 2.0;  ///< [m] > 0: the far box reaches this far beyond the meshes' bounds
  /// [m] > 0, Nef only: a component that is not closed and lies flat (all its points
  /// within this distance of one plane) becomes a plate this thick, centred on that plane.
  double sheet_thickness = 0.01;
  /// [m] the far box encloses this box too (with the margin): lines with no surfaces,
  /// e.g. Crow's wire objects. Empty by default.
  Box3 include;
  /// Bsp only: a soup with more triangles of non-zero area than `detail_above` is split
  /// (cells/soup_detail.h): its largest flat surfaces, up to `structural_triangles` triangles,
  /// cut space, and every other polygon is detail, drawn in the cells it crosses.
  size_t detail_above = 50'000;
  size_t structural_triangles = 16'000;
  /// Bsp only, where a soup is split: a surface cuts space only if its area is at least
  /// this share of the largest face of the meshes' bounding box, and never needs more than
  /// `structural_area_cap` [m²] (a wall's face cuts; a smooth surface's facets do not).
  double structural_share = 1e-4;
  double structural_area_cap = 0.1;
  /// Bsp only: a soup whose planes cut space into more leaves than this (cluttered: it
  /// would take minutes and gigabytes) is split too, its largest surfaces a quarter as
  /// many triangles at each try (0: no limit).
  size_t leaf_budget = 60'000;
  /// Bsp only: a closed, outward-oriented solid whose facets face at least this many ways,
  /// one plane a way nearly (soup_detail.h: is_curved), is detail: drawn in the cells that
  /// run through it, kept as a CellComplex::detail_solids entry that the walker stays out
  /// of (0: every closed solid cuts space).
  size_t curved_directions = 32;
};

/// The free space of meshes as convex cells (Cell::prism = false, CellKind::Outside), by
/// params.method. Bsp: every triangle is opaque from both sides (CellComplex::warnings
/// counts those with no area, dropped), except that the inside of a closed, outward-oriented
/// component is solid (CellComplex::solids names it for locate); faces of the far box are
/// opaque; portals
/// (PortalKind::Open) are the rest of the cells' boundaries. Real lines: the edges between
/// polygons that are not coplanar, and the open edges of surfaces (LineKind::Sheet).
/// A soup with more than params.detail_above triangles with area, or whose planes cut space
/// into more than params.leaf_budget leaves: only its largest flat surfaces cut space
/// (cells/soup_detail.h); the others are detail, one Object per cell they cross
/// (Object::cell), and a warning says how many of each. A closed curved solid
/// (params.curved_directions) is detail in any soup: no cell ends at it, and it is kept
/// whole in CellComplex::detail_solids (a warning names them).
///
/// Nef: free space around solids, the far box minus the union of the meshes as CGAL Nef
/// polyhedra, decomposed by CGAL::convex_decomposition_3 into convex cells (Cell::prism =
/// false, CellKind::Outside). Faces of the solids and of the far box are opaque, every
/// other face is a portal (PortalKind::Open). Each connected component of each mesh is a
/// solid. The solids' feature edges (between polygons that are not coplanar) are the real
/// lines, assigned to the cells they bound.
///
/// What is not a closed solid is repaired and said so in CellComplex::warnings, one line
/// per component: a component with boundary edges (or self-intersecting, or not a
/// manifold) is closed by its convex hull; one that lies flat becomes a plate
/// `sheet_thickness` thick (both its sides opaque); a component inside out is turned.
/// Throws std::invalid_argument for non-positive params.
CellComplex build_mesh_scene(const std::vector<Mesh>& solids, const MeshSceneParams& params = {});

/// Reads one mesh file as a whole scene: each connected component is a solid. Throws
/// std::runtime_error naming the file when unreadable.
CellComplex read_mesh_scene(const std::string& path, const MeshSceneParams& params = {});

/// Adds `lines` to the complex and gives each cell a CellLine for every stretch of a line
/// that lies in the cell (on its boundary, or through it, for lines with no surfaces).
/// Stretches outside every cell (inside solids) belong to no cell. Candidate cells come
/// from the complex's spatial index, built here (CellComplex::index) if it is not yet.
void add_real_lines(CellComplex& complex, const std::vector<RealLine>& lines);

/// Drops cells that rounding to double leaves without a shape (thinner than 1e-9 of the
/// far box's scale across some face, or with no outline from above). Where such a sliver
/// lies between free cells, its neighbours are joined across it by portals; the other
/// portals into it become opaque pieces of their neighbours' faces, in the material seen
/// through the sliver. One warning counts them.
void drop_slivers(CellComplex& complex);

/// Drops the cells marked in `drop` (one flag per cell), renumbering the rest; a portal
/// into a dropped cell becomes an opaque piece of its kept neighbour's face.
void remove_cells(CellComplex& complex, const std::vector<bool>& drop);

/// The connected components of a mesh (triangles joined by shared vertices), each a mesh
/// of its own with the vertices it uses; polygon_of is kept (renumbered from 0).
std::vector<Mesh> mesh_components(const Mesh& mesh);

}  // namespace avenues

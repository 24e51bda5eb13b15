// Avenues — meshes as whole scenes: the free space around a set of solids as convex cells.
//
// Jones 1971 leaves the general case open: "the scene ... may ... be a set of unconnected
// objects". Plans become prism cells (cells/build_cells.h); a scene given only as meshes
// (the papers' test scenes, Crow's objects) has no storeys, walls or rooms to extrude, so
// its free space is cut up in 3D instead: the far box minus the union of the solids, as
// exact CGAL Nef polyhedra, decomposed by CGAL::convex_decomposition_3 into convex
// polyhedra. Those become cells with Cell::prism == false; every face between two of
// them is a portal, every face on a solid or on the far box is opaque. Only
// mesh_scene.cpp sees CGAL; coordinates are rounded to double once, at the end.
#pragma once

#include <string>
#include <vector>

#include "cells/cell_complex.h"
#include "plans/mesh.h"

namespace avenues {

struct MeshSceneParams {
  double margin = 2.0;  ///< [m] > 0: the far box reaches this far beyond the meshes' bounds
  /// [m] > 0: a component that is not closed and lies flat (all its points within this
  /// distance of one plane) becomes a plate this thick, centred on that plane.
  double sheet_thickness = 0.01;
  /// [m] the far box encloses this box too (with the margin): lines with no surfaces,
  /// e.g. Crow's wire objects. Empty by default.
  Box3 include;
};

/// Free space around solids: the far box minus the union of the meshes as CGAL Nef
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
/// Stretches outside every cell (inside solids) belong to no cell.
void add_real_lines(CellComplex& complex, const std::vector<RealLine>& lines);

/// The connected components of a mesh (triangles joined by shared vertices), each a mesh
/// of its own with the vertices it uses; polygon_of is kept (renumbered from 0).
std::vector<Mesh> mesh_components(const Mesh& mesh);

}  // namespace avenues

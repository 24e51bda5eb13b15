// Avenues — one polygon of a mesh cut into triangles, whatever its shape.
//
// A mesh file's faces are polygons, and nothing in OBJ, OFF or PLY says they are convex:
// Blender's and SketchUp's n-gons, an IFC wall's face around its window exported by
// Assimp, a gable end, are not. A fan from one corner covers the notch of such a polygon
// and doubles part of it, so a picture shows a surface the model does not have. A convex
// polygon keeps its fan (mesh_of_polygons); any other is triangulated here with CGAL's
// constrained Delaunay triangulation in its own plane, each triangle kept where the
// polygon winds round it (nonzero winding: a bridged hole stays open, both lobes of a
// bow tie stay), so that the triangles cover exactly the polygon.
#pragma once

#include <array>
#include <vector>

#include "core/geometry.h"

namespace avenues {

/// True when polygon `p` (indices into `v`) turns one way only and once round, about its
/// own normal (Newell's): a fan from any corner covers it exactly. Collinear corners are
/// allowed.
bool polygon_is_convex(const std::vector<Vec3>& v, const std::vector<int>& p);

/// The triangles covering polygon `p` (indices into `v`), counter-clockwise about its
/// normal (Newell's, or for a bow tie whose lobes cancel in it, its largest lobe's), as
/// indices into `v`; where two of its edges cross, the crossing becomes
/// a vertex, appended to `v`. Empty when the polygon has no area.
std::vector<std::array<int, 3>> triangulate_polygon(std::vector<Vec3>& v, const std::vector<int>& p);

}  // namespace avenues
